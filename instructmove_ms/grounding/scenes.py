"""The scenes a grounding model learns from and is judged on, rendered once and kept.

Training scenes are composed from training seeds on every robot of every family (never a
stored set's seeds); judged scenes are the stored sets of a version. Each lands in its own
shard under a cache folder, so an interrupted run resumes where it stopped and a rerun
renders only what changed (a rewritten set, another sampler).
"""

from __future__ import annotations

from pathlib import Path

from tqdm import tqdm

from ..heldout import load_set
from ..readers.material import SceneRenderer, stored_sets
from ..sampler import SAMPLER
from ..tasks import TASKS
from .crops import Decisions, digest, rendered

#: Training scenes per shard.
SHARD = 50


def _kept(folder: Path, stem: str, specs, renderer: SceneRenderer, env_id: str) -> Decisions:
    """The decisions of ``specs``, from their shard under ``folder`` (named by ``stem`` and
    the episodes' digest) or rendered into it."""
    source = digest(specs)
    path = Path(folder) / f"{stem}-{source[:16]}.npz"
    found = Decisions.load(path, source)
    if found is None:
        found = rendered(renderer, env_id, specs)
        found.save(path, source)
    return found


def stored(
    cache: Path,
    version: int | None = None,
    folder: Path | None = None,
    progress: bool = True,
    families: tuple[str, ...] | None = None,
) -> Decisions:
    """Every decision of the stored sets of ``version`` (or under ``folder``; ``families``:
    of those env ids only), rendered."""
    renderer = SceneRenderer()
    sets = [s for s in stored_sets(version) if families is None or s[0] in families]
    try:
        parts = []
        shown = tqdm(sets, desc="stored sets", disable=not progress)
        for env_id, robot, split in shown:
            specs = load_set(env_id, robot, split, folder, version)
            where = Path(cache) / "sets" / env_id / robot
            parts.append(_kept(where, split, specs, renderer, env_id))
        return Decisions.join(parts)
    finally:
        renderer.close()


def training(
    cache: Path,
    scenes: int,
    sampler: int = SAMPLER,
    progress: bool = True,
    families: tuple[str, ...] | None = None,
    alternatives: bool = False,
) -> Decisions:
    """Every decision of the first ``scenes`` training seeds of each family (``families``:
    those env ids only) on each of its robots, as ``sampler`` draws them, rendered; with
    ``alternatives``, each also under its ``alternative_target`` instruction (the same
    pictures, words that name another goal: what only a reader can learn from)."""
    if scenes < 1:
        raise ValueError(f"training scenes must be 1 or more, got {scenes}")
    renderer = SceneRenderer(split="train", sampler=sampler)
    jobs = [
        (env_id, robot, start)
        for env_id, task in TASKS.items()
        if families is None or env_id in families
        for robot in task.supported_robots
        for start in range(0, scenes, SHARD)
    ]
    try:
        parts = []
        for env_id, robot, start in tqdm(jobs, desc="training scenes", disable=not progress):
            env = renderer.env(env_id, robot).unwrapped
            specs = [env.sample_episode(s) for s in range(start, min(start + SHARD, scenes))]
            where = Path(cache) / f"train-sampler{sampler}" / env_id / robot
            part = _kept(where, f"{start:06d}", specs, renderer, env_id)
            parts.append(part)
            if alternatives:
                aimed = [env.under_condition(s, "alternative_target") for s in specs]
                parts.append(part.instructed(aimed))
        return Decisions.join(parts)
    finally:
        renderer.close()
