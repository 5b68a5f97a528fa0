"""Trajectories of one robot -> one LeRobot dataset (v3.0 or v2.1), for training a VLA on
our demos.

Every episode of every input trajectory (several families make a multi-task dataset) is
restored state by state and rendered by the shared replay renderer (``replay.Replayer``, the
MCAP export's too) at ``width`` x ``height`` (224 x 224 by default). Frame ``t`` pairs the
state before action ``t`` with that action: an episode of T actions gives T frames.

Layouts (``lerobot_formats``): one data file and one video file per camera per episode, in
LeRobot's v3.0 (the default; lerobot >= 0.4) or v2.1 (openpi, GR00T, lerobot 0.3) naming and
``meta/`` files. Every dataset also holds GR00T's ``meta/modality.json`` and a modality
config for its fine-tuning script (``groot``).

Features: ``observation.images.<camera>`` (RGB video, AV1 in yuv420p with a keyframe every
two frames, as LeRobot encodes), ``observation.state`` (the robot's configuration in its
joint-space policy interface: joints in rad, then one gripper value per arm in the
``pd_joint_pos`` action's units), ``action`` (the recorded ``pd_joint_pos`` action, the same
layout), ``task`` (the instruction; its index is also the column
``annotation.human.task_description``, as GR00T reads it); the episode table also holds our
link to the source: ``instructmove/source``, ``instructmove/episode_id``,
``instructmove/family``, ``/split``, ``/seed`` and ``/spec`` (the episode spec as JSON).

Resumable and atomic: each episode's files are written atomically and then its record in
``.instructmove/episodes/`` (the episode counts as done once that exists); a rerun renders
only the missing episodes and rewrites the ``meta/`` files, each atomically. The input is
read and checked whole before anything is written.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import imageio.v2 as imageio
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
from tqdm import tqdm

from instructmove_ms.executor import Workers
from instructmove_ms.files import OutputLock, atomic_path, clean_stale, write_json

from . import groot
from .jobs import run_jobs
from .lerobot_formats import (
    DEFAULT_FORMAT,
    IMAGE,
    EpisodeMeta,
    layout,
    write_episode_tables,
    write_info,
)
from .lerobot_formats import info as format_info
from .replay import Replayer
from .source import EpisodeSource, Trajectory, TrajectoryError, load_trajectory

DEFAULT_SIZE = 224
STATE, ACTION = "observation.state", "action"
#: The instruction's task index under the name GR00T's loader reads language from.
ANNOTATION = "annotation.human.task_description"
WORK = ".instructmove"  # our own records, beside the dataset
#: How LeRobot encodes its videos (libsvtav1, yuv420p, a keyframe every 2 frames, crf 30).
VIDEO = {"codec": "libsvtav1", "pix_fmt": "yuv420p", "g": 2, "crf": 30}
QUANTILES = (0.01, 0.10, 0.50, 0.90, 0.99)
INDEX_FEATURES = ("timestamp", "frame_index", "episode_index", "index", "task_index", ANNOTATION)


@dataclass(frozen=True)
class LeRobotSettings:
    """The dataset's name, its camera resolution and its LeRobot format (``FORMATS``)."""

    repo_id: str
    width: int = DEFAULT_SIZE
    height: int = DEFAULT_SIZE
    format: str = DEFAULT_FORMAT

    def __post_init__(self) -> None:
        if not self.repo_id or any(c.isspace() for c in self.repo_id):
            raise ValueError(f"repo_id must be a name without spaces, got {self.repo_id!r}")
        layout(self.format)  # a format we write, or a clear error
        for name in ("width", "height"):
            value = getattr(self, name)
            if value <= 0 or value % 2:
                raise ValueError(f"{name} must be a positive even number, got {value}")


@dataclass
class LeRobotReport:
    written: list[int] = field(default_factory=list)  # episode indices rendered now
    skipped: list[int] = field(default_factory=list)  # already there
    frames: int = 0
    bytes: int = 0
    seconds: float = 0.0


@dataclass(frozen=True)
class Entry:
    """Episode ``index`` of the dataset: episode ``source`` of trajectory ``traj``, its first
    frame's global ``start`` index and its ``task_index``."""

    index: int
    traj: int
    source: EpisodeSource
    start: int
    task_index: int


