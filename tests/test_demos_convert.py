"""PiperX demos converted to end-effector control with both arms (ManiSkill's own converter
drives one arm only), then replayed by ManiSkill's plain command."""

from __future__ import annotations

import json
import subprocess
import sys

import h5py
import numpy as np
import pytest

from instructmove_ms.cli import main
from instructmove_ms.demos.ee_control import convert
from instructmove_ms.demos.generate import generate
from instructmove_ms.episode import actor_name

TASK, ROBOT = "PickCategory-InstructMove", "piperx"
STEM = f"{TASK}_{ROBOT}"
CONVERTED = f"{STEM}.state.pd_ee_delta_pose.physx_cpu"


@pytest.fixture(scope="module")
def converted(tmp_path_factory):
    out = tmp_path_factory.mktemp("convert")
    generate(TASK, ROBOT, 1, out, shard_size=1)
    return out, convert(out / f"{STEM}.h5")


def test_converted_demo_lifts_the_target_with_end_effector_actions(converted):
    out, report = converted
    assert (report.total, report.kept) == (1, 1)
    meta = json.loads((out / f"{CONVERTED}.json").read_text())
    assert meta["env_info"]["env_kwargs"]["control_mode"] == "pd_ee_delta_pose"
    sidecar = json.loads((out / f"{CONVERTED}.episodes.json").read_text())
    target = sidecar[0]["spec"]["target"]
    with h5py.File(report.path) as f, h5py.File(out / f"{STEM}.h5") as source:
        actions = f["traj_0/actions"][()]
        height = f[f"traj_0/env_states/actors/{actor_name(target)}"][:, 2]
        robot = "traj_0/env_states/articulations/piperx"
        end, planned_end = f[robot][-1], source[robot][-1]
    # arm_left (6), arm_right (6), then the two gripper widths, all within the action range
    assert actions.shape[1] == 14 and np.abs(actions[:, :12]).max() <= 1 + 1e-6
    assert height[-1] - height[0] > 0.05  # the target rose
    # the arms end where the planned joint-space demo ended (root pose 13 values, then qpos)
    np.testing.assert_allclose(end[13:29], planned_end[13:29], atol=0.02)
    assert sidecar[0]["stages"]["lift"][-1] and len(sidecar[0]["stages"]["lift"]) == len(actions)


def test_plain_replay_of_the_converted_demo_succeeds(converted):
    out, _ = converted
    result = subprocess.run(
        [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
        + ["--traj-path", f"{CONVERTED}.h5", "-o", "state", "-b", "physx_cpu"],
        cwd=out,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert "Replayed 1 episodes, 1/1=100.00% demos saved" in result.stdout + result.stderr


def test_cli_converts_and_rejects_modes_without_an_end_effector(converted, capsys):
    out, _ = converted
    traj = str(out / f"{STEM}.h5")
    assert main(["demos", "convert", "--traj", traj, "-c", "pd_joint_delta_pos"]) == 2
    assert "no end-effector controller" in capsys.readouterr().err
    assert main(["demos", "convert", "--traj", traj, "-c", "pd_ee_bogus"]) == 2
    assert "'pd_ee_bogus'; allowed:" in capsys.readouterr().err
    assert main(["demos", "convert", "--traj", traj, "--out", str(out / "cli")]) == 0
    assert "1/1 episodes converted" in capsys.readouterr().out
    assert (out / "cli" / f"{CONVERTED}.h5").exists()
