"""Scale-out: demos and evaluation episodes with 1 and 2 local worker processes and with Ray
on 2 CPUs, as ratios to 1 worker measured in the same run (the speed-up; divided by the
CPUs used, the scaling efficiency), the driver's overhead per shard, and the wall time the
measured costs project for 10,000 demos and for a full evaluation sweep (4 families x 3
splits x 100 episodes x 5 conditions) on N machines of this size.

One worker runs a short and a twice as long job: their difference gives the cost per demo
(episode) once a worker has started, the rest its start-up; the projection is start-up plus
that cost spread over N machines' CPUs at the Ray efficiency measured here. Demos:
PickCategory with the Franka, shards of 4. Evaluation: the random policy with rgb
observations from the default cameras (the simulation and rendering a served VLA gets,
without its inference), one episode per shard. Overhead: empty shards.

Threads: each worker runs torch with its share of the cores (``executor``); the evaluation
is also run as before that, every worker (and the one-process run) with torch's default
pool, to show what sharing the cores gains.

Worker profile (``--profile-only`` runs just this): each job once more on 2 workers with the
worker log on (``instructmove_ms.worker_log``): per worker its start-up (interpreter up,
imports until its first shard, the asset library, the first env), its busy time, and the
straggler's tail (how long the first worker to finish waited for the last); then the job
size from which W workers run at 80% efficiency, given the start-up F each pays and the cost c
per unit once started: T_W = F + n c / W, so n >= (4 W - 5) F / c."""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import ray
import torch

import instructmove_ms  # noqa: F401
from instructmove_ms import executor, worker_log
from instructmove_ms.demos.generate import generate
from instructmove_ms.evaluation import evaluate
from instructmove_ms.executor import Workers
from instructmove_ms.policies import RandomPolicy

TASK, ROBOT = "PickCategory-InstructMove", "franka"
DEMOS_WANTED, SWEEP_EPISODES = 10_000, 4 * 3 * 100 * 5
MACHINES = (1, 4, 16)


def _demos_seconds(workers: Workers, n: int) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        generate(TASK, ROBOT, n, Path(tmp), workers=workers, shard_size=4)
        return time.perf_counter() - start


def _eval_seconds(workers: Workers, n: int) -> float:
    policy = RandomPolicy(obs_mode="rgb")
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        evaluate(policy, TASK, "seen", Path(tmp), ROBOT, episodes=n, workers=workers)
        return time.perf_counter() - start


@contextmanager
def default_threads() -> Iterator[None]:
    """Workers as before they shared the cores: torch's default pool in every process."""
    saved = executor.share_of_cores, executor.IN_PROCESS_THREADS
    executor.share_of_cores = lambda processes: executor.cores()
    executor.IN_PROCESS_THREADS = torch.get_num_threads()
    try:
        yield
    finally:
        executor.share_of_cores, executor.IN_PROCESS_THREADS = saved


def _empty(shard: int, tick) -> int:
    return shard


def _overhead_ms(workers: Workers, shards: int) -> float:
    """The driver's milliseconds per empty shard: the marginal cost of ``shards`` more."""

    def seconds(count: int) -> float:
        start = time.perf_counter()
        list(workers.run(_empty, list(range(count))))
        return time.perf_counter() - start

    return (seconds(2 * shards) - seconds(shards)) * 1000 / shards


def _profile(job: str, measure, n: int, workers: int = 2) -> float:
    """``measure`` of ``n`` units on ``workers`` local workers with the worker log on: prints
    each worker's start-up, busy time and the straggler's tail; returns the mean start-up."""
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "workers.jsonl"
        os.environ[worker_log.VARIABLE] = str(log)
        try:
            measure(Workers(workers), n)
            events = worker_log.read(str(log))
        finally:
            del os.environ[worker_log.VARIABLE]
    pool = next(e["t"] for e in events if e["event"] == "pool")
    pids = sorted({e["pid"] for e in events if e["event"] == "start"})
    end = max(e["t"] for e in events if e["event"] == "shard_end")
    finished, startups = [], []
    for k, pid in enumerate(pids, 1):
        mine = [e for e in events if e["pid"] == pid]
        first = {e["event"]: e["t"] for e in reversed(mine)}  # each event's first time
        starts = [e["t"] for e in mine if e["event"] == "shard_start"]
        ends = [e["t"] for e in mine if e["event"] == "shard_end"]
        busy = sum(b - a for a, b in zip(starts, ends, strict=True))
        finished.append(max(ends))
        steps = [("up", pool, first["start"]), ("imports", first["start"], starts[0])]
        steps += [("library", starts[0], first.get("library", starts[0]))]
        steps += [("first env", first.get("library", starts[0]), first.get("env", starts[0]))]
        startups.append(first.get("env", starts[0]) - pool)
        parts = ", ".join(f"{name} {b - a:.1f} s" for name, a, b in steps)
        print(
            f"{job:5s} worker {k}: start-up {startups[-1]:.1f} s ({parts}); busy {busy:.1f} s "
            f"of {end - pool:.1f} s, {len(starts)} shards; done {end - max(ends):.1f} s before "
            "the last"
        )
    print(
        f"{job:5s} straggler tail: {end - min(finished):.1f} s (the first worker idle while "
        f"the last finished); mean start-up {statistics.mean(startups):.1f} s per worker"
    )
    return statistics.mean(startups)