def episode_record(out: Path, index: int) -> Path:
    return out / WORK / "episodes" / f"{index:06d}.json"


def _stats(values: np.ndarray, axes: tuple[int, ...]) -> dict:
    """LeRobot's statistics of ``values`` over ``axes``: min, max, mean, std, count and the
    ``QUANTILES``, as lists."""
    quantiles = np.quantile(values, QUANTILES, axis=axes, keepdims=True)
    out = {
        "min": values.min(axis=axes, keepdims=True),
        "max": values.max(axis=axes, keepdims=True),
        "mean": values.mean(axis=axes, keepdims=True),
        "std": values.std(axis=axes, keepdims=True),
    }
    out.update({f"q{round(q * 100):02d}": v for q, v in zip(QUANTILES, quantiles, strict=True)})
    out = {k: np.squeeze(v, axis=0) for k, v in out.items()}  # the frame axis
    return {**{k: v.tolist() for k, v in out.items()}, "count": [int(values.shape[0])]}


def _image_stats(frames: np.ndarray) -> dict:
    """Per-channel statistics of (T, H, W, 3) uint8 frames, scaled to [0, 1] and shaped
    (3, 1, 1) as LeRobot keeps them (every other pixel, every frame)."""
    values = frames[:, ::2, ::2].astype(np.float32) / 255.0
    channels = np.moveaxis(values, -1, 1).reshape(len(frames), 3, -1, 1)  # (T, 3, pixels, 1)
    return _stats(channels, axes=(0, 2))


class EpisodeWriter:
    """Renders episodes and writes their data, videos and records (one env per trajectory,
    made when first needed)."""

    def __init__(self, trajs: tuple[Trajectory, ...], settings: LeRobotSettings, out: Path):
        self.trajs, self.settings, self.out = trajs, settings, out
        self.layout = layout(settings.format)
        self.replayers: dict[int, Replayer] = {}

    def _replayer(self, traj: int) -> Replayer:
        if traj not in self.replayers:
            s = self.settings
            self.replayers[traj] = Replayer(self.trajs[traj], s.width, s.height)
        return self.replayers[traj]

    def convert(self, entry: Entry) -> tuple[int, int]:
        """Write ``entry``'s episode; returns (frames, bytes)."""
        ep, replayer = entry.source, self._replayer(entry.traj)
        _, _, efforts = replayer.start(ep)
        interface = replayer.policy_interface()
        states, images = [], {}
        for frame in replayer.frames(ep, efforts, steps=ep.steps, depth=False):
            states.append(interface.state(frame.qpos))
            for name, camera in frame.cameras.items():
                images.setdefault(name, []).append(camera.rgb)
        fps = replayer.rig().control_freq
        n = ep.steps
        columns = {
            STATE: np.asarray(states, dtype=np.float32),
            ACTION: np.asarray(ep.actions, dtype=np.float32),
            "timestamp": (np.arange(n) / fps).astype(np.float32),
            "frame_index": np.arange(n, dtype=np.int64),
            "episode_index": np.full(n, entry.index, dtype=np.int64),
            "index": entry.start + np.arange(n, dtype=np.int64),
            "task_index": np.full(n, entry.task_index, dtype=np.int64),
            ANNOTATION: np.full(n, entry.task_index, dtype=np.int64),
        }
        size = self._write_data(entry, columns)
        stats = {k: _stats(np.asarray(v).reshape(n, -1), axes=(0,)) for k, v in columns.items()}
        for name, frames in images.items():
            video = np.stack(frames)
            size += self._write_video(entry, IMAGE.format(name), video, fps)
            stats[IMAGE.format(name)] = _image_stats(video)
        spec = ep.spec
        write_json(
            episode_record(self.out, entry.index),
            {
                "episode_index": entry.index,
                "length": n,
                "task": spec["instruction"],
                "fps": fps,
                "names": list(interface.names),
                "parts": {name: list(span) for name, span in interface.parts().items()},
                "cameras": sorted(images),
                "stats": stats,
                "instructmove/source": self.trajs[entry.traj].path.name,
                "instructmove/episode_id": ep.episode_id,
                "instructmove/family": spec["family"],
                "instructmove/split": spec["split"],
                "instructmove/seed": ep.seed,
                "instructmove/spec": json.dumps(spec, sort_keys=True),
            },
        )
        return n, size

    def _write_data(self, entry: Entry, columns: dict[str, np.ndarray]) -> int:
        arrays = {}
        for name, values in columns.items():
            if values.ndim == 2:
                flat = pa.array(values.reshape(-1), type=pa.float32())
                arrays[name] = pa.FixedSizeListArray.from_arrays(flat, values.shape[1])
            else:
                arrays[name] = pa.array(values)
        path = self.out / self.layout.data_file(entry.index)
        with atomic_path(path) as tmp:
            pq.write_table(pa.table(arrays), tmp)
        return path.stat().st_size

    def _write_video(self, entry: Entry, key: str, frames: np.ndarray, fps: float) -> int:
        os.environ.setdefault("SVT_LOG", "1")  # the AV1 encoder's banner: errors only
        path = self.out / self.layout.video_file(entry.index, key)
        params = ["-g", str(VIDEO["g"]), "-crf", str(VIDEO["crf"]), "-preset", "8"]
        with (
            atomic_path(path) as tmp,
            imageio.get_writer(
                tmp,
                format="FFMPEG",
                fps=fps,
                codec=VIDEO["codec"],
                pixelformat=VIDEO["pix_fmt"],
                quality=None,
                macro_block_size=1,
                ffmpeg_params=params,
                ffmpeg_log_level="error",
            ) as writer,
        ):
            for frame in frames:
                writer.append_data(frame)
        return path.stat().st_size

    def close(self) -> None:
        for replayer in self.replayers.values():
            replayer.close()


