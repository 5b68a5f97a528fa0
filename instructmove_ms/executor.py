"""Where the shards of a long job run: in this process, in local spawned processes, or as
tasks on a Ray cluster.

A job (demo generation, an export, an evaluation) cuts its work into shards and gives
:meth:`Workers.run` a picklable ``fn(shard, tick)`` (a module-level function, possibly in a
``functools.partial``); ``tick(item)`` reports progress from inside a shard and reaches the
driver's ``tick`` wherever the shard runs. Results come back to the driver in completion
order and the job merges them in a fixed order, so its output does not depend on where the
shards ran.

A shard whose worker process dies (killed, out of memory) is run again, up to ``retries``
times: local pools are rebuilt with the unfinished shards, Ray retries its tasks. An
exception raised by ``fn`` itself is the job's and stops it (local shards in flight finish
first, Ray's are cancelled). Shards write into the job's output folder (atomically, see
``files``), so on a cluster that folder must be on a file system every node sees at the
same path: :meth:`Workers.run` checks it with a probe task and says so when it is not.

Workers share the machine: each local worker process runs torch's intra-op pool (and the
OpenMP and BLAS pools it starts, through their environment variables) with its share of the
cores, one thread per worker on a machine of as many cores as workers, and a Ray task with its
``cpus``; without it, two workers on two cores each start two threads and oversubscribe them.
A job run in this process uses ``IN_PROCESS_THREADS`` for its duration (the fastest measured
for one env stepping and rendering; ``bench/scale_out.py``).

Ray is optional (``pip install 'instructmove-ms[ray]'``) and imported only for ``ray=``.
Ray's worker processes are reused across tasks, so state a shard builds once per process
(:func:`worker_state`, e.g. an env that renders) serves the later shards of the same job.
"""

from __future__ import annotations

import importlib.util
import multiprocessing as mp
import os
import queue as queues
import threading
import uuid
from collections import Counter
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .worker_log import mark

Tick = Callable[[Any], None]
ShardFn = Callable[[Any, Tick], Any]
RAY_INSTALL = "pip install 'instructmove-ms[ray]'"
_DONE = "__done__"  # ends a progress queue
#: Thread pools a worker's share of the cores sets, before they start.
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
#: torch's intra-op threads for a job run in this process.
IN_PROCESS_THREADS = 1


class WorkerLost(RuntimeError):
    """A shard's worker process died more often than the retries allow."""


def _ignore(_: Any) -> None:
    pass


@dataclass(frozen=True)
class Workers:
    """Where shards run: ``processes`` local processes (1: this process), or the Ray
    cluster at ``ray`` (``"auto"``, ``"HOST:PORT"``, or ``""`` for Ray's default: the
    ``RAY_ADDRESS`` cluster, one started on this machine, else a new local one). Each Ray
    shard asks for ``cpus`` CPUs and ``gpus`` GPUs; a shard whose worker dies is retried
    ``retries`` times."""

    processes: int = 1
    ray: str | None = None
    cpus: float = 1.0
    gpus: float = 0.0
    retries: int = 3

    def __post_init__(self) -> None:
        if self.processes < 1:
            raise ValueError(f"workers must be at least 1, got {self.processes}")
        if self.ray is not None and self.processes != 1:
            raise ValueError(
                f"--workers {self.processes} with --ray: the cluster's CPUs set how many "
                "shards run at once; give one of them"
            )
        if self.retries < 0:
            raise ValueError(f"retries must be at least 0, got {self.retries}")
        if self.ray is not None and importlib.util.find_spec("ray") is None:
            raise ValueError(f"--ray needs Ray, which is not installed: {RAY_INSTALL}")

    @classmethod
    def of(cls, workers: Workers | int) -> Workers:
        """``workers`` as is, or that many local processes."""
        return workers if isinstance(workers, Workers) else cls(processes=workers)

    def run(
        self, fn: ShardFn, shards: list, tick: Tick = _ignore, folder: Path | None = None
    ) -> Iterator[tuple[Any, Any]]:
        """Yields ``(shard, fn(shard, tick))`` for every shard in completion order; ``folder``
        is the output folder the shards write into (checked to be visible on a cluster)."""
        if not shards:
            return iter(())
        if self.ray is not None:
            return _run_ray(self, fn, shards, tick, folder)
        if self.in_process(len(shards)):
            return _run_here(fn, shards, tick)
        return _run_local(self, fn, shards, tick)

    def in_process(self, shards: int) -> bool:
        """Whether :meth:`run` runs that many shards in this process."""
        return self.ray is None and (self.processes == 1 or shards <= 1)


# -- state kept by a worker process for the shards of one job ---------------------------
_STATE: tuple[str, Any] | None = None


def job_token() -> str:
    """A name for one run of a job, for :func:`worker_state`."""
    return uuid.uuid4().hex


def worker_state(token: str, make: Callable[[], Any]) -> Any:
    """The object ``make()`` built in this process for the job ``token`` (built on first use;
    the previous job's object is closed)."""
    global _STATE
    if _STATE is None or _STATE[0] != token:
        release_state()
        _STATE = (token, make())
        mark("env")
    return _STATE[1]


def release_state() -> None:
    """Close this process's job object, if any."""
    global _STATE
    if _STATE is not None:
        state, _STATE = _STATE[1], None
        getattr(state, "close", lambda: None)()


def cores() -> int:
    """The CPU cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def share_of_cores(processes: int) -> int:
    """Threads each of ``processes`` workers gets: its share of the cores, at least one."""
    return max(1, cores() // processes)


@contextmanager
def torch_threads(threads: int) -> Iterator[None]:
    """torch's intra-op pool at ``threads`` inside the block."""
    import torch

    before = torch.get_num_threads()
    torch.set_num_threads(threads)
    try:
        yield
    finally:
        torch.set_num_threads(before)


