"""What a lab cites and reports: CITATION.cff valid by the Citation File Format's own
validator, one version everywhere, and ``instructmove --version``."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
import yaml

import instructmove_ms
from instructmove_ms.cli import main
from instructmove_ms.heldout import SET_VERSION, benchmark_name

ROOT = Path(__file__).parents[1]
#: scripts/cff_env.sh builds it (scripts/test.sh runs that first).
CFFCONVERT = ROOT / ".cache" / "cff-env" / "bin" / "cffconvert"


def _validate(path: Path) -> subprocess.CompletedProcess:
    assert CFFCONVERT.exists(), "run scripts/cff_env.sh first (scripts/test.sh does)"
    return subprocess.run(
        [str(CFFCONVERT), "--validate", "-i", str(path)], capture_output=True, text=True
    )


def test_the_citation_file_is_valid_and_names_this_version(tmp_path):
    checked = _validate(ROOT / "CITATION.cff")
    assert checked.returncode == 0, checked.stdout + checked.stderr
    citation = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert citation["version"] == instructmove_ms.__version__
    assert citation["preferred-citation"]["title"].startswith("InstructMove")
    # the validator does refuse a broken file: the same citation without its authors
    del citation["authors"]
    broken = tmp_path / "CITATION.cff"
    broken.write_text(yaml.safe_dump(citation))
    assert _validate(broken).returncode != 0


def test_one_package_version_everywhere():
    project = (ROOT / "pyproject.toml").read_text()
    assert f'version = "{instructmove_ms.__version__}"' in project
    changelog = (ROOT / "CHANGELOG.md").read_text()
    assert "## [Unreleased]" in changelog
    assert f"package {instructmove_ms.__version__}" in changelog


def test_version_names_the_package_and_the_benchmark(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0
    line = capsys.readouterr().out.strip()
    assert line.startswith(f"instructmove-ms {instructmove_ms.__version__};")
    assert line.endswith(f"benchmark: {benchmark_name()}")
    assert f"held-out sets v{SET_VERSION}" in benchmark_name()
