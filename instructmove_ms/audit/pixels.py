"""The pixel adversary: a chooser that sees what the policy's cameras show, never the words.

It is trained on rendered training scenes of every family and robot (``grounding.scenes``)
to pick the answer from each option's crops in the 224 x 224 cameras and where they lay
(``grounding.network``), then picks on the stored sets. Options are located by
segmentation, so it judges what the pictures give away, not how well it detects objects.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from ..grounding import scenes
from ..grounding.training import Schedule, choose, fit
from .choices import Choice
from .stats import Cell, cells

#: The pixel adversary's name in the report.
NAME = "pixels, trained"


def _key(family: str, kind: str, split: str, robot: str, seed: int) -> tuple:
    return (str(family), str(kind), str(split), str(robot), int(seed))


def judge(
    stored: Sequence[Choice],
    cache: Path,
    training_scenes: int,
    sampler: int,
    version: int | None = None,
    folder: Path | None = None,
    progress: bool = True,
    schedule: Schedule | None = None,
) -> tuple[list[Cell], list[float]]:
    """(the adversary's cells on ``stored``, the choices of the sets of ``version`` or under
    ``folder``; its mean training loss per epoch), trained on ``training_scenes`` scenes per
    family and robot drawn by ``sampler``, renders and model kept under ``cache``."""
    taught = scenes.training(cache, training_scenes, sampler, progress)
    judged = scenes.stored(cache, version, folder, progress)
    checkpoint = Path(cache) / f"pixels-sampler{sampler}-{training_scenes}.pt"
    model, losses = fit(taught, schedule or Schedule(), checkpoint, progress)
    picked = choose(model, judged)
    correct = {
        _key(*row): float(p == a)
        for *row, p, a in zip(
            judged.family,
            judged.kind,
            judged.split,
            judged.robot,
            judged.seed,
            picked,
            judged.answer,
            strict=True,
        )
    }
    found: list[Cell] = []
    for family, kind in sorted({(c.family, c.kind) for c in stored}):
        group = [c for c in stored if (c.family, c.kind) == (family, kind)]
        scores = [correct[_key(c.family, c.kind, c.split, c.robot, c.seed)] for c in group]
        found += cells(group, scores, NAME)
    return found, losses