@contextmanager
def children_threads(threads: int) -> Iterator[None]:
    """Processes started inside the block get ``threads`` in their OpenMP and BLAS pools
    (a variable the user set is kept)."""
    saved = {name: os.environ.get(name) for name in THREAD_VARIABLES}
    os.environ.update({name: str(threads) for name, v in saved.items() if v is None})
    try:
        yield
    finally:
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)


def _run_here(fn: ShardFn, shards: list, tick: Tick) -> Iterator[tuple[Any, Any]]:
    try:
        with torch_threads(IN_PROCESS_THREADS):
            for shard in shards:
                yield shard, fn(shard, tick)
    finally:
        release_state()


# -- local spawned processes (SAPIEN and torch do not survive a fork) -------------------
def set_worker_threads(threads: int) -> None:
    """A worker process's start: torch's intra-op pool at its share of the cores."""
    import torch

    torch.set_num_threads(threads)
    mark("start")


def _timed(fn: ShardFn, shard: Any, tick: Tick) -> Any:
    mark("shard_start")
    try:
        return fn(shard, tick)
    finally:
        mark("shard_end")


def _call(fn: ShardFn, shard: Any, sink: Any) -> Any:
    return _timed(fn, shard, sink.put)


def _drain(source: Any, tick: Tick, get: Callable[[Any], Any]) -> None:
    while (item := get(source)) != _DONE:
        tick(item)


def _run_local(
    workers: Workers, fn: ShardFn, shards: list, tick: Tick
) -> Iterator[tuple[Any, Any]]:
    """Shards in a pool of spawned processes; a pool broken by a dead worker is rebuilt with
    the unfinished shards (each counted as one try)."""
    ctx = mp.get_context("spawn")
    pending = dict(enumerate(shards))
    tries: Counter[int] = Counter()
    threads = share_of_cores(workers.processes)
    with ctx.Manager() as manager, children_threads(threads):
        mark("pool")
        sink = manager.Queue()
        listener = threading.Thread(target=_drain, args=(sink, tick, lambda q: q.get()))
        listener.start()
        try:
            while pending:
                pool = ProcessPoolExecutor(
                    min(workers.processes, len(pending)), ctx, set_worker_threads, (threads,)
                )
                try:
                    futures = {pool.submit(_call, fn, s, sink): i for i, s in pending.items()}
                    while futures:
                        finished, _ = wait(futures, return_when=FIRST_COMPLETED)
                        for future in finished:
                            i = futures.pop(future)
                            try:
                                result = future.result()
                            except BrokenProcessPool:
                                continue  # run again in a new pool
                            del pending[i]
                            yield shards[i], result
                finally:
                    pool.shutdown(wait=True, cancel_futures=True)
                for i in pending:
                    tries[i] += 1
                    if tries[i] > workers.retries:
                        raise WorkerLost(
                            f"shard {shards[i]!r}: its worker process died {tries[i]} times"
                        )
        finally:
            sink.put(_DONE)
            listener.join()


# -- Ray ---------------------------------------------------------------------------------
def _ray_shard(fn: ShardFn, shard: Any, sink: Any, threads: int) -> Any:
    set_worker_threads(threads)  # Ray sets OMP_NUM_THREADS to the task's CPUs itself
    return _timed(fn, shard, sink.put_nowait)


def _visible(path: str) -> bool:
    return os.path.exists(path)


def _check_shared(ray: Any, folder: Path) -> None:
    """A Ray task must see ``folder`` where the driver does."""
    folder.mkdir(parents=True, exist_ok=True)
    probe = folder.resolve() / f".probe-{job_token()}"
    probe.touch()
    try:
        seen = ray.get(ray.remote(num_cpus=0)(_visible).remote(str(probe)))
    finally:
        probe.unlink()
    if not seen:
        raise ValueError(
            f"the Ray workers cannot see {folder.resolve()}: the output folder must be on a "
            "file system every node of the cluster mounts at the same path"
        )


def _run_ray(
    workers: Workers, fn: ShardFn, shards: list, tick: Tick, folder: Path | None
) -> Iterator[tuple[Any, Any]]:
    """Shards as Ray tasks (retried by Ray when their worker dies), progress through a Ray
    queue actor."""
    import ray
    from ray.util.queue import Queue

    if not ray.is_initialized():
        ray.init(address=workers.ray or None, log_to_driver=False, logging_level="WARNING")
    if folder is not None:
        _check_shared(ray, folder)
    sink = Queue(actor_options={"num_cpus": 0})

    def get(q: Any) -> Any:
        while True:
            try:
                return q.get(timeout=0.5)
            except queues.Empty:
                continue

    listener = threading.Thread(target=_drain, args=(sink, tick, get))
    listener.start()
    task = ray.remote(num_cpus=workers.cpus, num_gpus=workers.gpus, max_retries=workers.retries)(
        _ray_shard
    )
    threads = max(1, int(workers.cpus))
    refs = {task.remote(fn, shard, sink, threads): shard for shard in shards}
    waiting = list(refs)
    try:
        while waiting:
            done, waiting = ray.wait(waiting, num_returns=1)
            try:
                result = ray.get(done[0])
            except ray.exceptions.WorkerCrashedError as exc:
                raise WorkerLost(f"shard {refs[done[0]]!r}: {exc}") from exc
            except ray.exceptions.RayTaskError as exc:
                raise exc.as_instanceof_cause() from None
            yield refs[done[0]], result
    finally:
        for ref in waiting:  # after a failure: the shards not finished
            ray.cancel(ref)
        sink.put(_DONE)
        listener.join()
        ray.kill(sink.actor)
