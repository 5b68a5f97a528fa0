"""Evaluation throughput on the CPU: held-out episodes per hour.

Runs the random policy (full horizon, no early stop) and the scripted oracle on the first
episodes of the PickCategory held-out set, with state observations and with rgb observations
from the default cameras, and prints episodes per hour next to the same number of
ManiSkill PickCube-v1 episodes stretched to the same horizon (the baseline, measured in this
run).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import gymnasium as gym

import instructmove_ms  # noqa: F401
from instructmove_ms.evaluation import evaluate
from instructmove_ms.policies import RandomPolicy, ScriptedOraclePolicy

TASK = "PickCategory-InstructMove"


def baseline_per_hour(obs_mode: str, episodes: int, horizon: int) -> float:
    env = gym.make("PickCube-v1", obs_mode=obs_mode, render_backend="cpu")
    start = time.perf_counter()
    for seed in range(episodes):
        env.reset(seed=seed)
        for _ in range(horizon):
            env.step(env.action_space.sample())
    env.close()
    return episodes * 3600 / (time.perf_counter() - start)


def ours_per_hour(policy, obs_mode: str, episodes: int) -> float:
    policy.get_obs_mode = lambda: obs_mode  # the reference policies read only the state
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        evaluate(policy, TASK, "seen", Path(tmp), robot="franka", episodes=episodes)
        return episodes * 3600 / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--episodes", type=int, default=4)
    args = parser.parse_args()
    horizon = 300
    for obs_mode in ("state", "rgb"):
        base = baseline_per_hour(obs_mode, args.episodes, horizon)
        for name, policy in (("random", RandomPolicy(0)), ("oracle", ScriptedOraclePolicy(0))):
            ours = ours_per_hour(policy, obs_mode, args.episodes)
            print(
                f"{obs_mode:5s} obs, {name:6s}: {ours:7.0f} episodes/h; PickCube-v1 with "
                f"{horizon} random steps {base:7.0f} episodes/h; ratio {ours / base:.2f}"
            )


if __name__ == "__main__":
    main()
