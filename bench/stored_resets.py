"""Every stored held-out episode loads, certifies and resets on this machine.

For every family, robot and split (or the ones named), each stored spec is rebuilt through
``reset(options={"episode": ...})``, which runs the verifier on load; the run fails on the
first episode that does not rebuild, and prints the episodes per second and the BLAS
kernel it ran on. ``tests/test_portability.py`` resets the first episode of each set under
every floating-point set-up of CI; this resets all 2,400 (about 10 minutes on 2 cores):

    OPENBLAS_CORETYPE=Sandybridge python bench/stored_resets.py [--task T] [--robot R]
"""

from __future__ import annotations

import argparse
import time

import gymnasium as gym
from tqdm import tqdm

import instructmove_ms  # noqa: F401
from instructmove_ms.floats import describe
from instructmove_ms.heldout import load_set
from instructmove_ms.splits import EVAL_SPLITS
from instructmove_ms.tasks import TASKS


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--task", choices=sorted(TASKS), action="append")
    parser.add_argument("--robot", choices=("franka", "piperx"), action="append")
    args = parser.parse_args()
    count, start = 0, time.perf_counter()
    for env_id in args.task or sorted(TASKS):
        for robot in args.robot or ("franka", "piperx"):
            env = gym.make(env_id, robot_uids=robot, obs_mode="state", render_backend="none")
            for split in EVAL_SPLITS:
                specs = load_set(env_id, robot, split)
                for spec in tqdm(specs, desc=f"{env_id} {robot} {split}", unit="episode"):
                    env.reset(options={"episode": spec.to_dict()})
                    if env.unwrapped.episode.instruction != spec.instruction:
                        raise SystemExit(f"{env_id} {robot} {split} seed {spec.seed} changed")
                    count += 1
            env.close()
    elapsed = time.perf_counter() - start
    print(f"{count} stored episodes reset, {count / elapsed:.1f}/s ({describe()})")


if __name__ == "__main__":
    main()
