"""What each perturbation axis adds to a reset: reset time (a reset rebuilds the scene:
ManiSkill's reconfigure, the episode's spec, the first observation) with one axis at
level 3 as a ratio to level 0, measured in the same run, interleaved, for both robots.

PickCategory with rgb observations at the default camera resolution, seeds 0..``--seeds``-1
per round, medians of ``--repeats`` rounds. Target: no axis adds more than 15%.
"""

from __future__ import annotations

import argparse
import statistics
import time

import gymnasium as gym

import instructmove_ms  # noqa: F401
from instructmove_ms.perturbation import AXES, MAX_LEVEL

TARGET = 1.15


def _round(env, levels: dict, seeds: int) -> float:
    """Seconds per reset over ``seeds`` seeds at ``levels``."""
    start = time.perf_counter()
    for seed in range(seeds):
        env.reset(seed=seed, options={"perturbation": levels})
    return (time.perf_counter() - start) / seeds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--task", default="PickCategory-InstructMove")
    parser.add_argument("--seeds", type=int, default=5, help="resets per round and setting")
    parser.add_argument("--repeats", type=int, default=3, help="rounds (medians)")
    args = parser.parse_args()
    for robot in ("franka", "piperx"):
        env = gym.make(args.task, robot_uids=robot, obs_mode="rgb", render_backend="cpu")
        settings = {"none": {}} | {axis: {axis: MAX_LEVEL} for axis in AXES}
        _round(env, {}, 2)  # warm-up
        times: dict[str, list[float]] = {name: [] for name in settings}
        for _ in range(args.repeats):
            for name, levels in settings.items():
                times[name].append(_round(env, levels, args.seeds))
        env.close()
        base = statistics.median(times["none"])
        print(f"{robot}: reset at level 0 {base * 1000:.0f} ms")
        for axis in AXES:
            ratio = statistics.median(times[axis]) / base
            mark = "ok" if ratio <= TARGET else f"over {TARGET:.2f}x"
            print(f"  {axis:<11} level {MAX_LEVEL}: {ratio:.2f}x level 0 ({mark})")


if __name__ == "__main__":
    main()
