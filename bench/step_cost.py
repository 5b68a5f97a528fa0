"""Where an env step's time goes: the controller and physics against everything else.

For each env (our PickCategory with either robot, ManiSkill's PickCube-v1 as the baseline),
state observations and each reward mode, it times in the same run:

- ``physics``: ``env.unwrapped._step_action(action)``, ManiSkill's controller plus the
  physics substeps of one control step (the floor no task can go below);
- ``step``: the whole ``env.step(action)`` (physics, ``evaluate``, observation, reward);

and prints steps/s, the ratio step/physics and steps/s against PickCube-v1. Then the cost as
the scene grows (dense reward): steps/s, step/physics and reconfigure time of PickCategory
with 1, 3 and 5 distractors (its maximum), and of hand-made scenes of 3, 6 and 10 small
objects on a grid (beyond any family's count, built with ``"verify": False``), with the
slope per object and the 10-object step against the 3-object one. Random actions (a fixed
seed), ``--steps`` per measurement after a warm-up; medians of ``--repeats``.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

import gymnasium as gym
import numpy as np
import torch

import instructmove_ms  # noqa: F401
from instructmove_ms.episode import EpisodeSpec, ObjectSpec

ENV_ID = "PickCategory-InstructMove"
ROBOTS = ("franka", "piperx")
REWARDS = ("dense", "sparse")
WARMUP = 10
GRID_SIZES = (3, 6, 10)


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


def _grid_scenes(env, sizes: tuple[int, ...]) -> dict[int, EpisodeSpec]:
    """Hand-made scenes of ``sizes`` objects: the first small (at most 0.1 m wide) distinct
    objects of PickCategory's episodes, resting as sampled, on a grid of 0.15 m."""
    u = env.unwrapped
    base = u.sample_episode(0)
    pool: list[ObjectSpec] = []
    seed = 0
    while len(pool) < max(sizes):
        for obj in u.sample_episode(seed).objects:
            lo, hi = u.catalog[obj.uuid].bounds
            if obj.uuid not in {o.uuid for o in pool} and max(hi[:2] - lo[:2]) <= 0.1:
                pool.append(obj)
        seed += 1
    scenes = {}
    for size in sizes:
        objects = tuple(
            dataclasses.replace(
                obj,
                role="target" if i == 0 else "distractor",
                pose=(0.33 + 0.15 * (i // 5), -0.3 + 0.15 * (i % 5), *obj.pose[2:]),
            )
            for i, obj in enumerate(pool[:size])
        )
        scenes[size] = dataclasses.replace(base, objects=objects, target=0, candidates=(0,))
    return scenes


def _grown(env, resets: list[dict], steps: int) -> tuple[float, float, float]:
    """Median seconds per step, per physics step and per reconfiguring reset, one round
    per reset's keyword arguments in ``resets``; both kinds of step start from the reset
    (the same actions from the same state: the same physics)."""
    reconfigure, full, physics = [], [], []
    for kwargs in resets:
        start = time.perf_counter()
        env.reset(**kwargs)
        reconfigure.append(time.perf_counter() - start)
        full.append(_time_steps(env, steps, physics_only=False))
        env.reset(**kwargs)
        physics.append(_time_steps(env, steps, physics_only=True))
    return statistics.median(full), statistics.median(physics), statistics.median(reconfigure)


def scaling(robot: str, steps: int, repeats: int) -> list[tuple[str, int, float, float, float]]:
    """(scene kind, objects, s per step, s per physics step, s per reconfiguring reset) for
    PickCategory with 1, 3 and 5 distractors, then grid scenes of 3, 6 and 10 objects."""
    rows = []
    for distractors in (1, 3, 5):
        env = _make(ENV_ID, robot, "dense", num_distractors=distractors)
        timed = _grown(env, [{"seed": k} for k in range(repeats)], steps)
        env.close()
        rows.append(("family", distractors + 1, *timed))
    env = _make(ENV_ID, robot, "dense")
    for size, spec in _grid_scenes(env, GRID_SIZES).items():
        options = {"episode": spec.to_dict(), "verify": False}
        rows.append(("grid", size, *_grown(env, [{"options": options}] * repeats, steps)))
    env.close()
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
    print("\nscene size (dense reward): objects, steps/s, step/physics, reconfigure s")
    for robot in ROBOTS:
        grown = scaling(robot, args.steps, args.repeats)
        for kind, objects, per_step, physics, reset in grown:
            print(
                f"{robot:7s} {kind:6s} {objects:2d} objects {1 / per_step:7.0f} steps/s "
                f"{per_step / physics:5.2f}x {reset:6.2f} s"
            )
        for kind in ("family", "grid"):
            (n0, s0, p0), (n1, s1, p1) = [r[1:4] for r in grown if r[0] == kind][::2]
            slope = (s1 - s0) / (n1 - n0)
            rest = ((s1 - p1) - (s0 - p0)) / (n1 - n0)
            print(
                f"{robot:7s} {kind:6s} per object: +{slope * 1e3:.3f} ms/step "
                f"({slope / s0:.1%} of the {n0}-object step), of which the step beyond the "
                f"physics +{rest * 1e3:.3f} ms; {n1} objects cost {s1 / s0:.2f}x the step of "
                f"{n0} (physics {p1 / p0:.2f}x, the rest {(s1 - p1) / (s0 - p0):.2f}x)"
            )


if __name__ == "__main__":
    main()
