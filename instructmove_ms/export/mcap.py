"""Trajectory -> one MCAP per episode, rendered by parallel workers (local or Ray), resumable.

The input is read and checked first (nothing is written for a bad input); episodes whose
MCAP already exists are skipped; each file is written atomically.
"""

from __future__ import annotations

import dataclasses
import functools
import time
from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

from instructmove_ms.executor import Workers
from instructmove_ms.files import OutputLock, clean_stale

from .jobs import run_jobs
from .metadata import episode_metadata
from .replay import Replayer
from .source import EpisodeSource, Trajectory, load_trajectory
from .writer import write_episode


@dataclass(frozen=True)
class ExportSettings:
    """Camera resolution (None: the robot's default) and JPEG quality of the colour images."""

    width: int | None = None
    height: int | None = None
    jpeg_quality: int = 90

    def __post_init__(self) -> None:
        for name in ("width", "height"):
            value = getattr(self, name)
            if value is not None and value <= 0:
                raise ValueError(f"{name} must be positive, got {value}")
        if not 1 <= self.jpeg_quality <= 100:
            raise ValueError(f"jpeg_quality must be in 1..100, got {self.jpeg_quality}")


@dataclass
class ExportReport:
    written: list[Path] = field(default_factory=list)
    skipped: list[Path] = field(default_factory=list)
    bytes: int = 0
    seconds: float = 0.0


def episode_path(out_dir: Path, traj: Trajectory, episode_id: int) -> Path:
    return out_dir / f"{traj.stem}_ep{episode_id:05d}.mcap"


class EpisodeConverter:
    """Renders and writes episodes of one trajectory with a single env."""

    def __init__(self, traj: Trajectory, settings: ExportSettings):
        self.traj = dataclasses.replace(traj, episodes=())
        self.settings = settings
        self.replayer = Replayer(self.traj, settings.width, settings.height)

    def convert(self, ep: EpisodeSource, path: Path) -> int:
        """Write ``ep`` to ``path``; returns the file size in bytes."""
        rig, info, efforts = self.replayer.start(ep)
        metadata = episode_metadata(self.traj, ep, rig, info)
        frames = self.replayer.frames(ep, efforts)
        return write_episode(path, metadata, rig, ep.actions, frames, self.settings.jpeg_quality)

    def close(self) -> None:
        self.replayer.close()


def export_trajectory(
    traj_path: str | Path,
    out_dir: str | Path,
    workers: Workers | int = 1,
    settings: ExportSettings | None = None,
) -> ExportReport:
    """Convert every episode of the trajectory ``traj_path`` into ``out_dir`` (see the module
    docstring); ``workers``: local processes or a Ray cluster (``executor``)."""
    workers = Workers.of(workers)
    settings = settings or ExportSettings()
    traj = load_trajectory(traj_path)
    out = Path(out_dir)
    with OutputLock(out, "instructmove export mcap"):
        clean_stale(out)  # the files a killed run was writing
        report = _export(traj, out, workers, settings)
        clean_stale(out)  # what a worker killed mid-episode left (the episode ran again)
        return report


def _export(
    traj: Trajectory, out: Path, workers: Workers, settings: ExportSettings
) -> ExportReport:
    report = ExportReport()
    todo = []
    for ep in traj.episodes:
        path = episode_path(out, traj, ep.episode_id)
        if path.exists():
            report.skipped.append(path)
        else:
            todo.append((ep, path))
    start = time.perf_counter()
    with tqdm(
        total=len(traj.episodes), initial=len(report.skipped), desc=traj.stem, unit="episode"
    ) as bar:
        shell = dataclasses.replace(traj, episodes=())  # what each worker needs to pickle
        make = functools.partial(EpisodeConverter, shell, settings)
        for (_, path), size in run_jobs(make, todo, workers, out):
            report.written.append(path)
            report.bytes += size
            bar.update(1)
    report.written.sort()  # in episode order, however the workers finished
    report.seconds = time.perf_counter() - start
    return report