def _check_sources(trajs: list[Trajectory]) -> None:
    """One robot, joint-position control and a control rate for every input."""
    robots = {t.env_kwargs.get("robot_uids") for t in trajs}
    if len(robots) != 1:
        raise TrajectoryError(f"one dataset holds one robot's demos; the inputs have {robots}")
    for t in trajs:
        if t.control_mode != "pd_joint_pos":
            raise TrajectoryError(
                f"{t.path}: recorded with {t.control_mode!r}; the dataset's actions are the "
                "pd_joint_pos policy interface"
            )


def _entries(trajs: list[Trajectory]) -> tuple[list[Entry], list[str]]:
    """Every episode of ``trajs`` in order with its global frame offset, and the tasks."""
    entries, tasks, start = [], {}, 0
    for t, traj in enumerate(trajs):
        for ep in traj.episodes:
            task = tasks.setdefault(ep.spec["instruction"], len(tasks))
            entries.append(Entry(len(entries), t, ep, start, task))
            start += ep.steps
    return entries, list(tasks)


def export_lerobot(
    traj_paths: list[str | Path],
    out_dir: str | Path,
    settings: LeRobotSettings,
    workers: Workers | int = 1,
) -> LeRobotReport:
    """Write the episodes of ``traj_paths`` into the LeRobot dataset ``out_dir`` (see the
    module docstring); ``workers``: local processes or a Ray cluster (``executor``)."""
    workers = Workers.of(workers)
    if not traj_paths:
        raise ValueError("give at least one trajectory (--traj)")
    trajs = [load_trajectory(p) for p in traj_paths]  # every input checked before writing
    _check_sources(trajs)
    out = Path(out_dir)
    with OutputLock(out, "instructmove export lerobot"):
        clean_stale(out)
        report = _export(trajs, out, settings, workers)
        clean_stale(out)  # what a worker killed mid-episode left (the episode ran again)
        return report


