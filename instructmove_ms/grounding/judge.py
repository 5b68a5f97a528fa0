"""How often a chooser picks each decision's answer, per family, kind, split and robot."""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from ..audit.choices import decisions
from ..episode import CONDITIONS
from ..heldout import evaluator_config, load_set
from ..readers.material import stored_sets
from .crops import Decisions
from .training import choose

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
    """Rows of ``table`` or ``counterfactuals`` as a Markdown table."""
    keys = list(rows[0])

    def shown(v) -> str:
        return f"{v:.3f}" if isinstance(v, float) else "" if v is None else str(v)

    lines = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    lines += ["| " + " | ".join(shown(r[k]) for k in keys) + " |" for r in rows]
    return "\n".join(lines)


def counterfactuals(
    model, judged: Decisions, episodes: int, version: int | None = None
) -> list[dict]:
    """Per family, kind and condition, on the first ``episodes`` of every stored set of
    ``version`` (``judged``: all of them, rendered): how often ``model`` picks the normal
    episode's goal and the condition's own (``None`` where it has none), against chance.
    The scenes are the normal episodes' (a condition changes only the words), so their
    crops serve every condition."""
    counts: dict[tuple, np.ndarray] = defaultdict(lambda: np.zeros(4))
    for env_id, robot, split in stored_sets(version):
        first = np.nonzero(
            (judged.robot == robot) & (judged.split == split) & (judged.family == _family(env_id))
        )[0]
        specs = load_set(env_id, robot, split, version=version)[:episodes]
        rows = first[: sum(len(decisions(s)) for s in specs)]
        part = judged.take(rows)
        for condition in CONDITIONS:
            variants = [
                e.spec
                for e in evaluator_config(
                    env_id, robot, split, condition, episodes, version=version
                ).episodes
            ]
            asked = part.instructed(variants)
            answers, picked = asked.answer, choose(model, asked)
            for i, kind in enumerate(part.kind):
                c = counts[(str(part.family[i]), str(kind), condition)]
                c += [
                    1,
                    picked[i] == part.answer[i],
                    answers[i] >= 0 and picked[i] == answers[i],
                    1 / part.count[i],
                ]
    rows_out = []
    for (family, kind, condition), (n, normal, own, chance) in sorted(counts.items()):
        has_goal = condition in ("normal", "alternative_target")
        rows_out.append(
            {
                "family": family,
                "kind": kind,
                "condition": condition,
                "decisions": int(n),
                "normal goal": round(normal / n, 4),
                "condition's goal": round(own / n, 4) if has_goal else None,
                "chance": round(chance / n, 4),
            }
        )
    return rows_out


def _family(env_id: str) -> str:
    from ..tasks import TASKS

    return TASKS[env_id].family
