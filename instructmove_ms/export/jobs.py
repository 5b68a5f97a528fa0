"""Episodes converted as shards of :class:`~instructmove_ms.executor.Workers`: each worker
process makes one converter (an env that renders) for all the episodes it gets."""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, Protocol

from instructmove_ms.executor import Tick, Workers, job_token, worker_state


class Converter(Protocol):
    def convert(self, *job: Any) -> Any: ...

    def close(self) -> None: ...


def _convert(token: str, make: Callable[[], Converter], job: tuple, tick: Tick) -> Any:
    return worker_state(token, make).convert(*job)


def run_jobs(
    make: Callable[[], Converter], jobs: list[tuple], workers: Workers, out: Path
) -> Iterator[tuple]:
    """Yields (job, result) of ``converter.convert(*job)`` for every job, in completion order,
    each worker making its converter once with ``make`` (a picklable callable); the
    converters write into ``out``."""
    return workers.run(functools.partial(_convert, job_token(), make), jobs, folder=out)
