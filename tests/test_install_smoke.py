"""The wheel built from this checkout installs in a clean virtual environment, with the
versions pip picks today, and works from outside the source tree: scripts/smoke_install.sh
(about a minute and a half on 2 cores, most of it pip; it needs the package index)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_wheel_installs_and_runs_outside_the_checkout(tmp_path):
    venv = tmp_path / "venv"
    result = subprocess.run(
        ["bash", str(ROOT / "scripts" / "smoke_install.sh"), str(venv)],
        env=dict(os.environ, PYTHON=sys.executable),
        capture_output=True,
        text=True,
        timeout=1200,
    )
    log = result.stdout + result.stderr
    assert result.returncode == 0, f"smoke_install.sh failed:\n{log[-8000:]}"
    assert "[smoke] FAILED" not in log
    assert "passed in" in result.stdout.splitlines()[-1]
    shutil.rmtree(venv)  # 2.5 GB, most of it torch; kept only when the test fails
