"""bench/gpu_check.py, dry-run on the CPU backend (so that the GPU check a user runs cannot
rot), and its one-line stop where GPU physics cannot start."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

from instructmove_ms.tasks import TASKS

SCRIPT = Path(__file__).resolve().parent.parent / "bench" / "gpu_check.py"
ROW = re.compile(r"^\| (\S+) \| (\w+) \| (state|rgb) \| 1 \| ([0-9.]+) \| ([0-9.]+) \|$", re.M)


def _run(*args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, str(SCRIPT), *args],
        capture_output=True,
        text=True,
        env={**os.environ, **(env or {})},
        timeout=900,
    )


def test_the_dry_run_steps_every_family_and_robot_replays_a_demo_and_scores_the_oracle():
    run = _run("--dry-run")
    assert run.returncode == 0, run.stderr[-3000:]
    rows = ROW.findall(run.stdout)
    expected = {
        (t, r, o) for t, s in TASKS.items() for r in s.supported_robots for o in ("state", "rgb")
    }
    assert {(t, r, o) for t, r, o, _, _ in rows} == expected and len(rows) == len(expected)
    assert all(float(reset) > 0 and float(rate) > 0 for *_, reset, rate in rows)
    assert "CPU-recorded demo replayed on physx_cpu: 1/1 succeeded" in run.stdout
    assert "oracle, 1 episodes at once on physx_cpu: S 1.00, success 1.00" in run.stdout


def test_without_gpu_physics_it_stops_in_one_line(tmp_path):
    run = _run("--num-envs", "4", env={"HOME": str(tmp_path)})
    assert run.returncode == 1 and not run.stdout
    (line,) = [x for x in run.stderr.splitlines() if x.startswith("gpu_check:")]
    assert "GPU physics needs SAPIEN's PhysX GPU library libPhysXGpu_64.so" in line
    assert str(tmp_path / ".sapien" / "physx") in line
