"""Learned adversaries: gradient-boosted trees over what each option is, never the words.

Each option becomes one row: its figures, the same figures relative to the other options of
its choice (difference from their mean, rank), how many other options share each annotated
value, whether it lies outside the training partition, and its annotations as categorical
codes (a category the target often comes from is a prior a policy can learn). The model
scores every option; the adversary picks the highest score of each choice. Two protocols:
``fit`` on training scenes and ``predict`` on the stored sets (what a policy can learn),
and ``cross_validated`` within the stored sets, folds grouped by scene seed (what the sets
give away: one seed's scene is one scene on both robots).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from sklearn.ensemble import HistGradientBoostingClassifier
from sklearn.model_selection import GroupKFold
from threadpoolctl import threadpool_limits

from .choices import CATEGORICAL, Choice
from .rules import score

#: Annotations given to the trees as categories (one value each).
CODED = ("category", "super_category", "material", "shape", "size")
FOLDS = 5
#: Fixed so that the same choices give the same model (on one machine).
SEED = 0
#: OpenMP threads the trees use. The tables are small, and many threads spinning at each
#: parallel region beside other busy processes slow the fits several times over.
THREADS = 1


class Encoder:
    """Turns choices into rows: a fixed list of figures and a code per annotation value;
    ``novelty`` False leaves out whether an option lies outside the training partition."""

    def __init__(self, choices: Sequence[Choice], novelty: bool = True) -> None:
        self.novelty = novelty
        names = sorted({n for c in choices for o in c.options for n in o.numbers})
        self.figures = names
        self.codes = {
            a: {
                v: i
                for i, v in enumerate(
                    sorted({min(o.values[a]) for c in choices for o in c.options})
                )
            }
            for a in CODED
        }

    @property
    def columns(self) -> list[str]:
        relative = [f"{n} {how}" for n in self.figures for how in ("minus mean", "rank")]
        shared = [f"shares {a}" for a in CATEGORICAL]
        return [*self.figures, *relative, *shared, "novel", *(f"{a} code" for a in CODED)]

    @property
    def categorical(self) -> list[bool]:
        return [c.endswith(" code") for c in self.columns]

    def rows(self, choice: Choice) -> np.ndarray:
        n = len(choice.options)
        raw = np.array(
            [[o.numbers.get(f, np.nan) for f in self.figures] for o in choice.options], float
        )
        present = (~np.isnan(raw)).sum(axis=0)
        minus_mean = raw - np.nansum(raw, axis=0) / np.maximum(present, 1)
        rank = np.argsort(np.argsort(raw, axis=0), axis=0) / max(n - 1, 1)
        rank[np.isnan(raw)] = np.nan
        shared = np.array(
            [
                [
                    sum(
                        bool(o.values[a] & p.values[a])
                        for j, p in enumerate(choice.options)
                        if j != k
                    )
                    for a in CATEGORICAL
                ]
                for k, o in enumerate(choice.options)
            ],
            float,
        )
        novel = np.array([[float(o.novel and self.novelty)] for o in choice.options])
        coded = np.array(
            [[self.codes[a].get(min(o.values[a]), np.nan) for a in CODED] for o in choice.options],
            float,
        )
        relative = np.stack([minus_mean, rank], axis=2).reshape(n, -1)
        return np.hstack([raw, relative, shared, novel, coded])

    def table(self, choices: Sequence[Choice]) -> tuple[np.ndarray, np.ndarray]:
        """(rows, labels): every option of ``choices``, 1 for each answer."""
        rows = np.vstack([self.rows(c) for c in choices])
        labels = np.concatenate(
            [[float(k == c.answer) for k in range(len(c.options))] for c in choices]
        )
        return rows, labels


def _model(encoder: Encoder) -> HistGradientBoostingClassifier:
    return HistGradientBoostingClassifier(
        max_iter=150,
        learning_rate=0.05,
        max_leaf_nodes=15,
        min_samples_leaf=20,
        l2_regularization=1.0,
        categorical_features=np.array(encoder.categorical),
        early_stopping=False,
        random_state=SEED,
    )


def _scores(model, encoder: Encoder, choices: Sequence[Choice]) -> list[float]:
    """The adversary's expected accuracy on each choice: it picks the top-scored options."""
    out = []
    with threadpool_limits(THREADS, user_api="openmp"):  # once: it reads the loaded libraries
        for choice in choices:
            p = model.predict_proba(encoder.rows(choice))[:, 1]
            picked = [k for k, v in enumerate(p) if v == p.max()]
            out.append(score(picked, choice.answer))
    return out


def fit(train: Sequence[Choice], encoder: Encoder):
    """A model trained to score the answer of ``train``'s choices highest."""
    rows, labels = encoder.table(train)
    with threadpool_limits(THREADS, user_api="openmp"):
        return _model(encoder).fit(rows, labels)


def trained_on(train: Sequence[Choice], test: Sequence[Choice]) -> list[float]:
    """Per-choice accuracy on ``test`` of a model trained on ``train`` (training scenes), on
    the figures and annotation values training scenes hold (others read as missing)."""
    encoder = Encoder(train)
    return _scores(fit(train, encoder), encoder, test)


def cross_validated(choices: Sequence[Choice], novelty: bool = True) -> list[float]:
    """Per-choice accuracy on ``choices`` of models trained on the other folds, the folds
    grouped by scene seed (``novelty`` False: without the training partition's flag)."""
    encoder = Encoder(choices, novelty)
    groups = np.array([c.seed for c in choices])
    out = [0.0] * len(choices)
    folds = GroupKFold(n_splits=min(FOLDS, len(set(groups.tolist()))))
    for train, test in folds.split(np.zeros(len(choices)), groups=groups):
        model = fit([choices[i] for i in train], encoder)
        for i, s in zip(test, _scores(model, encoder, [choices[i] for i in test]), strict=True):
            out[i] = s
    return out
