"""Scale-out: demos/min and evaluation episodes/h with 1 and 2 local worker processes and
with Ray on 2 CPUs, as ratios to 1 worker measured in the same run (the speed-up; divided
by the CPUs used, the scaling efficiency), the driver's overhead per shard, and the wall time
those figures project for 10,000 demos and for a full evaluation sweep (4 families x 3
splits x 100 episodes x 5 conditions) on N machines of this size.

Demos: PickCategory with the Franka, shards of 2 demos. Evaluation: the random policy with
rgb observations from the default cameras (the simulation and rendering a served VLA gets,
without its inference), one episode per shard. Overhead: empty shards through each executor.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import ray

import instructmove_ms  # noqa: F401
from instructmove_ms.demos.generate import generate
from instructmove_ms.evaluation import evaluate
from instructmove_ms.executor import Workers
from instructmove_ms.policies import RandomPolicy

TASK, ROBOT = "PickCategory-InstructMove", "franka"
DEMOS_WANTED, SWEEP_EPISODES = 10_000, 4 * 3 * 100 * 5
MACHINES = (1, 4, 16)


def _demos_per_min(workers: Workers, n: int) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        generate(TASK, ROBOT, n, Path(tmp), workers=workers, shard_size=2)
        return n * 60 / (time.perf_counter() - start)


def _episodes_per_hour(workers: Workers, n: int) -> float:
    policy = RandomPolicy(obs_mode="rgb")
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        evaluate(policy, TASK, "seen", Path(tmp), ROBOT, episodes=n, workers=workers)
        return n * 3600 / (time.perf_counter() - start)


def _empty(shard: int, tick) -> int:
    return shard


def _overhead_ms(workers: Workers, shards: int) -> float:
    """Milliseconds per empty shard, the executor's start-up excluded (a first round)."""
    list(workers.run(_empty, list(range(4))))
    start = time.perf_counter()
    list(workers.run(_empty, list(range(shards))))
    return (time.perf_counter() - start) * 1000 / shards


def _hours(units: float, per_hour_one: float, efficiency: float, cpus: int) -> float:
    return units / (per_hour_one * efficiency * cpus)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--demos", type=int, default=8)
    parser.add_argument("--episodes", type=int, default=6)
    args = parser.parse_args()
    cpus = os.cpu_count() or 1
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False, logging_level="ERROR")
    setups = (("1 worker", Workers(1), 1), ("2 workers", Workers(2), 2))
    setups += (("Ray, 2 CPUs", Workers(ray=""), 2),)  # the cluster started above
    speedups, one = {}, {}
    for job, measure, n, unit in (
        ("demos", _demos_per_min, args.demos, "demos/min"),
        ("eval", _episodes_per_hour, args.episodes, "episodes/h"),
    ):
        for name, workers, used in setups:
            rate = measure(workers, n)
            one.setdefault(job, rate)
            speedups[job, name] = rate / one[job]
            print(
                f"{job:5s} {name:12s}: {rate:8.1f} {unit}; speed-up {rate / one[job]:.2f}x, "
                f"efficiency {rate / one[job] / used:.2f}"
            )
    for name, workers, _ in setups:
        print(f"driver overhead per shard, {name:12s}: {_overhead_ms(workers, 200):.1f} ms")
    ray.shutdown()
    for job, units, per_hour in (
        ("demos", DEMOS_WANTED, one["demos"] * 60),
        ("eval", SWEEP_EPISODES, one["eval"]),
    ):
        efficiency = speedups[job, "Ray, 2 CPUs"] / 2
        projected = ", ".join(
            f"{m} x {cpus} CPUs {_hours(units, per_hour, efficiency, m * cpus):.1f} h"
            for m in MACHINES
        )
        what = f"{units} demos" if job == "demos" else f"an eval sweep of {units} episodes"
        print(f"projected for {what} (Ray efficiency {efficiency:.2f}): {projected}")


if __name__ == "__main__":
    main()