def _scaling_size(job: str, fixed: float, marginal: float, unit: str) -> None:
    """The job size from which W spawned workers, each paying start-up ``fixed`` (measured
    by the worker log), run at 80% efficiency with ``marginal`` seconds per unit:
    n >= (4 W - 5) F / c."""
    sizes = ", ".join(
        f"{w} workers {max(1, round((4 * w - 5) * fixed / marginal))}" for w in (2, 8, 16)
    )
    print(f"{job:5s} {unit}s for 80% efficiency: {sizes}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--demos", type=int, default=12, help="demos of the short job")
    parser.add_argument("--episodes", type=int, default=3, help="episodes of the short job")
    parser.add_argument("--profile-only", action="store_true", help="just the worker profile")
    args = parser.parse_args()
    cpus = os.cpu_count() or 1
    jobs = (
        ("demos", _demos_seconds, args.demos, "demo", DEMOS_WANTED),
        ("eval", _eval_seconds, args.episodes, "episode", SWEEP_EPISODES),
    )
    one_worker = {}
    for job, measure, n, unit, _ in jobs:
        short, long = measure(Workers(1), n), measure(Workers(1), 2 * n)
        marginal = (long - short) / n  # seconds per unit once started
        fixed = max(0.0, short - n * marginal)  # start-up: imports, env, renderer
        one_worker[job] = long, marginal, fixed
        print(
            f"{job:5s} 1 worker   : {2 * n} {unit}s in {long:.0f} s ({2 * n * 3600 / long:.0f}"
            f"/h); {marginal:.1f} s per {unit} once started, {fixed:.0f} s start-up"
        )
        _scaling_size(job, _profile(job, measure, 2 * n), marginal, unit)
    if args.profile_only:
        return
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False, logging_level="ERROR")
    setups = (("2 workers", Workers(2), 2), ("Ray, 2 CPUs", Workers(ray=""), 2))
    for job, measure, n, unit, units in jobs:
        long, marginal, fixed = one_worker[job]
        efficiency = {}
        for name, workers, used in setups:
            seconds = measure(workers, 2 * n)
            efficiency[name] = long / seconds / used
            print(
                f"{job:5s} {name:11s}: {2 * n} {unit}s in {seconds:.0f} s; speed-up "
                f"{long / seconds:.2f}x, efficiency {efficiency[name]:.2f}"
            )
        projected = ", ".join(
            f"{m} x {cpus} CPUs "
            f"{(fixed + units * marginal / (m * cpus * efficiency['Ray, 2 CPUs'])) / 3600:.1f} h"
            for m in MACHINES
        )
        print(f"projected for {units} {unit}s with Ray: {projected}")
        if job == "eval":
            with default_threads():
                before = {k: measure(Workers(k), 2 * n) for k in (1, 2)}
            print(
                f"eval  torch's default threads (before): 1 worker {before[1]:.0f} s, 2 workers "
                f"{before[2]:.0f} s, speed-up {before[1] / before[2]:.2f}x; with shared cores "
                f"1 worker {long:.0f} s ({before[1] / long:.2f}x faster)"
            )
    for name, workers in (("2 workers", Workers(2)), ("Ray", Workers(ray=""))):
        print(f"driver overhead per shard, {name}: {_overhead_ms(workers, 200):.2f} ms")
    ray.shutdown()


if __name__ == "__main__":
    main()
