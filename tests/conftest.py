"""Shared fixtures: envs are expensive to build, so modules share them."""

from __future__ import annotations

import gymnasium as gym
import pytest

import instructmove_ms  # noqa: F401  (registers envs and robots)

ENV_ID = "PickCategory-InstructMove"


def make_env(**kwargs):
    kwargs.setdefault("robot_uids", "franka")  # the scripted tests drive a Franka
    kwargs.setdefault("obs_mode", "state")
    kwargs.setdefault("render_backend", "none")
    return gym.make(ENV_ID, **kwargs)


@pytest.fixture(scope="module")
def state_env():
    env = make_env()
    yield env
    env.close()
