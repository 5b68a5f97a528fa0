"""Layering: the package's modules import one way (no module imports, even lazily or for
type checking only, one that imports it back), and the core modules that describe and score
an episode import neither the task families nor a simulator, directly or through the package
modules they import."""

from __future__ import annotations

import ast
import configparser
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
#: Where the package's subpackages live in a checkout (setup.cfg's package_dir), the
#: folders shipped inside it first.
FOLDERS = {
    "instructmove_ms.assets": ROOT / "assets",
    "instructmove_ms.agents": ROOT / "agents",
    "instructmove_ms.tasks": ROOT / "tasks",
    "instructmove_ms": ROOT / "instructmove_ms",
}


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
    """Every module ``module`` (at ``path``) imports, anywhere in it (at the top, in a
    function, under ``if TYPE_CHECKING``), relative ones resolved; ``from P import name``
    imports the module ``P.name`` where there is one, else ``P``."""
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
            modules = {f"{base}.{a.name}" for a in node.names if source_of(f"{base}.{a.name}")}
            found.update(modules or {base})
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


def package_modules() -> list[str]:
    """Every module of the package in a checkout (a package by its name)."""
    found = set()
    for prefix, folder in FOLDERS.items():
        for path in folder.rglob("*.py"):
            parts = path.relative_to(folder).with_suffix("").parts
            name = ".".join((prefix, *parts[: -1 if parts[-1] == "__init__" else None]))
            if source_of(name) == path:  # a folder shipped as its own package is its own
                found.add(name)
    return sorted(found)


def import_graph() -> dict[str, set[str]]:
    """Package module -> the package modules it imports (a submodule of a module that
    is not one counts as the module: ``P.name`` for ``from P import name``)."""
    graph = {}
    for module in package_modules():
        targets = set()
        for name in imports(module, source_of(module)):
            while name and source_of(name) is None:
                name = name.rpartition(".")[0]
            if name and name != module:
                targets.add(name)
        graph[module] = targets
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of ``graph`` of more than one node (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = [stack.pop()]
            while component[-1] != node:
                component.append(stack.pop())
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_the_import_graph_has_no_circle():
    graph = import_graph()
    setup = configparser.ConfigParser()
    setup.read(ROOT / "setup.cfg")
    assert set(setup["options"]["packages"].split()) <= set(graph)  # every layer walked
    assert "instructmove_ms.planning.robot" in graph["instructmove_ms.planning.kinematics"]
    assert circles(graph) == []


def test_the_circle_check_sees_every_kind_of_import(tmp_path, monkeypatch):
    """Type-only and function-level imports count; a circle through three modules is found."""
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "a.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .b import B\n"
    )
    (tmp_path / "b.py").write_text("def f():\n    from . import c\n")
    (tmp_path / "c.py").write_text("import json\nfrom fake.a import thing\n")
    monkeypatch.setitem(globals(), "FOLDERS", {"fake": tmp_path})
    graph = import_graph()
    assert graph == {
        "fake": set(),
        "fake.a": {"fake.b"},
        "fake.b": {"fake.c"},
        "fake.c": {"fake.a"},
    }
    assert circles(graph) == [["fake.a", "fake.b", "fake.c"]]
    assert circles({"a": {"b"}, "b": {"c"}}) == []
