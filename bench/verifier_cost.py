"""What the verifier gate and the visibility check cost per episode.

Per family (one robot): composing an episode through the gate (the verifier certifies it;
a refused scene is drawn again) against composing it ungated, in the same run, both over
seeds 0..``--seeds``-1, with the share of seeds the gate re-drew; then the visibility
measure (segmentation renders of the scene cameras, ``tasks.visibility``) against the
reset it follows, at the default camera resolution.
"""

from __future__ import annotations

import argparse
import time

import gymnasium as gym

import instructmove_ms  # noqa: F401
from instructmove_ms.composer import compose
from instructmove_ms.tasks import TASKS
from instructmove_ms.tasks.visibility import measure


def _compose(env, seed: int, gate) -> object:
    u = env.unwrapped
    return compose(
        u.task,
        u._roles,
        u.catalog,
        u.split,
        seed,
        u.robot_uids,
        lambda rng: u.agent.sample_init_qpos(rng, u.robot_init_qpos_noise),
        gate,
        workspace=u.agent.workspace,
    )


def _per_seed(fn, seeds: int) -> float:
    start = time.perf_counter()
    for seed in range(seeds):
        fn(seed)
    return (time.perf_counter() - start) / seeds


def _family(env_id: str, robot: str, seeds: int) -> str:
    """One row of the table for ``env_id``."""
    env = gym.make(env_id, robot_uids=robot, obs_mode="state")
    u = env.unwrapped

    def ungated(seed: int):
        return _compose(env, seed, lambda spec: spec)

    def gated(seed: int):
        return _compose(env, seed, u.certified)

    plain, checked = _per_seed(ungated, seeds), _per_seed(gated, seeds)
    redrawn = sum(ungated(s).objects != gated(s).objects for s in range(seeds))
    specs = [u.sample_episode(s) for s in range(seeds)]

    def reset(seed: int):
        env.reset(options={"episode": specs[seed]})

    resets = _per_seed(reset, seeds)
    seen = _per_seed(lambda seed: (reset(seed), measure(env)), seeds) - resets
    env.close()
    return (
        f"{env_id:<28} {plain * 1e3:>7.1f}ms {checked * 1e3:>7.1f}ms {checked / plain:>5.2f}x "
        f"{redrawn / seeds:>8.0%} {resets * 1e3:>6.0f}ms {seen * 1e3:>9.0f}ms "
        f"{seen / resets:>5.2f}x"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--robot", default="franka")
    parser.add_argument("--seeds", type=int, default=50)
    args = parser.parse_args()
    print(
        f"{'family':<28} {'ungated':>9} {'gated':>9} {'ratio':>6} {'re-drawn':>9} "
        f"{'reset':>8} {'visibility':>11} {'ratio':>6}"
    )
    for env_id in TASKS:
        print(_family(env_id, args.robot, args.seeds))


if __name__ == "__main__":
    main()
