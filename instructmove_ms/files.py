"""Writing output safely: atomic files, staging folders, append-only results and a lock per
output folder.

- Atomic writes: content goes to a hidden temporary (``.<name>.part-XXXX<suffix>``) in the
  same folder, renamed over the target when complete (``os.replace`` is atomic on one file
  system), so a run killed mid-write leaves the old file or none, never a torn one.
- Several files that belong together are assembled in a staging folder
  (``.staging-XXXX``) and moved into place.
- A long job holds ``OutputLock`` on its output folder: a second process on the same folder
  gets an error naming the first; the holder removes the temporaries a killed run left
  (``clean_stale``).
- Append-only JSON lines (``read_rows``) drop a torn last line, the one a killed run was
  writing, before anything is appended after it.
"""

from __future__ import annotations

import fcntl
import json
import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

PART = ".part-"  # in the names of atomic writes' temporaries
STAGING = ".staging-"  # prefix of staging folders
LOCK = ".instructmove.lock"


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """A temporary path to write ``path``'s content to (keeping its suffix, for writers that
    pick a format by it); renamed to ``path`` when the block ends without an error, removed
    otherwise. Missing parent folders are created."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}{PART}", suffix=path.suffix)
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically; returns ``path``."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def write_json(path: str | Path, data: Any, indent: int | None = 1) -> Path:
    """Write ``data`` as JSON to ``path`` atomically; returns ``path``."""
    return write_text(path, json.dumps(data, indent=indent))


@contextmanager
def staging(folder: str | Path) -> Iterator[Path]:
    """A fresh staging folder inside ``folder`` for files to move into place together
    (``os.replace``); removed with whatever is left in it when the block ends."""
    Path(folder).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=folder, prefix=STAGING) as tmp:
        yield Path(tmp)


def clean_stale(folder: str | Path) -> list[Path]:
    """Remove the staging folders and atomic-write temporaries below ``folder`` that a
    killed run left (call it holding the folder's ``OutputLock``); returns them."""
    folder = Path(folder)
    stale = [p for p in folder.rglob(f"{STAGING}*") if p.is_dir()]
    stale += [p for p in folder.rglob(f".*{PART}*") if p.is_file()]
    for path in stale:
        if path.is_dir():
            shutil.rmtree(path, ignore_errors=True)
        else:
            path.unlink(missing_ok=True)
    return stale


class OutputLock:
    """An exclusive lock on an output folder for one job at a time (``with OutputLock(out,
    "demos generate"):``); the second process gets a ``ValueError`` naming the first. The
    kernel releases it when the holder exits, however it exits."""

    def __init__(self, folder: str | Path, job: str) -> None:
        self.folder, self.job = Path(folder), job
        self._fd: int | None = None

    def __enter__(self) -> OutputLock:
        self.folder.mkdir(parents=True, exist_ok=True)
        path = self.folder / LOCK
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.read(fd, 200).decode(errors="replace").strip() or "another process"
            os.close(fd)
            raise ValueError(
                f"{self.folder} is in use by {holder}; wait for it to finish or choose "
                "another output folder"
            ) from None
        os.ftruncate(fd, 0)
        os.write(fd, f"process {os.getpid()} ({self.job})".encode())
        self._fd = fd
        return self

    def __exit__(self, *exc) -> None:
        if self._fd is not None:
            os.ftruncate(self._fd, 0)
            os.close(self._fd)  # closing releases the lock
            self._fd = None


def read_rows(path: str | Path) -> list[dict]:
    """The rows of an append-only JSON-lines file (none if it does not exist). A torn last
    line, one a killed run was writing, is cut off the file so that the next row starts a
    line of its own; a bad line before the last one is an error naming it."""
    path = Path(path)
    if not path.is_file():
        return []
    data = path.read_bytes()
    lines = data.split(b"\n")
    complete, tail = lines[:-1], lines[-1]  # tail: after the last newline (empty if none)
    rows = []
    for number, line in enumerate(complete, start=1):
        try:
            rows.append(json.loads(line))
        except json.JSONDecodeError as exc:
            if number < len(complete) or tail:
                raise ValueError(f"{path}:{number}: not a JSON row ({exc.msg})") from None
            tail = line  # the last complete line is torn too: drop it
            complete = complete[:-1]
    if tail:
        with path.open("r+b") as f:
            f.truncate(sum(len(line) + 1 for line in complete))
    return rows


def append_text(path: str | Path, text: str) -> None:
    """Append ``text`` to a log at ``path``, starting on a line of its own even after a
    torn entry."""
    path = Path(path)
    torn = path.is_file() and path.stat().st_size and not path.read_bytes().endswith(b"\n")
    with path.open("a") as f:
        f.write(("\n" if torn else "") + text)
