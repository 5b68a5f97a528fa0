"""The scenes an audit judges: the stored sets of a version; training scenes composed from
training seeds the way demos are; and fresh evaluation scenes, composed from evaluation
seeds no stored set reaches, which judge the sampler itself on as many scenes as asked.
Composed scenes are not rendered: the figures a render adds (what the cameras see) are the
stored sets' alone."""

from __future__ import annotations

from pathlib import Path

from tqdm import tqdm

from ..assets import load_snapshot
from ..episode import EpisodeSpec
from ..heldout import EPISODES_PER_SET, SEEDS_PER_EPISODE, load_set
from ..sampler import SAMPLER
from ..splits import EVAL_SPLITS, eval_seed
from ..tasks import TASKS
from .choices import Choice, choices_of


def stored_specs(version: int | None = None, folder: Path | None = None) -> list[EpisodeSpec]:
    """Every episode of the stored sets of ``version`` (or under ``folder``): each family,
    robot and split."""
    specs: list[EpisodeSpec] = []
    for env_id, task in TASKS.items():
        for robot in task.supported_robots:
            for split in EVAL_SPLITS:
                specs.extend(load_set(env_id, robot, split, folder, version))
    return specs


def sampler_of(specs: list[EpisodeSpec]) -> int:
    """The sampler that drew every one of ``specs`` (a ``ValueError`` if they mix)."""
    found = sorted({s.sampler for s in specs})
    if len(found) != 1:
        raise ValueError(f"the sets mix episodes of samplers {found}: audit one sampler's")
    return found[0]


#: Fresh evaluation scenes start at this index of each split's seeds, past every seed a
#: stored set may try.
FRESH_INDEX = EPISODES_PER_SET * SEEDS_PER_EPISODE


def _composed(
    env_id: str, split: str, seeds: range, sampler: int, progress: bool
) -> list[EpisodeSpec]:
    """The episodes ``env_id`` (its default robot) composes with ``sampler`` for ``seeds``
    of ``split``."""
    import gymnasium as gym

    env = gym.make(env_id, split=split, sampler=sampler, obs_mode="state", render_backend="none")
    try:
        unwrapped = env.unwrapped
        shown = tqdm(seeds, desc=f"{split} scenes {env_id}", disable=not progress)
        return [unwrapped.sample_episode(seed) for seed in shown]
    finally:
        env.close()


def training_choices(
    env_id: str, scenes: int, sampler: int = SAMPLER, progress: bool = True
) -> list[Choice]:
    """The choices of the first ``scenes`` training seeds of ``env_id`` (its default robot)
    as ``sampler`` draws them."""
    return choices(_composed(env_id, "train", range(scenes), sampler, progress))


def fresh_choices(
    env_id: str, scenes: int, sampler: int = SAMPLER, progress: bool = True
) -> list[Choice]:
    """The choices of ``scenes`` fresh evaluation scenes of ``env_id`` per evaluation split
    as ``sampler`` draws them."""
    specs = []
    for split in EVAL_SPLITS:
        first = eval_seed(split, FRESH_INDEX)
        specs += _composed(env_id, split, range(first, first + scenes), sampler, progress)
    return choices(specs)


def choices(specs: list[EpisodeSpec]) -> list[Choice]:
    """Every choice of ``specs``."""
    catalogs = {name: load_snapshot(name) for name in {s.snapshot for s in specs}}
    return [c for s in specs for c in choices_of(s, catalogs[s.snapshot])]
