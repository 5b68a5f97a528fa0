"""What runs on a GPU machine, for a user who has one: every family and robot as batched
sub-scenes at several ``--num-envs`` (state and rgb observations; reset time and env-steps/s),
a demo recorded on the CPU backend replayed on the GPU backend by ManiSkill's own replay tool,
and the planner oracle through ``instructmove eval --num-envs``.

    python bench/gpu_check.py                  # GPU physics (physx_cuda), --num-envs 1 4 16
    python bench/gpu_check.py --dry-run        # the same steps on the CPU backend, one env

GPU physics is checked first (``instructmove doctor`` says the same): without SAPIEN's PhysX GPU
library or a CUDA device the check stops in one line. ``--dry-run`` runs every step on the CPU
backend with one env and a few steps, so the test suite keeps the script from rotting.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import gymnasium as gym
import torch

import instructmove_ms  # noqa: F401  (registration)
from instructmove_ms.demos.generate import generate
from instructmove_ms.gpu_physics import GpuPhysicsUnavailable, check_gpu_physics
from instructmove_ms.tasks import TASKS

REPLAYED = re.compile(r"Replayed (\d+) episodes, (\d+)/\d+=")


def batched(task: str, robot: str, obs_mode: str, num_envs: int, backend: str, steps: int):
    """(reset seconds, env-steps/s) of ``num_envs`` sub-scenes under random actions."""
    env = gym.make(
        task, robot_uids=robot, obs_mode=obs_mode, num_envs=num_envs, sim_backend=backend
    )
    start = time.perf_counter()
    env.reset(seed=list(range(num_envs)))
    reset = time.perf_counter() - start
    actions = torch.rand((steps, *env.action_space.shape)) * 2 - 1
    start = time.perf_counter()
    for action in actions:
        env.step(action)
    rate = num_envs * steps / (time.perf_counter() - start)
    env.close()
    return reset, rate


def replayed_on(backend: str, folder: Path) -> tuple[int, int]:
    """One PickCategory Franka demo recorded on the CPU backend, replayed on ``backend`` by
    ManiSkill's replay tool: (replayed, succeeded)."""
    path = generate("PickCategory-InstructMove", "franka", 1, folder, shard_size=1).path
    run = subprocess.run(
        [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
        + ["--traj-path", str(path), "-o", "state", "-b", backend, "--allow-failure"],
        capture_output=True,
        text=True,
        timeout=900,
    )
    found = REPLAYED.search(run.stdout + run.stderr)
    if run.returncode != 0 or found is None:
        raise SystemExit(f"replay on {backend} failed: {(run.stdout + run.stderr)[-2000:]}")
    return int(found.group(1)), int(found.group(2))


def oracle_on(backend: str, num_envs: int, folder: Path) -> dict:
    """``instructmove eval`` of the oracle on ``num_envs`` stored PickCategory episodes at once:
    its summary (S and success)."""
    argv = [sys.executable, "-m", "instructmove_ms.cli", "eval", "--task"]
    argv += ["PickCategory-InstructMove", "--policy", "oracle", "--episodes", str(num_envs)]
    argv += ["--num-envs", str(num_envs), "--sim-backend", backend, "--out", str(folder)]
    run = subprocess.run(argv, capture_output=True, text=True, timeout=1800)
    if run.returncode != 0:
        raise SystemExit(f"eval on {backend} failed: {run.stderr[-2000:]}")
    (group,) = json.loads((folder / "summary.json").read_text())["groups"]
    return group


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--num-envs", type=int, nargs="+", default=[1, 4, 16])
    parser.add_argument("--steps", type=int, default=50, help="random steps per measurement")
    parser.add_argument("--dry-run", action="store_true", help="the CPU backend, one env")
    args = parser.parse_args()
    backend, sizes, steps = "physx_cuda", args.num_envs, args.steps
    if args.dry_run:
        backend, sizes, steps = "physx_cpu", [1], 3
    else:
        try:
            check_gpu_physics()
        except GpuPhysicsUnavailable as exc:
            raise SystemExit(f"gpu_check: {exc}") from None
    print(f"backend {backend}\n")
    print("| task | robot | obs | num_envs | reset (s) | env-steps/s |\n|---|---|---|---|---|---|")
    for task, spec in TASKS.items():
        for robot in spec.supported_robots:
            for obs_mode in ("state", "rgb"):
                for n in sizes:
                    reset, rate = batched(task, robot, obs_mode, n, backend, steps)
                    print(f"| {task} | {robot} | {obs_mode} | {n} | {reset:.2f} | {rate:.1f} |")
    with tempfile.TemporaryDirectory() as tmp:
        replayed, succeeded = replayed_on(backend, Path(tmp) / "demos")
        print(f"\nCPU-recorded demo replayed on {backend}: {succeeded}/{replayed} succeeded")
        group = oracle_on(backend, max(sizes), Path(tmp) / "eval")
    print(
        f"oracle, {group['episodes']} episodes at once on {backend}: "
        f"S {group['stage_score']:.2f}, success {group['success']:.2f}"
    )


if __name__ == "__main__":
    main()
