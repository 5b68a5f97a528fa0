"""Demo synthesis on the CPU: valid-synthesis rate and demos per minute per core.

For every family and robot, plans and runs ``--seeds`` training seeds in one process (one
core) as the generator does (up to ``GRASP_TRIALS`` rollouts per scene) and prints the
valid-synthesis rate (also among the scenes that show every candidate: the others are left
out as ``hidden`` before any motion) with the failures by reason, the rollouts per scene,
demos per minute, and the ratio of the whole synthesis time to the baseline measured in
this run: replaying each scene's last action sequence open loop in the same env (the
simulation cost alone), so the ratio is the planning overhead. With ``--workers K`` it
also times the generator with K spawned workers against one, on PickCategory with the
Franka.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from collections import Counter

import gymnasium as gym

import instructmove_ms  # noqa: F401
from instructmove_ms.demos.generate import generate
from instructmove_ms.demos.synthesis import FAILURES, synthesize_scene
from instructmove_ms.tasks import TASKS


class ActionLog(gym.Wrapper):
    """Keeps every action stepped since the last reset."""

    def reset(self, **kwargs):
        self.actions = []
        return self.env.reset(**kwargs)

    def step(self, action):
        self.actions.append(action)
        return self.env.step(action)


def synthesis(task: str, robot: str, seeds: int) -> tuple[Counter, float, float]:
    """(outcomes by reason, synthesis seconds, open-loop replay seconds of the same actions)."""
    env = ActionLog(
        gym.make(
            task,
            robot_uids=robot,
            obs_mode="state",
            control_mode="pd_joint_pos",
            render_backend="cpu",
        )
    )
    outcomes, recorded = Counter(), []
    start = time.perf_counter()
    for seed in range(seeds):
        scene = synthesize_scene(env, seed)
        outcomes[scene.failure or "kept"] += 1
        outcomes["rollouts"] += scene.rollouts
        recorded.append((seed, env.actions))
    planned = time.perf_counter() - start
    start = time.perf_counter()
    for seed, actions in recorded:
        env.reset(seed=seed)
        for action in actions:
            env.step(action)
    replayed = time.perf_counter() - start
    env.close()
    return outcomes, planned, replayed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", type=int, default=20, help="seeds per family and robot")
    parser.add_argument("--task", default=None, help="one env id (default: every family)")
    parser.add_argument("--robot", default=None, help="one robot (default: both)")
    parser.add_argument("--workers", type=int, default=0, help="also time K generator workers")
    args = parser.parse_args()
    for task in [args.task] if args.task else list(TASKS):
        for robot in [args.robot] if args.robot else TASKS[task].supported_robots:
            outcomes, planned, replayed = synthesis(task, robot, args.seeds)
            kept = outcomes["kept"]
            failures = ", ".join(f"{k}={outcomes[k]}" for k in FAILURES)
            shown = args.seeds - outcomes["hidden"]
            print(
                f"{task:28s} {robot:7s} valid-synthesis rate {kept / args.seeds:6.1%}, "
                f"{kept / max(1, shown):6.1%} of the {shown} scenes that show every candidate "
                f"({failures}; {outcomes['rollouts'] / args.seeds:.2f} rollouts per scene); "
                f"{kept * 60 / planned:5.1f} demos/min/core; "
                f"time vs open-loop replay of the same steps {planned / replayed:4.2f}x"
            )
    if args.workers > 1:
        task, n = "PickCategory-InstructMove", 2 * args.workers
        times = {}
        for workers in (1, args.workers):
            with tempfile.TemporaryDirectory() as tmp:
                start = time.perf_counter()
                generate(task, "franka", n, tmp, workers=workers, shard_size=1)
                times[workers] = time.perf_counter() - start
        print(
            f"generator, {n} demos: {args.workers} workers {times[args.workers]:.1f} s, "
            f"1 worker {times[1]:.1f} s; speed-up {times[1] / times[args.workers]:.2f}x"
        )


if __name__ == "__main__":
    main()
