"""Evaluation at the cost of what the policy reads, on the CPU.

A chunked policy reads an observation only when it asks for a new chunk. For both robots,
with rgb from every camera at the ``instructmove`` format's 224 x 224, a policy replanning
every 1, 5 and 10 steps (random joint targets near the rest pose, drawn a chunk at a time;
no inference cost) runs the first stored PickCategory ``seen`` episodes through the
evaluator's runner:

- on demand: the policy says how many actions it holds, the env renders only at queries;
- today: the same policy without saying it, the env renders every step (what the evaluator
  did before; its cost does not depend on the replanning);
- the limit: the episode's reset, controller and physics for every step without an
  observation, and one render of every camera per query, each timed in this run.

It prints episodes/h, the ratio to the limit and to today, and the projected wall time of
the full evaluation (4 families x 3 splits x 100 episodes x 5 conditions = 6,000 episodes)
at the replanning of openpi's examples (every 5 steps) on 1, 4 and 16 machines of this size,
at the speed-up of 2 worker processes running at once (each with its share of the cores, as
``--workers 2`` runs them) measured here.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import multiprocessing as mp
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
import torch

import instructmove_ms  # noqa: F401
from instructmove_ms import evaluation, heldout
from instructmove_ms.executor import children_threads, cores, set_worker_threads, share_of_cores

TASK, SIZE = "PickCategory-InstructMove", 224
REPLANS = (1, 5, 10)
SWEEP_EPISODES, MACHINES = 4 * 3 * 100 * 5, (1, 4, 16)


class Chunks:
    """Random joint targets within 0.05 rad of the rest pose, ``every`` at a time, asked
    for with the rgb observation of all cameras at 224 x 224 (it says nothing of what it
    holds: the evaluator renders every step)."""

    def __init__(self, every: int) -> None:
        self.every, self.rng = every, np.random.default_rng(0)
        self.queries = 0

    def get_obs_mode(self) -> str:
        return "rgb"

    def get_control_mode(self) -> str:
        return "pd_joint_pos"

    def get_sensor_configs(self) -> dict:
        return {"width": SIZE, "height": SIZE}

    def bind(self, env) -> None:
        u = env.unwrapped
        self.rest = u.agent.policy_interface().state(u.agent.robot.get_qpos()[0].cpu())

    def reset(self, obs) -> None:
        self.chunk: list[np.ndarray] = []

    def act(self, obs) -> np.ndarray:
        if not self.chunk:
            assert obs["sensor_data"], "a query gets the cameras"
            self.queries += 1
            noise = self.rng.uniform(-0.05, 0.05, (self.every, len(self.rest)))
            self.chunk = list((self.rest + noise).astype(np.float32)[:, None])
        return self.chunk.pop(0)


class ChunksOnDemand(Chunks):
    def held_actions(self) -> int:
        return len(self.chunk)


def _config(robot: str, episodes: int) -> heldout.EvaluatorConfig:
    return heldout.evaluator_config(TASK, robot, "seen", episodes=episodes)


def episode_seconds(policy: Chunks, config: heldout.EvaluatorConfig, barrier: Any = None) -> float:
    """Seconds per episode of the evaluator's runner (the env built and warmed beforehand;
    the timing starts once every party of ``barrier`` is there too)."""
    setup = evaluation._Setup(
        policy, dataclasses.replace(config, episodes=[]), Path("."), 1, "auto", None, frozenset()
    )
    runner = setup.runner()
    runner.run(list(config.episodes[:1]))  # warm: first render, shader compilation
    if barrier is not None:
        barrier.wait()
    start = time.perf_counter()
    for episode in config.episodes:
        runner.run([episode])
    runner.close()
    return (time.perf_counter() - start) / len(config.episodes)


def limit_parts(config: heldout.EvaluatorConfig) -> tuple[float, float, float]:
    """(reset, step without an observation, render of every camera) in seconds, in an env
    made as the evaluator makes it."""
    policy = Chunks(1)
    env = evaluation._make_env(policy, config, 1, "auto", None)
    u = env.unwrapped
    resets, steps, renders = [], [], []
    for episode in config.episodes:
        start = time.perf_counter()
        env.reset(seed=episode.seed, options={"episode": episode.spec.to_dict()})
        resets.append(time.perf_counter() - start)
        policy.bind(env)
        hold = torch.from_numpy(policy.rest.astype(np.float32))[None]
        with evaluation.observations_off(env):
            start = time.perf_counter()
            for _ in range(config.max_episode_steps):
                env.step(hold)
            steps.append((time.perf_counter() - start) / config.max_episode_steps)
        start = time.perf_counter()
        for _ in range(10):
            u.get_obs()
        renders.append((time.perf_counter() - start) / 10)
    env.close()
    return float(np.median(resets)), float(np.median(steps)), float(np.median(renders))


def _timed_together(args: tuple[str, int, Any]) -> float:
    """In a worker process: seconds per episode replanning every 5 steps, the timing started
    when every worker is ready (so that they run at the same time)."""
    robot, episodes, barrier = args
    return episode_seconds(ChunksOnDemand(5), _config(robot, episodes), barrier)


def two_workers_speedup(robot: str, episodes: int, alone: float) -> float:
    """Episodes/h of 2 worker processes at once (as ``--workers 2`` runs them, each with its
    share of the cores) over one process alone (``alone`` seconds per episode)."""
    threads = share_of_cores(2)
    ctx = mp.get_context("spawn")
    with ctx.Manager() as manager, children_threads(threads):
        barrier = manager.Barrier(2)
        with ProcessPoolExecutor(2, ctx, set_worker_threads, (threads,)) as pool:
            seconds = list(pool.map(_timed_together, [(robot, episodes, barrier)] * 2))
    return 2 * alone / float(np.mean(seconds))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--episodes", type=int, default=3, help="stored episodes per run")
    parser.add_argument("--robots", nargs="+", default=["franka", "piperx"])
    args = parser.parse_args()
    for robot in args.robots:
        config = _config(robot, args.episodes)
        horizon = config.max_episode_steps
        reset, step, render = limit_parts(config)
        today = episode_seconds(Chunks(5), config)
        print(
            f"{robot}: {horizon} steps; reset {reset * 1e3:.0f} ms, step without observation "
            f"{step * 1e3:.2f} ms, render of every camera {render * 1e3:.1f} ms; today "
            f"(a render every step) {3600 / today:.0f} episodes/h"
        )
        per_episode = {}
        for every in REPLANS:
            seconds = episode_seconds(ChunksOnDemand(every), config)
            per_episode[every] = seconds
            limit = reset + horizon * step + math.ceil(horizon / every) * render
            print(
                f"  replanning every {every:2d}: {3600 / seconds:6.0f} episodes/h, "
                f"{seconds / limit:.2f}x its limit ({3600 / limit:.0f}/h), "
                f"{today / seconds:.2f}x today"
            )
        speedup = two_workers_speedup(robot, args.episodes, per_episode[5])
        hours = [SWEEP_EPISODES * per_episode[5] / (m * speedup) / 3600 for m in MACHINES]
        print(
            f"  2 workers on {cores()} cores: {speedup:.2f}x one; {SWEEP_EPISODES} episodes "
            f"replanning every 5: "
            + ", ".join(f"{h:.1f} h on {m}" for h, m in zip(hours, MACHINES, strict=True))
        )


if __name__ == "__main__":
    main()
