"""Report figures: the stage funnel per group and what grounding errors share with the goal."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .metrics import SHARED_ATTRIBUTES  # noqa: E402


def stage_funnel(rows: list[dict], path: Path) -> Path:
    """Bar chart of each stage's rate (with its 95% interval) per aggregate row."""
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for k, row in enumerate(rows):
        stages = row["stages"]
        rates = [row[s] for s in stages]
        errors = [  # clamped: rounding can put a rate a hair outside its interval
            [max(0.0, row[s] - row[f"{s}_ci"][0]) for s in stages],
            [max(0.0, row[f"{s}_ci"][1] - row[s]) for s in stages],
        ]
        xs = [i + k * 0.8 / len(rows) for i in range(len(stages))]
        ax.bar(
            xs,
            rates,
            width=0.8 / len(rows),
            yerr=errors,
            capsize=3,
            label=f"{row['family']} {row['split']} {row['condition']}",
        )
        ax.set_xticks(range(len(stages)), stages)
    ax.set_ylim(0, 1)
    ax.set_ylabel("rate")
    ax.set_title("stage funnel")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def grounding_attribution(results: list, path: Path) -> Path:
    """How often a wrongly chosen object shared each attribute with the goal."""
    counts = Counter(a for r in results if r.grounding_error for a in r.shared)
    errors = sum(r.grounding_error for r in results)
    fig, ax = plt.subplots(figsize=(5, 3))
    ax.bar(SHARED_ATTRIBUTES, [counts[a] / max(1, errors) for a in SHARED_ATTRIBUTES])
    ax.set_ylim(0, 1)
    ax.set_ylabel("share of grounding errors")
    ax.set_title(f"grounding errors: {errors}")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
