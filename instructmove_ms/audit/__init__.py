"""The language-blind audit: can anything but the instruction tell which candidate is meant?

Adversaries that never read the instruction pick among each choice's options (``choices``):
fixed rules (``rules``: odd one out, extremes, layout, visibility, novelty) and gradient-
boosted trees (``learned``), trained on training scenes or cross-validated within the stored
sets. ``run`` scores them per family, split and robot against chance (``stats``) and writes
the report (``report``). A benchmark version passes when no adversary beats chance.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from ..heldout import benchmark_name
from ..sampler import SAMPLERS
from ..tasks import TASKS
from ..validation import check_choice
from . import report, rules
from .choices import Choice, by_decision
from .noise import yardstick
from .scenes import choices, fresh_choices, sampler_of, stored_specs, training_choices
from .stats import Cell, cells

__all__ = ["run", "judge"]

#: Training scenes per family the learned adversary trains on, by default.
TRAINING_SCENES = 300
#: Rendered training scenes per family and robot the pixel adversary learns from, for the
#: published figures (the audit runs it only when asked: it renders for tens of minutes).
PIXEL_SCENES = 400


def _adversaries(
    group: Sequence[Choice], taught: Sequence[Choice] | None, trees: bool, source: str
) -> list[Cell]:
    """Every adversary's cells on ``group`` (one family and kind); the trained trees learn
    from ``taught`` (its training choices) where given."""
    from . import learned  # scikit-learn, only when an audit runs

    found: list[Cell] = []
    for name, rule in rules.rules().items():
        scores = [rules.score(rule(c.options), c.answer) for c in group]
        found += cells(group, scores, name, source)
    if trees:
        found += cells(group, learned.cross_validated(group), "trees, within the sets", source)
        blind = learned.cross_validated(group, novelty=False)
        found += cells(group, blind, "trees, no novelty flag", source)
        if taught:
            found += cells(group, learned.trained_on(taught, group), "trees, trained", source)
    return found


def judge(
    stored: Sequence[Choice],
    training: Sequence[Choice] = (),
    trees: bool = True,
    fresh: Sequence[Choice] = (),
) -> tuple[list[Cell], list[Cell]]:
    """(cells of the stored and the ``fresh`` choices, cells of the rules on the
    ``training`` choices): every rule and, with ``trees``, the learned adversaries
    (cross-validated within the choices judged, and trained on ``training``)."""
    taught = by_decision(training)
    found: list[Cell] = []
    for source, judged in (("stored", stored), ("fresh", fresh)):
        for key, group in by_decision(judged).items():
            found += _adversaries(group, taught.get(key), trees, source)
    on_training = [
        c
        for key, group in taught.items()
        for c in _adversaries(group, None, False, "training")
        if c.split == "pooled"
    ]
    return found, on_training


def run(
    out: Path,
    version: int | None = None,
    folder: Path | None = None,
    training_scenes: int = TRAINING_SCENES,
    fresh_scenes: int = 0,
    progress: bool = True,
    sampler: int | None = None,
    pixel_scenes: int = 0,
) -> tuple[list[Cell], list[Path]]:
    """Audit the stored sets of ``version`` (or under ``folder``) and, with ``fresh_scenes``,
    that many fresh scenes per family and split, training and fresh scenes drawn by the
    sampler that drew the sets; with ``sampler`` instead, audit that sampler's fresh scenes
    alone. With ``pixel_scenes``, the pixel adversary (``pixels``) judges the stored sets
    too, trained on that many rendered training scenes per family and robot (renders and
    model kept under ``out/pixels``). Write the report under ``out``; returns the cells and
    the files written."""
    counts = {
        "training scenes": training_scenes,
        "fresh scenes": fresh_scenes,
        "pixel scenes": pixel_scenes,
    }
    for what, count in counts.items():
        if count < 0:
            raise ValueError(f"{what} must be 0 or more, got {count}")
    if sampler is not None and pixel_scenes:
        raise ValueError("the pixel adversary judges stored sets: drop --sampler or --pixel-scenes")
    if sampler is None:
        specs = stored_specs(version, folder)
        sampler, sets = sampler_of(specs), str(folder) if folder else benchmark_name(version)
    else:
        check_choice("sampler", sampler, SAMPLERS)
        if fresh_scenes < 1:
            raise ValueError("auditing a sampler alone needs fresh scenes (--fresh-scenes N)")
        specs, sets = [], f"none: sampler {sampler}'s fresh scenes alone"
    stored = choices(specs)
    training: list[Choice] = []
    fresh: list[Choice] = []
    for env_id in TASKS:
        training += training_choices(env_id, training_scenes, sampler, progress)
        fresh += fresh_choices(env_id, fresh_scenes, sampler, progress)
    found, on_training = judge(stored, training, fresh=fresh)
    noises = [yardstick(group) for group in by_decision(stored).values()]
    about: dict = {}
    if pixel_scenes:
        from . import pixels  # torch and the renderer, only when asked

        cache = out / "pixels"
        seen, losses = pixels.judge(cache, pixel_scenes, sampler, version, folder, progress)
        found += seen
        about["pixel adversary's training loss per epoch"] = [round(v, 3) for v in losses]
    about = {
        "sets": sets,
        "sampler": sampler,
        "episodes": len({(c.family, c.split, c.robot, c.seed) for c in stored}),
        "training scenes per family": training_scenes,
        "fresh scenes per family and split": fresh_scenes,
        "rendered training scenes per family and robot (pixel adversary)": pixel_scenes,
        **about,
    }
    return found, report.write(out, about, found, on_training, noises)
