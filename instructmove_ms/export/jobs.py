"""Episodes converted in this process or in spawned worker processes, each holding one
converter (an env that renders) for all the episodes it gets."""

from __future__ import annotations

import multiprocessing
from collections.abc import Callable, Iterator
from concurrent.futures import ProcessPoolExecutor, as_completed
from typing import Any, Protocol


class Converter(Protocol):
    def convert(self, *job: Any) -> Any: ...

    def close(self) -> None: ...


_WORKER: Converter | None = None


def _init_worker(make: Callable[[], Converter]) -> None:
    global _WORKER
    _WORKER = make()


def _convert_in_worker(job: tuple) -> Any:
    assert _WORKER is not None, "worker not initialised"
    return _WORKER.convert(*job)


def run_jobs(make: Callable[[], Converter], jobs: list[tuple], workers: int) -> Iterator[tuple]:
    """Yields (job, result) of ``converter.convert(*job)`` for every job, in completion order,
    with ``workers`` spawned processes (SAPIEN and torch do not survive a fork), each making
    its converter once with ``make`` (a picklable callable); in this process for one."""
    if not jobs:
        return
    if workers == 1 or len(jobs) == 1:
        converter = make()
        try:
            for job in jobs:
                yield job, converter.convert(*job)
        finally:
            converter.close()
        return
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(
        min(workers, len(jobs)), context, initializer=_init_worker, initargs=(make,)
    ) as pool:
        futures = {pool.submit(_convert_in_worker, job): job for job in jobs}
        try:
            for future in as_completed(futures):
                yield futures[future], future.result()
        finally:
            for future in futures:
                future.cancel()
