"""Layering: the core modules that describe and score an episode import neither the task
families nor a simulator, directly or through the package modules they import."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: The modules that describe and score an episode (``instructmove_ms.<name>``).
CORE = (
    "episode",
    "family",
    "splits",
    "sampler",
    "layout",
    "language",
    "relations",
    "composer",
    "verify",
    "metrics",
    "validation",
    "files",
)
FORBIDDEN = ("instructmove_ms.tasks", "instructmove_ms.agents", "mani_skill", "sapien", "torch")
#: Where the package's subpackages live in a checkout.
FOLDERS = {"instructmove_ms.assets": ROOT / "assets", "instructmove_ms": ROOT / "instructmove_ms"}


def source_of(module: str) -> Path | None:
    """The file of package module ``module`` (None for modules outside the package)."""
    for prefix, folder in FOLDERS.items():
        if module == prefix or module.startswith(prefix + "."):
            rest = module[len(prefix) :].lstrip(".").split(".") if module != prefix else []
            base = folder.joinpath(*rest)
            for path in (base.with_suffix(".py"), base / "__init__.py"):
                if path.is_file():
                    return path
    return None


def imports(module: str, path: Path) -> set[str]:
    """Every module ``module`` (at ``path``) imports, anywhere in it, relative ones resolved."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                parent = ".".join(parts[: len(parts) - node.level + 1])
                base = f"{parent}.{base}" if base else parent
            found.add(base)
            found.update(
                f"{base}.{alias.name}" for alias in node.names if source_of(f"{base}.{alias.name}")
            )
    return found


def closure(module: str) -> dict[str, str]:
    """Every module reached from ``module`` through package modules: name -> importer."""
    seen: dict[str, str] = {}
    todo = [module]
    while todo:
        name = todo.pop()
        path = source_of(name)
        if path is None:
            continue
        for imported in imports(name, path):
            if imported not in seen:
                seen[imported] = name
                todo.append(imported)
    return seen


@pytest.mark.parametrize("name", CORE)
def test_core_module_imports_no_tasks_and_no_simulator(name):
    module = f"instructmove_ms.{name}"
    assert source_of(module) is not None, f"no core module {module}"
    reached = closure(module)
    bad = {
        m: importer
        for m, importer in reached.items()
        if any(m == f or m.startswith(f + ".") for f in FORBIDDEN)
    }
    assert not bad, f"{module} reaches {bad} (module: the package module that imports it)"


def test_the_check_sees_a_forbidden_import(tmp_path, monkeypatch):
    """The walk follows package imports: a module importing the envs through another fails."""
    (tmp_path / "a.py").write_text("from .b import thing\n")
    (tmp_path / "b.py").write_text("import json\nfrom instructmove_ms.tasks import TASKS\n")
    monkeypatch.setitem(FOLDERS, "fake", tmp_path)
    assert "instructmove_ms.tasks" in closure("fake.a")
