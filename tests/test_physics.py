"""Scripted physics: reaching and lifting the target latches the stages; a distractor does not."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import hand_spec, make_env
from instructmove_ms.episode import EpisodeSpec
from scripted import CLOSED, OPEN, hold
from scripted import servo as move_to

LAYOUT = [  # category, x, y (robot frame)
    ("canned_coke", 0.45, -0.05),
    ("tomato", 0.30, 0.20),
    ("lemon", 0.30, -0.25),
    ("egg", 0.55, 0.22),
    ("eraser", 0.56, -0.30),
    ("usb_drive", 0.28, 0.0),
]


def _spec(target: int) -> EpisodeSpec:
    return hand_spec(
        [(cat, (x, y)) for cat, x, y in LAYOUT],
        "franka",
        (0.0, -0.569, 0.0, -1.97, 0.0, 1.5, 0.741, 0.04, 0.04),
        target,
    )


@pytest.fixture(scope="module")
def ee_env():
    env = make_env(control_mode="pd_ee_delta_pose")
    yield env
    env.close()


def _object_z(env, k: int) -> float:
    return float(env.unwrapped.objects[k].pose.p[0, 2])


def test_reach_and_lift_target(ee_env):
    ee_env.reset(options={"episode": _spec(target=0), "verify": False})
    hold(ee_env, OPEN, 10)  # let objects settle
    can = ee_env.unwrapped.objects[0].pose.p[0].numpy()
    z0 = _object_z(ee_env, 0)
    info = move_to(ee_env, can + [0, 0, 0.2], OPEN)
    assert not bool(info["reach"]) and int(info["reached_object"]) == -1
    height = ee_env.unwrapped.catalog[ee_env.unwrapped.episode.objects[0].uuid].height
    info = move_to(ee_env, can + [0, 0, height - 0.035], OPEN, steps=80)  # palm clears the top
    assert bool(info["reach"]) and int(info["reached_object"]) == 0
    assert not bool(info["lift"])
    hold(ee_env, CLOSED, 15)
    info = move_to(ee_env, can + [0, 0, 0.2], CLOSED, steps=80)
    rise = _object_z(ee_env, 0) - z0
    assert rise > 0.08, "the can rose with the gripper"
    assert bool(ee_env.unwrapped.agent.is_grasping(ee_env.unwrapped.objects[0])[0])
    assert bool(info["lift"]) and bool(info["success"])
    assert float(info["stage_score"]) == 1.0
    assert int(info["lifted_object"]) == 0


def test_reaching_a_distractor_is_not_reach(ee_env):
    ee_env.reset(options={"episode": _spec(target=0), "verify": False})
    hold(ee_env, OPEN, 10)
    tomato = ee_env.unwrapped.objects[1].pose.p[0].numpy()
    info = move_to(ee_env, tomato + [0, 0, 0.05], OPEN, steps=80)
    assert int(info["reached_object"]) == 1
    assert not bool(info["reach"]) and float(info["stage_score"]) == 0.0
    info = hold(ee_env, CLOSED, 10)
    assert not bool(info["success"])


def test_knocked_object_is_not_lifted(ee_env):
    """Raising an object without grasping it does not count as a lift."""
    ee_env.reset(options={"episode": _spec(target=0), "verify": False})
    hold(ee_env, OPEN, 5)
    u = ee_env.unwrapped
    pose = u.objects[0].pose.raw_pose.clone()
    pose[:, 2] += 0.1
    u.objects[0].set_pose(pose)
    info = hold(ee_env, OPEN, 1)
    assert not bool(info["lift"])
    assert np.isfinite(float(info["target_distance"]))


def test_dense_reward_grows_with_progress(ee_env):
    ee_env.reset(options={"episode": _spec(target=0), "verify": False})
    info = hold(ee_env, OPEN, 5)
    u = ee_env.unwrapped
    far = float(u.compute_dense_reward(None, None, info))
    can = u.objects[0].pose.p[0].numpy()
    height = u.catalog[u.episode.objects[0].uuid].height
    info = move_to(ee_env, can + [0, 0, height - 0.035], OPEN, steps=80)
    near = float(u.compute_dense_reward(None, None, info))
    assert 0.0 <= far < near <= 1.0
