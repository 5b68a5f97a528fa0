"""The scenes need the text: a privileged oracle reaches the target, a blind policy rarely."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import instructmove_ms  # noqa: F401
import scripted
from instructmove_ms.tasks import TASKS

ORACLE_EPISODES, BLIND_EPISODES = 20, 40


def _reach_rate(env_id: str, privileged: bool, episodes: int, seed0: int) -> tuple[float, float]:
    """(reach rate, mean 1/|candidates|) of the scripted policy over ``episodes`` seeds."""
    env = gym.make(
        env_id,
        obs_mode="state",
        render_backend="none",
        control_mode="pd_ee_delta_pose",
        robot_uids="franka",
    )
    rng = np.random.default_rng(seed0)
    reached, chance = [], []
    for seed in range(seed0, seed0 + episodes):
        env.reset(seed=seed)
        spec = env.unwrapped.episode
        info = scripted.reach_object(env, scripted.choose(spec, rng, privileged))
        reached.append(bool(info["reach"]))
        chance.append(1.0 / len(spec.candidates))
    env.close()
    return float(np.mean(reached)), float(np.mean(chance))


@pytest.mark.parametrize("env_id", sorted(TASKS))
def test_oracle_reaches_and_blind_policy_is_at_chance(env_id):
    oracle, _ = _reach_rate(env_id, True, ORACLE_EPISODES, 0)
    blind, chance = _reach_rate(env_id, False, BLIND_EPISODES, 1000)
    assert oracle >= 0.95
    # binomial tolerance: three standard deviations around chance
    sd = np.sqrt(chance * (1 - chance) / BLIND_EPISODES)
    assert abs(blind - chance) <= 3 * sd + 0.02, (blind, chance)
    assert oracle - blind >= 0.3
