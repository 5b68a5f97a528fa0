"""Where a worker's time goes: with ``INSTRUCTMOVE_WORKER_LOG`` naming a file, each process of
a job appends one JSON line per event (``pid``, ``event``, wall time ``t``); without it,
nothing is written. ``bench/scale_out.py`` reads it.

Events: ``pool`` (the driver starts a pool of local worker processes), ``start`` (a worker's
initializer runs: its interpreter is up), ``shard_start`` / ``shard_end`` (each shard),
``library`` (the process has loaded its asset snapshot), ``env`` (it has built the job's env,
``executor.worker_state``).
"""

from __future__ import annotations

import json
import os
import time

VARIABLE = "INSTRUCTMOVE_WORKER_LOG"


def mark(event: str) -> None:
    """Log ``event`` of this process, where the log is on."""
    path = os.environ.get(VARIABLE)
    if path:
        line = json.dumps({"pid": os.getpid(), "event": event, "t": time.time()}) + "\n"
        with open(path, "a", encoding="utf-8") as f:  # one short append: lines stay whole
            f.write(line)


def read(path: str) -> list[dict]:
    """The events of a log, in the order written."""
    with open(path, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]
