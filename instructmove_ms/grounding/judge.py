"""How often a chooser picks each decision's answer, per family, kind, split and robot."""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from .crops import Decisions

#: The robot and split of rows that pool them.
POOLED = "pooled"


def table(d: Decisions, picked: np.ndarray) -> list[dict]:
    """One row per (family, kind, split, robot), with each split's and the family's robots
    pooled: decisions, accuracy and chance (the mean of 1 / options)."""
    groups: dict[tuple, list[int]] = defaultdict(list)
    for i in range(len(d)):
        family, kind, split, robot = (
            str(d.family[i]),
            str(d.kind[i]),
            str(d.split[i]),
            str(d.robot[i]),
        )
        for key in ((split, robot), (split, POOLED), (POOLED, POOLED)):
            groups[(family, kind, *key)].append(i)
    rows = []
    for (family, kind, split, robot), idx in sorted(groups.items()):
        rows.append(
            {
                "family": family,
                "kind": kind,
                "split": split,
                "robot": robot,
                "decisions": len(idx),
                "accuracy": round(float(np.mean(picked[idx] == d.answer[idx])), 4),
                "chance": round(float(np.mean(1.0 / d.count[idx])), 4),
            }
        )
    return rows


def markdown(rows: list[dict]) -> str:
    """``table``'s rows as a Markdown table."""
    lines = [
        "| family | kind | split | robot | decisions | accuracy | chance |",
        "|---|---|---|---|---|---|---|",
    ]
    lines += [
        f"| {r['family']} | {r['kind']} | {r['split']} | {r['robot']} | {r['decisions']} | "
        f"{r['accuracy']:.3f} | {r['chance']:.3f} |"
        for r in rows
    ]
    return "\n".join(lines)
