"""Demo synthesis: planned PickCategory demos, recorded, replayed by ManiSkill and resumed."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys

import h5py
import pytest

from instructmove_ms.cli import main
from instructmove_ms.demos.generate import generate

TASK, ROBOT = "PickCategory-InstructMove", "franka"
STEM = f"{TASK}_{ROBOT}"


@pytest.fixture(scope="module")
def demos(tmp_path_factory):
    out = tmp_path_factory.mktemp("demos")
    report = generate(TASK, ROBOT, 2, out)
    return out, report


def _episodes(out) -> list[dict]:
    return json.loads((out / f"{STEM}.json").read_text())["episodes"]


def test_generate_records_successful_demos(demos):
    out, report = demos
    assert report.kept == 2 and report.tried >= 2
    episodes = _episodes(out)
    assert len(episodes) == 2 and all(e["success"] for e in episodes)
    with h5py.File(out / f"{STEM}.h5") as f:
        assert all(bool(f[f"traj_{k}/success"][-1]) for k in range(2))
    sidecar = json.loads((out / f"{STEM}.episodes.json").read_text())
    assert [s["seed"] for s in sidecar] == [e["reset_kwargs"]["seed"] for e in episodes]
    for entry, episode in zip(sidecar, episodes, strict=True):
        assert entry["spec"]["family"] == "pick_category"
        assert (
            entry["stages"]["success"][-1]
            and len(entry["stages"]["lift"]) == episode["elapsed_steps"]
        )


def test_replay_reproduces_success(demos):
    out, _ = demos
    result = subprocess.run(
        [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
        + ["--traj-path", f"{STEM}.h5", "-o", "state", "--save-traj", "-b", "physx_cpu"],
        cwd=out,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    assert "Replayed 2 episodes, 2/2=100.00% demos saved" in result.stdout + result.stderr


def test_resume_extends_without_duplicates(demos, tmp_path, capsys):
    out, _ = demos
    shutil.copytree(out / "shards", tmp_path / "shards")  # the first run's finished work
    shutil.copy(out / f"{STEM}.ledger.json", tmp_path)
    first = [e["reset_kwargs"]["seed"] for e in _episodes(out)]
    argv = ["demos", "generate", "--task", TASK, "--robot", ROBOT, "-n", "3"]
    assert main([*argv, "--out", str(tmp_path)]) == 0
    assert "valid-synthesis rate" in capsys.readouterr().out
    episodes = _episodes(tmp_path)
    seeds = [e["reset_kwargs"]["seed"] for e in episodes]
    assert len(episodes) == 3 and seeds[:2] == first and len(set(seeds)) == 3
    with h5py.File(out / f"{STEM}.h5") as a, h5py.File(tmp_path / f"{STEM}.h5") as b:
        for k in range(2):
            assert (a[f"traj_{k}/actions"][:] == b[f"traj_{k}/actions"][:]).all()
