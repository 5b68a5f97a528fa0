"""The per-step info and dense rewards of planned demos, replayed, equal those recorded
before the step was made cheaper (tests/data/step_reference.json): one pass of measurements
per step, contacts read once, grasp checks that stop at an untouched finger. The PiperX
cases were recorded again when its SRDF removed the self-contacts of its own links (a
change of the physics, not of the scoring), and the PickSpatial case when relations gained
their direction cone (its seed's scene moved). The scoring made batched (one read of the
scene, rotations by cross products, grasp checks that ask bounding boxes first) and the
PiperX's base links ignoring the table left every case as recorded. Every case was recorded
again when the default snapshot moved to library revision 2 (seed 0's scenes moved).
``tests/tools/record_step_reference.py CASE`` records a case again.

The reference was recorded on one machine and is checked on others, whose BLAS kernels,
CPU features and PhysX code paths differ in the last bits: stage flags and the indices of
reached and lifted objects must be equal, distances and rewards may differ by what a
positional error of ``POSITION_ERROR`` in every body makes of them. A distance between two
bodies moves by at most twice that; the dense reward by at most its largest slope per metre
of distance or rise (``reward_slope``) times that. 10 um is 2,000 times less than the reach
threshold and 3,000 times less than the lift height, and about 100 times the differences
seen between machines (rewards within 7.3e-6)."""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium as gym
import h5py
import numpy as np
import pytest
import torch

from instructmove_ms.demos.generate import generate
from instructmove_ms.tasks import TASKS

pytestmark = pytest.mark.portability  # recorded on one machine, checked on every other

REFERENCE = json.loads((Path(__file__).parent / "data" / "step_reference.json").read_text())
#: How far any body's position may land from where the recording machine put it (m).
POSITION_ERROR = 5e-6
#: float32 resolution of a reward of about 10 (the env scores in float32).
FLOAT32_REWARD = 2e-6


def reward_slope(task: str) -> float:
    """The largest change of the dense reward per metre of any distance or rise: the
    approach term 1 - tanh(10 d) (10), the raise term 2 * rise / lift (2 / lift) and, for
    PlaceA2B, the carry term 2 * (1 - tanh(5 d)) (10); see ``compute_dense_reward``."""
    env_task = TASKS[task]
    carry = 10.0 if env_task.family == "PlaceA2B" else 0.0
    return 10.0 + 2.0 / env_task.thresholds.lift + carry


def tolerances(task: str) -> dict[str, float]:
    distance = 2 * POSITION_ERROR
    return {
        "target_distance": distance,
        "reward": reward_slope(task) * distance + FLOAT32_REWARD,
    }


def replayed(case: str, folder: Path, keys) -> dict:
    """The first planned demo of ``case`` ("<env id>/<robot>"), recorded in ``folder`` and
    replayed: its seed and every step's ``keys`` of info (and ``reward``)."""
    task, robot = case.split("/")
    path = generate(task, robot, 1, folder, shard_size=1).path
    (episode,) = json.loads(path.with_suffix(".json").read_text())["episodes"]
    with h5py.File(path) as f:
        actions = f[f"traj_{episode['episode_id']}/actions"][()]
    env = gym.make(
        task,
        robot_uids=robot,
        obs_mode="state",
        control_mode="pd_joint_pos",
        reward_mode="dense",
        render_backend="none",
    )
    env.reset(**episode["reset_kwargs"])
    seen: dict[str, list] = {key: [] for key in keys}
    for action in actions:
        _, reward, _, _, info = env.step(torch.from_numpy(action)[None])
        info = {**info, "reward": reward}
        for key in seen:
            seen[key].append(info[key][0].item())
    env.close()
    return {"seed": episode["reset_kwargs"]["seed"], "steps": seen}


@pytest.mark.parametrize("case", sorted(REFERENCE))
def test_replayed_demo_scores_every_step_as_before(case, tmp_path):
    expected = REFERENCE[case]
    got = replayed(case, tmp_path, expected["steps"])
    assert got["seed"] == expected["seed"], "the same demo"
    assert len(got["steps"]["reward"]) == len(expected["steps"]["reward"])
    atol = tolerances(case.split("/")[0])
    for key, values in expected["steps"].items():
        if key in atol:
            np.testing.assert_allclose(
                got["steps"][key], values, rtol=0, atol=atol[key], err_msg=key
            )
        else:  # flags, object indices and the stage score they make: exactly
            assert got["steps"][key] == values, key
    assert any(expected["steps"]["success"]), "the demo succeeds: grasps were checked"
