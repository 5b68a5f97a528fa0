"""Held-out evaluation sets: fixed episode specs per family, robot and split.

Evaluation seeds start at ``EVAL_SEED_BASE`` (one block of a million per split); training
data and demos use seeds below it, so the two never share an episode. The sets ship with
the package under ``tasks/episodes/<env id>/<robot>/<split>.jsonl``.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from importlib import resources
from pathlib import Path

from .episode import EpisodeSpec
from .validation import check_choice

EVAL_SEED_BASE = 1_000_000_000
EVAL_SPLITS = ("seen", "unseen_instance", "unseen_category")
EPISODES_PER_SET = 100


def eval_seed(split: str, index: int) -> int:
    return EVAL_SEED_BASE + EVAL_SPLITS.index(split) * 1_000_000 + index


def default_folder() -> Path:
    return Path(str(resources.files("instructmove_ms.tasks").joinpath("episodes")))


def set_path(env_id: str, robot: str, split: str, folder: Path | None = None) -> Path:
    return (folder or default_folder()) / env_id / robot / f"{split}.jsonl"


def write_set(path: Path, specs: list[EpisodeSpec]) -> Path:
    """Write ``specs`` as JSON lines, atomically."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    with os.fdopen(fd, "w") as f:
        f.writelines(spec.to_json() + "\n" for spec in specs)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)
    return path


def load_set(env_id: str, robot: str, split: str, folder: Path | None = None) -> list[EpisodeSpec]:
    """The stored held-out episodes of (env, robot, split)."""
    check_choice("split", split, EVAL_SPLITS)
    path = set_path(env_id, robot, split, folder)
    if not path.is_file():
        stored = sorted(
            p.relative_to(path.parents[2]).as_posix() for p in path.parents[2].glob("*/*/*.jsonl")
        )
        raise ValueError(f"no held-out set {env_id}/{robot}/{split}; stored: {stored}")
    return [EpisodeSpec.from_json(line) for line in path.read_text().splitlines() if line]


def generate_set(env, count: int = EPISODES_PER_SET) -> Iterator[EpisodeSpec]:
    """Sample ``count`` held-out specs of the split ``env`` was made for."""
    for index in range(count):
        yield env.unwrapped.sample_episode(eval_seed(env.unwrapped.split, index))
