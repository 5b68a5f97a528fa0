"""The two LeRobot dataset layouts our exporter writes, and the ``meta/`` files of each.

- ``v3.0`` (lerobot >= 0.4: ``lerobot-train``, SmolVLA, pi0/pi0.5 and GR00T in LeRobot):
  ``data/chunk-000/file-000.parquet``, ``videos/<key>/chunk-000/file-000.mp4``,
  ``meta/episodes/chunk-000/file-000.parquet``, ``meta/tasks.parquet``, ``meta/stats.json``.
- ``v2.1`` (openpi's training, pinned to a 2025 lerobot; GR00T's "LeRobot v2" with
  ``meta/modality.json``; PyPI lerobot 0.3.x): ``data/chunk-000/episode_000000.parquet``,
  ``videos/chunk-000/<key>/episode_000000.mp4``, ``meta/episodes.jsonl``,
  ``meta/episodes_stats.jsonl``, ``meta/tasks.jsonl`` (and ``meta/stats.json``, which GR00T
  reads and lerobot 0.3 ignores).

Both hold one data file and one video file per camera per episode, episode ``e`` in chunk
``e // CHUNK_SIZE``; the files' contents are the same in both.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from instructmove_ms.files import atomic_path, write_json, write_text

CHUNK_SIZE = 1000
IMAGE = "observation.images.{}"
#: The statistics LeRobot v2.1 keeps per episode (v3.0 adds quantiles).
V21_STATS = ("min", "max", "mean", "std", "count")


@dataclass(frozen=True)
class Layout:
    """Where a dataset of one format keeps an episode's files."""

    version: str
    data_path: str
    video_path: str

    def chunk(self, episode: int) -> dict[str, int]:
        """The placeholders of ``data_path`` and ``video_path`` for ``episode``."""
        if self.version == "v3.0":
            return {"chunk_index": episode // CHUNK_SIZE, "file_index": episode % CHUNK_SIZE}
        return {"episode_chunk": episode // CHUNK_SIZE, "episode_index": episode}

    def data_file(self, episode: int) -> str:
        return self.data_path.format(**self.chunk(episode))

    def video_file(self, episode: int, key: str) -> str:
        return self.video_path.format(video_key=key, **self.chunk(episode))


LAYOUTS = {
    "v3.0": Layout(
        "v3.0",
        "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet",
        "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4",
    ),
    "v2.1": Layout(
        "v2.1",
        "data/chunk-{episode_chunk:03d}/episode_{episode_index:06d}.parquet",
        "videos/chunk-{episode_chunk:03d}/{video_key}/episode_{episode_index:06d}.mp4",
    ),
}
FORMATS = tuple(LAYOUTS)
DEFAULT_FORMAT = "v3.0"
EPISODES_V30 = "meta/episodes/chunk-000/file-000.parquet"


def layout(version: str) -> Layout:
    if version not in LAYOUTS:
        raise ValueError(f"LeRobot format {version!r} is not one we write; choose from {FORMATS}")
    return LAYOUTS[version]


def dataset_version(root: Path) -> str:
    """The ``codebase_version`` of the dataset at ``root``."""
    info = root / "meta" / "info.json"
    if not info.is_file():
        raise ValueError(f"{root}: no LeRobot dataset (meta/info.json missing)")
    return json.loads(info.read_text())["codebase_version"]


def read_tasks(root: Path) -> dict[int, str]:
    """task index -> task of the dataset at ``root``, in either format."""
    if dataset_version(root) == "v2.1":
        lines = (root / "meta" / "tasks.jsonl").read_text().splitlines()
        rows = [json.loads(line) for line in lines if line]
        return {int(r["task_index"]): str(r["task"]) for r in rows}
    tasks = pd.read_parquet(root / "meta" / "tasks.parquet")
    return {int(i): str(t) for t, i in zip(tasks.index, tasks["task_index"], strict=True)}


def _jsonl(rows: list[dict]) -> str:
    return "".join(json.dumps(row) + "\n" for row in rows)


@dataclass(frozen=True)
class EpisodeMeta:
    """What ``meta/`` says of one episode: its index, first frame, record (``lerobot``'s
    per-episode record: length, task, cameras, stats, our ``instructmove/`` fields)."""

    index: int
    start: int
    record: dict

    @property
    def ours(self) -> dict:
        return {k: v for k, v in self.record.items() if k.startswith("instructmove/")}


def write_episode_tables(
    out: Path, version: str, episodes: list[EpisodeMeta], tasks: list[str], fps: float
) -> None:
    """The episode, task and per-episode statistics tables of format ``version``."""
    if version == "v2.1":
        rows = [
            {"episode_index": e.index, "tasks": [e.record["task"]], "length": e.record["length"]}
            | e.ours
            for e in episodes
        ]
        write_text(out / "meta" / "episodes.jsonl", _jsonl(rows))
        stats = [
            {
                "episode_index": e.index,
                "stats": {
                    feature: {k: v for k, v in values.items() if k in V21_STATS}
                    for feature, values in e.record["stats"].items()
                },
            }
            for e in episodes
        ]
        write_text(out / "meta" / "episodes_stats.jsonl", _jsonl(stats))
        rows = [{"task_index": i, "task": task} for i, task in enumerate(tasks)]
        write_text(out / "meta" / "tasks.jsonl", _jsonl(rows))
        return
    v30 = LAYOUTS["v3.0"]
    rows = []
    for e in episodes:
        length, where = e.record["length"], v30.chunk(e.index)
        row = {
            "episode_index": e.index,
            "tasks": [e.record["task"]],
            "length": length,
            "data/chunk_index": where["chunk_index"],
            "data/file_index": where["file_index"],
            "dataset_from_index": e.start,
            "dataset_to_index": e.start + length,
        }
        for cam in e.record["cameras"]:
            key = IMAGE.format(cam)
            row.update(
                {
                    f"videos/{key}/chunk_index": where["chunk_index"],
                    f"videos/{key}/file_index": where["file_index"],
                    f"videos/{key}/from_timestamp": 0.0,
                    f"videos/{key}/to_timestamp": length / fps,
                }
            )
        row.update({"meta/episodes/chunk_index": 0, "meta/episodes/file_index": 0})
        for feature, stats in e.record["stats"].items():
            row.update({f"stats/{feature}/{k}": v for k, v in stats.items()})
        rows.append(row | e.ours)
    with atomic_path(out / EPISODES_V30) as tmp:
        pq.write_table(pa.Table.from_pylist(rows), tmp)
    with atomic_path(out / "meta" / "tasks.parquet") as tmp:
        pd.DataFrame({"task_index": range(len(tasks))}, index=pd.Index(tasks)).to_parquet(tmp)


def info(version: str, episodes: int, cameras: int) -> dict:
    """The format-specific fields of ``meta/info.json``."""
    where = layout(version)
    fields = {
        "codebase_version": version,
        "chunks_size": CHUNK_SIZE,
        "data_path": where.data_path,
        "video_path": where.video_path,
    }
    if version == "v2.1":
        fields |= {"total_chunks": -(-episodes // CHUNK_SIZE), "total_videos": episodes * cameras}
    else:
        fields |= {"data_files_size_in_mb": 100, "video_files_size_in_mb": 200}
    return fields


def write_info(out: Path, data: dict) -> None:
    """``meta/info.json``, written last: its presence says the dataset is complete."""
    write_json(out / "meta" / "info.json", data, indent=4)
