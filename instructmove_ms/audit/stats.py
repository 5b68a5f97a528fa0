"""Adversary accuracy per cell against chance, counted by scene.

The Franka and PiperX episodes of one seed share a scene, so they are not two draws: every
figure averages the episodes of one (family, split, seed) first and counts scenes. The
standard error is chance's (what a blind adversary's accuracy spreads by when it carries no
signal): ``sqrt(sum c (1 - c)) / scenes``, ``c`` a scene's chance.

What gates: each split of a family with the robots pooled fails past ``MAX_Z`` standard
errors; the family pooled over its splits fails when it is past ``MAX_Z`` and more than
``MAX_POOLED_EXCESS`` above chance. Per-robot cells are reported, not gated: at a hundred
scenes each, dozens of adversaries on every robot put some past 3 standard errors by chance
alone.
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass

from .choices import Choice

#: A gated cell fails when its adversary beats chance by more than this many standard errors.
MAX_Z = 3.0
#: ... and a family pooled over its splits only when it is also past chance plus this.
MAX_POOLED_EXCESS = 0.03
#: The robot of a cell that pools both robots.
POOLED = "pooled"


@dataclass(frozen=True)
class Cell:
    """One adversary's accuracy on one cell (family and choice kind, split, robot)."""

    family: str
    kind: str
    split: str
    robot: str
    adversary: str
    episodes: int
    scenes: int
    accuracy: float
    chance: float
    se: float  # chance's standard error
    ci: tuple[float, float]  # 95% interval of the accuracy, by scenes
    source: str = "stored"  # "stored": the stored sets; "fresh": fresh scenes of the sampler

    @property
    def z(self) -> float:
        return (self.accuracy - self.chance) / self.se if self.se > 0 else 0.0

    @property
    def gated(self) -> bool:
        """Whether the cell can fail the audit (robots pooled)."""
        return self.robot == POOLED

    @property
    def failed(self) -> bool:
        if not self.gated or self.z <= MAX_Z:
            return False
        return self.split != POOLED or self.accuracy > self.chance + MAX_POOLED_EXCESS

    def to_dict(self) -> dict:
        return {
            "family": self.family,
            "kind": self.kind,
            "split": self.split,
            "robot": self.robot,
            "adversary": self.adversary,
            "episodes": self.episodes,
            "scenes": self.scenes,
            "accuracy": round(self.accuracy, 4),
            "chance": round(self.chance, 4),
            "se": round(self.se, 4),
            "z": round(self.z, 2),
            "ci95": [round(v, 4) for v in self.ci],
            "failed": self.failed,
            "source": self.source,
        }


def cell(
    choices: Sequence[Choice],
    scores: Sequence[float],
    adversary: str,
    split: str,
    robot: str,
    source: str = "stored",
) -> Cell:
    """The accuracy of ``scores`` (one per choice) on ``choices``, counted by scene."""
    by_scene: dict[tuple, list[tuple[float, float]]] = defaultdict(list)
    for c, s in zip(choices, scores, strict=True):
        by_scene[(c.split, c.seed)].append((s, c.chance))
    acc = [sum(s for s, _ in v) / len(v) for v in by_scene.values()]
    chance = [sum(c for _, c in v) / len(v) for v in by_scene.values()]
    n = len(acc)
    mean, base = sum(acc) / n, sum(chance) / n
    spread = math.sqrt(sum((a - mean) ** 2 for a in acc) / max(n - 1, 1) / n)
    first = choices[0]
    return Cell(
        family=first.family,
        kind=first.kind,
        split=split,
        robot=robot,
        adversary=adversary,
        episodes=len(choices),
        scenes=n,
        accuracy=mean,
        chance=base,
        se=math.sqrt(sum(c * (1 - c) for c in chance)) / n,
        ci=(max(0.0, mean - 1.96 * spread), min(1.0, mean + 1.96 * spread)),
        source=source,
    )


def cells(
    choices: Sequence[Choice], scores: Sequence[float], adversary: str, source: str = "stored"
) -> list[Cell]:
    """``adversary``'s cells for one family and kind: each split and robot, each split with
    the robots pooled, and everything pooled."""
    groups: dict[tuple[str, str], list[int]] = defaultdict(list)
    for i, c in enumerate(choices):
        for key in ((c.split, c.robot), (c.split, POOLED), (POOLED, POOLED)):
            groups[key].append(i)
    return [
        cell([choices[i] for i in idx], [scores[i] for i in idx], adversary, split, robot, source)
        for (split, robot), idx in sorted(groups.items())
    ]
