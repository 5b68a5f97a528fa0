"""Pixel adversaries: what the policy's cameras show at the first step, never the words.

Every object of a scene is located by segmentation in the robot's three 224 x 224 cameras
and cut out (``grounding.crops``); the adversaries see each option's crops and where they
lay, nothing the spec or the catalog says of it. Locating by segmentation is given: they
judge what the pictures give away, not how well they detect objects.

- ``pixels, trained``: the grounding network without its instruction reader (the image-only
  twin), trained on rendered training scenes of every family and robot.
- ``pixel statistics, ...``: gradient-boosted trees (``learned``) over each option's image
  statistics per camera (mean and spread of each colour channel over its mask, how much of
  its crop it fills, where the crop lay), trained on the training scenes or cross-validated
  within the stored sets. Few figures learn from few scenes: where the network needs more
  scenes than are rendered, the trees still find a colour or a size that stands out.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..grounding import scenes
from ..grounding.crops import GEOMETRY, Decisions
from ..grounding.training import Schedule, choose, fit
from . import learned
from .choices import CATEGORICAL, Choice, Option, by_decision
from .stats import Cell, cells

#: The network's name in the report.
NAME = "pixels, trained"
#: A mask channel above this is the option.
MASKED = 127


def _figures(crops: np.ndarray, geometry: np.ndarray) -> dict[str, float]:
    """One option's image statistics: per camera, where its crop lay and (where the camera
    shows it) the mean and spread of each colour channel over its mask and how much of the
    crop the mask fills."""
    out: dict[str, float] = {}
    for c, (crop, where) in enumerate(zip(crops, geometry, strict=True)):
        out.update({f"{name} {c}": float(v) for name, v in zip(GEOMETRY, where, strict=True)})
        mask = crop[3] > MASKED
        if mask.any():
            colours = crop[:3][:, mask] / 255.0
            for channel, values in zip("rgb", colours, strict=True):
                out[f"{channel} mean {c}"] = float(values.mean())
                out[f"{channel} spread {c}"] = float(values.std())
            out[f"fill {c}"] = float(mask.mean())
    return out


def statistics(d: Decisions) -> list[Choice]:
    """The decisions of ``d`` as choices whose options hold their image statistics alone
    (every annotation blank: the trees see the pictures only)."""
    blank = {a: frozenset({""}) for a in CATEGORICAL}
    found = []
    for i, start in enumerate(d.starts):
        options = tuple(
            Option(blank, _figures(d.crops[k], d.geometry[k]), novel=False)
            for k in range(start, start + d.count[i])
        )
        found.append(
            Choice(
                family=str(d.family[i]),
                kind=str(d.kind[i]),
                split=str(d.split[i]),
                robot=str(d.robot[i]),
                seed=int(d.seed[i]),
                options=options,
                answer=int(d.answer[i]),
            )
        )
    return found


def judge(
    cache: Path,
    training_scenes: int,
    sampler: int,
    version: int | None = None,
    folder: Path | None = None,
    progress: bool = True,
    schedule: Schedule | None = None,
    families: tuple[str, ...] | None = None,
) -> tuple[list[Cell], list[float]]:
    """(the pixel adversaries' cells on the stored sets of ``version`` or under ``folder``;
    the network's mean training loss per epoch), trained on ``training_scenes`` scenes per
    family and robot drawn by ``sampler`` (``families``: of those env ids only), renders and
    model kept under ``cache``."""
    taught = scenes.training(cache, training_scenes, sampler, progress, families)
    judged = scenes.stored(cache, version, folder, progress, families)
    name = "-".join(sorted(families)) if families else "all"
    checkpoint = Path(cache) / f"pixels-sampler{sampler}-{training_scenes}-{name}.pt"
    model, history = fit(taught, schedule, checkpoint, progress)
    stored, trained = statistics(judged), statistics(taught)
    picked = choose(model, judged)
    correct = {id(c): float(p == c.answer) for c, p in zip(stored, picked, strict=True)}
    taught_by = by_decision(trained)
    found: list[Cell] = []
    for key, group in sorted(by_decision(stored).items()):
        found += cells(group, [correct[id(c)] for c in group], NAME)
        if key in taught_by:
            trees = learned.trained_on(taught_by[key], group)
            found += cells(group, trees, "pixel statistics, trees trained")
        found += cells(group, learned.cross_validated(group), "pixel statistics, trees within")
    return found, history.losses
