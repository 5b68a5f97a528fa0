"""The installed package (``pip install .``) ships every subpackage of the source tree, and
the exact versions of constraints.txt agree with pyproject.toml's bounds."""

from __future__ import annotations

import configparser
import re
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[1]


def _declared() -> tuple[set[str], dict[str, str]]:
    cfg = configparser.ConfigParser()
    cfg.read(ROOT / "setup.cfg")
    packages = set(cfg["options"]["packages"].split())
    mapping = dict(
        (k.strip(), v.strip())
        for k, v in (line.split("=") for line in cfg["options"]["package_dir"].split("\n") if line)
    )
    return packages, mapping


def test_every_source_package_is_declared():
    packages, mapping = _declared()
    found = set()
    for name, folder in mapping.items():
        for init in (ROOT / folder).rglob("__init__.py"):
            rel = init.parent.relative_to(ROOT / folder)
            found.add(".".join([name, *rel.parts]))
    assert found <= packages, f"setup.cfg [options] packages misses {sorted(found - packages)}"


def _pins() -> dict[str, str]:
    lines = (ROOT / "constraints.txt").read_text().splitlines()
    return dict(line.split("==") for line in lines if line and not line.startswith("#"))


def test_constraints_meet_the_declared_bounds():
    """constraints.txt (written by scripts/lock.sh) pins every dependency of the package and
    its dev extra inside pyproject.toml's bounds, sorted, with no local version label (pip
    matches torch==2.13.0 to the 2.13.0+cpu build)."""
    tomllib = pytest.importorskip("tomllib")
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    pins = _pins()
    assert list(pins) == sorted(pins) and all(n == canonicalize_name(n) for n in pins)
    assert not [v for v in pins.values() if "+" in v]
    for line in [*project["dependencies"], *project["optional-dependencies"]["dev"]]:
        req = Requirement(line)
        version = pins.get(canonicalize_name(req.name))
        assert version, f"constraints.txt pins no {req.name}"
        assert req.specifier.contains(version, prereleases=True), f"{version} is outside {req}"


def test_every_upper_bound_says_why():
    """A cap on a dependency carries its reason: a comment on its line or just above it."""
    lines = (ROOT / "pyproject.toml").read_text().splitlines()
    capped = [k for k, line in enumerate(lines) if re.match(r'\s+"[A-Za-z][^"]*<[^"]*",', line)]
    assert capped
    silent = [
        lines[k].strip()
        for k in capped
        if "#" not in lines[k] and not lines[k - 1].strip().startswith("#")
    ]
    assert not silent, f"upper bounds without a reason: {silent}"
