"""Where an env step's time goes: the controller and physics against everything else.

For each env (our PickCategory with either robot, ManiSkill's PickCube-v1 as the baseline),
state observations and each reward mode, it times in the same run:

- ``physics``: ``env.unwrapped._step_action(action)``, ManiSkill's controller plus the
  physics substeps of one control step (the floor no task can go below);
- ``step``: the whole ``env.step(action)`` (physics, ``evaluate``, observation, reward);

and prints steps/s, the ratio step/physics and steps/s against PickCube-v1. Then the cost as
the scene grows: steps/s and reconfigure time with 1, 3 and 5 distractors (PickCategory's
maximum), and the slope per object. Random actions (a fixed seed), ``--steps`` per
measurement after a warm-up; medians of ``--repeats``.
"""

from __future__ import annotations

import argparse
import statistics
import time

import gymnasium as gym
import numpy as np
import torch

import instructmove_ms  # noqa: F401

ENV_ID = "PickCategory-InstructMove"
ROBOTS = ("franka", "piperx")
REWARDS = ("dense", "sparse")
WARMUP = 10


def _make(env_id: str, robot: str | None, reward: str, **kwargs):
    extra = {"robot_uids": robot} if robot else {}
    return gym.make(
        env_id,
        obs_mode="state",
        reward_mode=reward,
        render_backend="none",
        **extra,
        **kwargs,
    )


def _time_steps(env, steps: int, physics_only: bool) -> float:
    """Seconds per step over ``steps`` random actions (after a warm-up)."""
    rng = np.random.default_rng(0)
    space = env.action_space
    actions = [
        torch.from_numpy(rng.uniform(space.low, space.high).astype(np.float32))
        for _ in range(steps + WARMUP)
    ]
    u = env.unwrapped
    step = u._step_action if physics_only else env.step
    for action in actions[:WARMUP]:
        step(action)
    start = time.perf_counter()
    for action in actions[WARMUP:]:
        step(action)
    return (time.perf_counter() - start) / steps


def measure(env_id: str, robot: str | None, reward: str, steps: int, repeats: int) -> dict:
    """Median seconds per physics-only step and per full step."""
    env = _make(env_id, robot, reward)
    physics, full = [], []
    for k in range(repeats):
        env.reset(seed=k)
        physics.append(_time_steps(env, steps, physics_only=True))
        env.reset(seed=k)
        full.append(_time_steps(env, steps, physics_only=False))
    env.close()
    return {"physics": statistics.median(physics), "step": statistics.median(full)}


def scaling(robot: str, steps: int, repeats: int) -> list[tuple[int, float, float]]:
    """(objects, seconds per step, seconds per reconfiguring reset) per distractor count."""
    rows = []
    for distractors in (1, 3, 5):
        env = _make(ENV_ID, robot, "dense", num_distractors=distractors)
        resets, per_step = [], []
        for k in range(repeats):
            start = time.perf_counter()
            env.reset(seed=k)
            resets.append(time.perf_counter() - start)
            per_step.append(_time_steps(env, steps, physics_only=False))
        env.close()
        rows.append((distractors + 1, statistics.median(per_step), statistics.median(resets)))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--steps", type=int, default=200, help="timed steps per measurement")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rows = {}
    for reward in REWARDS:
        rows[("PickCube-v1", reward)] = measure(
            "PickCube-v1", None, reward, args.steps, args.repeats
        )
        for robot in ROBOTS:
            rows[(robot, reward)] = measure(ENV_ID, robot, reward, args.steps, args.repeats)
    print(
        f"{'env':12s} {'reward':7s} {'steps/s':>8s} {'physics/s':>9s} {'step/physics':>12s} "
        f"{'vs PickCube':>11s}"
    )
    for (name, reward), row in rows.items():
        cube = rows[("PickCube-v1", reward)]["step"]
        print(
            f"{name:12s} {reward:7s} {1 / row['step']:8.0f} {1 / row['physics']:9.0f} "
            f"{row['step'] / row['physics']:11.2f}x {cube / row['step']:10.2f}x"
        )
    for reward in REWARDS:
        ratio = rows[("franka", reward)]["step"] / rows[("piperx", reward)]["step"]
        print(f"PiperX steps/s / Franka steps/s ({reward}): {ratio:.2f}x")
    print("\nscene size (dense reward): objects, steps/s, reconfigure s")
    for robot in ROBOTS:
        grown = scaling(robot, args.steps, args.repeats)
        for objects, per_step, reset in grown:
            print(f"{robot:7s} {objects:2d} objects {1 / per_step:7.0f} steps/s  {reset:6.2f} s")
        (n0, s0, _), (n1, s1, _) = grown[0], grown[-1]
        slope = (s1 - s0) / (n1 - n0)
        print(
            f"{robot:7s} per object: +{slope * 1e3:.3f} ms/step ({slope / s0:.1%} of the "
            f"{n0}-object step); {n1} objects cost {s1 / grown[1][1]:.2f}x "
            f"the step of {grown[1][0]}"
        )


if __name__ == "__main__":
    main()