def _export(
    trajs: list[Trajectory], out: Path, settings: LeRobotSettings, workers: Workers
) -> LeRobotReport:
    entries, tasks = _entries(trajs)
    params = {
        "repo_id": settings.repo_id,
        "width": settings.width,
        "height": settings.height,
        "format": settings.format,
        "sources": [{"file": t.path.name, "episodes": len(t.episodes)} for t in trajs],
    }
    stamp = out / WORK / "export.json"
    if stamp.is_file() and json.loads(stamp.read_text()) != params:
        raise ValueError(
            f"{out} holds a dataset exported with {json.loads(stamp.read_text())}; "
            "resume it with the same inputs and settings or choose another folder"
        )
    write_json(stamp, params)
    report = LeRobotReport()
    todo = []
    for entry in entries:
        if episode_record(out, entry.index).is_file():
            report.skipped.append(entry.index)
        else:
            todo.append((entry,))
    start = time.perf_counter()
    shells = tuple(dataclasses.replace(t, episodes=()) for t in trajs)
    make = functools.partial(EpisodeWriter, shells, settings, out)
    done = len(report.skipped)
    with tqdm(total=len(entries), initial=done, desc=out.name, unit="episode") as bar:
        for (entry,), (frames, size) in run_jobs(make, todo, workers, out):
            report.written.append(entry.index)
            report.frames += frames
            report.bytes += size
            bar.update(1)
    report.written.sort()  # in episode order, however the workers finished
    report.seconds = time.perf_counter() - start
    _finalize(out, trajs, entries, tasks, settings)
    return report


def _features(record: dict, settings: LeRobotSettings) -> dict:
    """The ``features`` of ``meta/info.json`` (from an episode's record)."""
    names, fps = record["names"], record["fps"]
    video_info = {
        "video.height": settings.height,
        "video.width": settings.width,
        "video.codec": "av1",
        "video.pix_fmt": VIDEO["pix_fmt"],
        "video.is_depth_map": False,
        "video.fps": fps,
        "video.channels": 3,
        "has_audio": False,
    }
    features = {
        IMAGE.format(cam): {
            "dtype": "video",
            "shape": [settings.height, settings.width, 3],
            "names": ["height", "width", "channels"],
            "info": video_info,
        }
        for cam in record["cameras"]
    }
    for key in (STATE, ACTION):
        features[key] = {"dtype": "float32", "shape": [len(names)], "names": names}
    features["timestamp"] = {"dtype": "float32", "shape": [1], "names": None}
    for key in INDEX_FEATURES[1:]:
        features[key] = {"dtype": "int64", "shape": [1], "names": None}
    return features


def _finalize(
    out: Path, trajs: list[Trajectory], entries: list[Entry], tasks: list[str], settings
) -> None:
    """Write ``meta/``: the episode and task tables, the statistics, GR00T's modality files
    and, last, the info."""
    records = [json.loads(episode_record(out, e.index).read_text()) for e in entries]
    fps = records[0]["fps"]
    episodes = [EpisodeMeta(e.index, e.start, r) for e, r in zip(entries, records, strict=True)]
    write_episode_tables(out, settings.format, episodes, tasks, fps)
    write_json(out / "meta" / "stats.json", _aggregate([r["stats"] for r in records]), indent=2)
    groot.write_modality(out, records[0], settings)
    data = {
        "codebase_version": settings.format,
        "robot_type": trajs[0].env_kwargs.get("robot_uids"),
        "total_episodes": len(entries),
        "total_frames": sum(r["length"] for r in records),
        "total_tasks": len(tasks),
        "fps": fps,
        "splits": {"train": f"0:{len(entries)}"},
    }
    data |= format_info(settings.format, len(entries), len(records[0]["cameras"]))
    data["features"] = _features(records[0], settings)
    write_info(out, data)


def _aggregate(episodes: list[dict]) -> dict:
    """The dataset's statistics from its episodes' (LeRobot's aggregation: pooled mean and
    variance, weighted mean of the quantiles)."""
    out = {}
    for feature in episodes[0]:
        stacked = {
            key: np.stack([np.asarray(e[feature][key], dtype=np.float64) for e in episodes])
            for key in episodes[0][feature]
        }
        counts = stacked.pop("count")[:, 0]
        w = (counts / counts.sum()).reshape(-1, *([1] * (stacked["mean"].ndim - 1)))
        mean = (stacked["mean"] * w).sum(axis=0)
        var = ((stacked["std"] ** 2 + (stacked["mean"] - mean) ** 2) * w).sum(axis=0)
        stats = {"min": stacked["min"].min(axis=0), "max": stacked["max"].max(axis=0)}
        stats.update(mean=mean, std=np.sqrt(var))
        for key in (k for k in stacked if k.startswith("q")):
            stats[key] = (stacked[key] * w).sum(axis=0)
        out[feature] = {**{k: v.tolist() for k, v in stats.items()}, "count": [int(counts.sum())]}
    return out
