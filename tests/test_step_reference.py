"""The per-step info and dense rewards of planned demos, replayed, equal those recorded
before the step was made cheaper (tests/data/step_reference.json): one pass of measurements
per step, contacts read once, grasp checks that stop at an untouched finger. The PiperX
cases were recorded again when its SRDF removed the self-contacts of its own links (a
change of the physics, not of the scoring), and the PickSpatial case when relations gained
their direction cone (its seed's scene moved). The scoring made batched (one read of the
scene, rotations by cross products, grasp checks that ask bounding boxes first) and the
PiperX's base links ignoring the table left every case as recorded.
``tests/tools/record_step_reference.py CASE`` records a case again."""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium as gym
import h5py
import numpy as np
import pytest
import torch

from instructmove_ms.demos.generate import generate

REFERENCE = json.loads((Path(__file__).parent / "data" / "step_reference.json").read_text())
FLOATS = ("target_distance", "stage_score", "reward")


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
    for key, values in expected["steps"].items():
        if key in FLOATS:
            np.testing.assert_allclose(got["steps"][key], values, rtol=0, atol=1e-6, err_msg=key)
        else:
            assert got["steps"][key] == values, key
    assert any(expected["steps"]["success"]), "the demo succeeds: grasps were checked"
