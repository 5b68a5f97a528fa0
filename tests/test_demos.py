"""Demo synthesis: planned PickCategory demos recorded by parallel workers, replayed by
ManiSkill, interrupted and resumed."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys

import h5py
import pytest

from instructmove_ms.cli import main
from instructmove_ms.demos import generate as generator
from instructmove_ms.demos.generate import SEED_BLOCK, generate
from instructmove_ms.files import LOCK

TASK, ROBOT = "PickCategory-InstructMove", "franka"
STEM = f"{TASK}_{ROBOT}"


@pytest.fixture(scope="module")
def demos(tmp_path_factory):
    out = tmp_path_factory.mktemp("demos")
    report = generate(TASK, ROBOT, 2, out, workers=2, shard_size=1)  # two spawned workers
    return out, report


def _episodes(out) -> list[dict]:
    return json.loads((out / f"{STEM}.json").read_text())["episodes"]


def test_generate_records_successful_demos(demos):
    out, report = demos
    assert report.kept == 2 and report.tried >= 2
    episodes = _episodes(out)
    assert len(episodes) == 2 and all(e["success"] for e in episodes)
    seeds = [e["reset_kwargs"]["seed"] for e in episodes]
    assert seeds[0] < SEED_BLOCK <= seeds[1] < 2 * SEED_BLOCK  # shard k owns its seed block
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


def _replay(out) -> str:
    """ManiSkill's plain replay of the merged demos to state observations; its output."""
    result = subprocess.run(
        [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
        + ["--traj-path", f"{STEM}.h5", "-o", "state", "--save-traj", "-b", "physx_cpu"],
        cwd=out,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    return result.stdout + result.stderr


def test_replay_reproduces_success(demos):
    out, _ = demos
    assert "Replayed 2 episodes, 2/2=100.00% demos saved" in _replay(out)


def test_a_slipped_grasp_is_tried_again_with_the_next_plan(tmp_path):
    """Seed 11 (InstructMove 1.0's sampler): the first grasp plan's lift loses a hair clip;
    the scene is reset and the next grasp plan lifts it. Only that rollout is recorded, so
    ManiSkill's replay from the seed reproduces it. (Seed 33's watering can slipped so while
    its cheapest grasp held the handle with the open hand touching the can; such grasps now
    go last, and it rises at the first plan.)"""
    report = generate(TASK, ROBOT, 1, tmp_path, seed0=11, shard_size=1, sampler=1)
    assert (report.kept, report.tried, report.rollouts) == (1, 1, 2)
    (entry,) = json.loads((tmp_path / f"{STEM}.episodes.json").read_text())
    assert entry["seed"] == 11 and entry["variant"] == 1
    assert entry["spec"]["objects"][entry["spec"]["target"]]["category"] == "hair_clip"
    assert "Replayed 1 episodes, 1/1=100.00% demos saved" in _replay(tmp_path)


def test_interrupted_run_resumes_to_exactly_n(demos, tmp_path, monkeypatch, capsys):
    out, _ = demos
    shutil.copytree(out / "shards", tmp_path / "shards")  # the first run's finished work
    shutil.copy(out / f"{STEM}.ledger.json", tmp_path)
    real = generator.synthesize
    calls = []

    def interrupt_second(env, variant):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt  # Ctrl-C while the fourth demo is being planned
        return real(env, variant)

    monkeypatch.setattr(generator, "synthesize", interrupt_second)
    with pytest.raises(KeyboardInterrupt):
        generate(TASK, ROBOT, 4, tmp_path, shard_size=1)
    ledger = json.loads((tmp_path / f"{STEM}.ledger.json").read_text())
    assert [s["index"] for s in ledger["shards"]] == [0, 1, 2]
    left = sorted(p.name for p in tmp_path.iterdir() if p.name != LOCK)
    assert left == [f"{STEM}.ledger.json", "shards"], "no staging folder left behind"
    monkeypatch.undo()
    argv = ["demos", "generate", "--task", TASK, "--robot", ROBOT, "-n", "4"]
    assert main([*argv, "--out", str(tmp_path)]) == 2
    assert "was started with shard_size=1, not 5" in capsys.readouterr().err
    assert generate(TASK, ROBOT, 4, tmp_path, shard_size=1).kept == 4
    first = [e["reset_kwargs"]["seed"] for e in _episodes(out)]
    episodes = _episodes(tmp_path)
    seeds = [e["reset_kwargs"]["seed"] for e in episodes]
    assert len(episodes) == 4 and seeds[:2] == first and len(set(seeds)) == 4
    with h5py.File(out / f"{STEM}.h5") as a, h5py.File(tmp_path / f"{STEM}.h5") as b:
        for k in range(2):
            assert (a[f"traj_{k}/actions"][:] == b[f"traj_{k}/actions"][:]).all()


def test_cli_reports_rate_and_rejects_bad_input(demos, capsys):
    out, _ = demos
    argv = ["demos", "generate", "--task", TASK, "--robot", ROBOT, "--out", str(out)]
    assert main([*argv, "-n", "2"]) == 2
    assert "was started with shard_size=1" in capsys.readouterr().err
    assert main([*argv, "-n", "2", "--shard-size", "1"]) == 0  # finished already: merge only
    assert "2 demos from" in capsys.readouterr().out
    assert main(["demos", "generate", "--robot", "ur5", "--out", str(out)]) == 2
    assert "unknown robot 'ur5'; allowed: 'franka', 'piperx'" in capsys.readouterr().err
