"""Reading and checking a recorded trajectory: ``<stem>.h5`` + ``.json`` + ``.episodes.json``.

The three files are read and checked before any output is written, so a truncated or inconsistent
input fails with a message naming the file and the fault, and leaves nothing behind.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np


class TrajectoryError(ValueError):
    """The input trajectory is missing, unreadable or inconsistent."""


@dataclass(frozen=True)
class EpisodeSource:
    """One recorded episode: ``steps`` actions and the ``steps + 1`` env states around them."""

    episode_id: int
    seed: int
    reset_kwargs: dict
    states: dict  # ManiSkill env-state dict, every leaf an array of steps + 1 rows
    actions: np.ndarray  # (steps, action dim)
    success: bool
    spec: dict  # the EpisodeSpec dict
    stages: dict[str, list[bool]]  # per-step stage flags

    @property
    def steps(self) -> int:
        return len(self.actions)


@dataclass(frozen=True)
class Trajectory:
    """A trajectory file's env and its episodes."""

    path: Path
    env_id: str
    env_kwargs: dict
    control_mode: str
    episodes: tuple[EpisodeSource, ...] = ()

    @property
    def stem(self) -> str:
        return self.path.name.removesuffix(".h5")


def _read_json(path: Path, what: str):
    if not path.is_file():
        raise TrajectoryError(f"{path}: missing ({what})")
    try:
        return json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise TrajectoryError(f"{path}: unreadable {what} ({exc})") from exc


def _read_group(group: h5py.Group) -> dict:
    return {
        k: _read_group(v) if isinstance(v, h5py.Group) else np.asarray(v[:])
        for k, v in group.items()
    }


def _leaves(tree: dict):
    for value in tree.values():
        yield from _leaves(value) if isinstance(value, dict) else (value,)


def _episode(file: h5py.File, path: Path, entry: dict, extra: dict) -> EpisodeSource:
    name = f"traj_{entry['episode_id']}"
    where = f"{path}: {name}"
    if name not in file:
        raise TrajectoryError(f"{where} is missing")
    try:
        actions = np.asarray(file[name]["actions"][:])
        states = _read_group(file[name]["env_states"])
    except (KeyError, OSError) as exc:
        raise TrajectoryError(f"{where}: unreadable actions or env_states ({exc})") from exc
    steps = entry["elapsed_steps"]
    if actions.ndim != 2 or len(actions) != steps:
        raise TrajectoryError(
            f"{where}: actions of shape {actions.shape}, expected {steps} rows (elapsed_steps)"
        )
    lengths = {len(leaf) for leaf in _leaves(states)}
    if lengths != {steps + 1}:
        raise TrajectoryError(
            f"{where}: env_states of {sorted(lengths)} rows, expected {steps + 1}"
        )
    stages = extra["stages"]
    if any(len(flags) != steps for flags in stages.values()):
        raise TrajectoryError(f"{where}: its .episodes.json stage flags miss some of {steps} steps")
    return EpisodeSource(
        episode_id=entry["episode_id"],
        seed=extra["seed"],
        reset_kwargs=entry["reset_kwargs"],
        states=states,
        actions=actions,
        success=bool(entry.get("success", False)),
        spec=extra["spec"],
        stages=stages,
    )


def _require(path: Path, entries, keys: tuple[str, ...]) -> None:
    """``entries`` (read from ``path``) is a list of dicts that all hold ``keys``."""
    if not isinstance(entries, list):
        raise TrajectoryError(f"{path}: expected a list of episode entries")
    for k, entry in enumerate(entries):
        missing = [key for key in keys if not isinstance(entry, dict) or key not in entry]
        if missing:
            raise TrajectoryError(f"{path}: episode entry {k} lacks {', '.join(missing)}")


def load_trajectory(path: str | Path) -> Trajectory:
    """Read and check the trajectory ``path`` (``.h5``) with its ``.json`` and
    ``.episodes.json`` sidecars; raises :class:`TrajectoryError` naming the fault."""
    path = Path(path)
    if path.suffix != ".h5" or not path.is_file():
        raise TrajectoryError(f"{path}: no such trajectory (.h5) file")
    meta_path = path.with_name(f"{path.stem}.json")
    sidecar_path = path.with_name(f"{path.stem}.episodes.json")
    meta = _read_json(meta_path, "trajectory metadata")
    sidecar = _read_json(sidecar_path, "episode specs")
    try:
        env_id, env_kwargs = meta["env_info"]["env_id"], meta["env_info"]["env_kwargs"]
        entries = meta["episodes"]
    except (KeyError, TypeError) as exc:
        raise TrajectoryError(f"{meta_path}: no env_info or episodes ({exc!r})") from exc
    _require(meta_path, entries, ("episode_id", "elapsed_steps", "reset_kwargs"))
    _require(sidecar_path, sidecar, ("episode_id", "seed", "spec", "stages"))
    extras = {e["episode_id"]: e for e in sidecar}
    missing = [e["episode_id"] for e in entries if e["episode_id"] not in extras]
    if missing:
        raise TrajectoryError(f"{sidecar_path}: no entry for episodes {missing}")
    try:
        file = h5py.File(path, "r")
    except OSError as exc:
        raise TrajectoryError(f"{path}: truncated or corrupted HDF5 file ({exc})") from exc
    with file:
        episodes = tuple(_episode(file, path, e, extras[e["episode_id"]]) for e in entries)
    return Trajectory(
        path=path,
        env_id=env_id,
        env_kwargs=env_kwargs,
        control_mode=env_kwargs.get("control_mode", "pd_joint_pos"),
        episodes=episodes,
    )
