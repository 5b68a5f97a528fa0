"""How far above chance the rules read when nothing predicts the target: the yardstick for a
family's pooled figures at the size of its sets.

A rule's picks depend on the options alone. Redrawing every scene's answer uniformly among
its options (one draw per scene: a seed's scene is one scene on both robots) gives a set of
the same size whose target a fair die chose; the largest pooled excess over chance among
the rules on many such draws is what noise alone shows there.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np

from . import rules
from .choices import Choice

#: Redrawn answers per family and kind.
DRAWS = 1000
#: The draws' random seed (the yardstick is the same on every run).
SEED = 0
#: Draws scored at once (memory: rules x draws x choices).
CHUNK = 100


@dataclass(frozen=True)
class Noise:
    """The rules' largest pooled excess over chance on one family and kind: on the stored
    answers, and its spread over ``draws`` sets of redrawn answers."""

    family: str
    kind: str
    scenes: int
    draws: int
    observed: float
    median: float
    p95: float
    #: share of the draws whose largest excess is at least ``observed``
    share: float

    def to_dict(self) -> dict:
        return {k: round(v, 4) if isinstance(v, float) else v for k, v in asdict(self).items()}


def _pick_scores(group: Sequence[Choice]) -> np.ndarray:
    """(rules, choices, options): a rule's score on a choice were each option the answer
    (ties share the pick; options past a choice's own count score 0)."""
    width = max(len(c.options) for c in group)
    table = list(rules.rules().values())
    out = np.zeros((len(table), len(group), width))
    for r, rule in enumerate(table):
        for i, c in enumerate(group):
            picked = rule(c.options)
            out[r, i, picked] = 1.0 / len(picked)
    return out


def yardstick(group: Sequence[Choice], draws: int = DRAWS, seed: int = SEED) -> Noise:
    """The rules' largest pooled excess on ``group`` (one family and kind), counted by scene
    as the audit counts, against the same on ``draws`` redrawn answers."""
    scenes: dict[tuple[str, int], list[int]] = defaultdict(list)
    for i, c in enumerate(group):
        scenes[(c.split, c.seed)].append(i)
    weight = np.zeros(len(group))  # a scene's choices share its weight
    scene_of = np.zeros(len(group), dtype=int)
    for s, members in enumerate(scenes.values()):
        weight[members] = 1.0 / (len(scenes) * len(members))
        scene_of[members] = s
    counts = np.array([len(c.options) for c in group])
    chance = float(weight @ (1.0 / counts))
    scores = _pick_scores(group)
    columns = np.arange(len(group))
    answers = np.array([c.answer for c in group])
    observed = float((scores[:, columns, answers] @ weight).max() - chance)
    draw = np.random.default_rng(seed).random((draws, len(scenes)))
    excess = np.concatenate(
        [
            np.einsum("rdi,i->rd", scores[:, columns, redrawn], weight).max(axis=0) - chance
            for part in np.array_split(draw, max(1, draws // CHUNK))
            for redrawn in [(part[:, scene_of] * counts).astype(int)]  # (draws, choices)
        ]
    )
    return Noise(
        family=group[0].family,
        kind=group[0].kind,
        scenes=len(scenes),
        draws=draws,
        observed=observed,
        median=float(np.median(excess)),
        p95=float(np.quantile(excess, 0.95)),
        share=float((excess >= observed - 1e-12).mean()),
    )
