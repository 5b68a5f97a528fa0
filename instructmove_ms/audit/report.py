"""The audit's outputs: ``summary.json``, ``report.md`` and one plot per family."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..files import atomic_path, write_json, write_text  # noqa: E402
from .noise import Noise  # noqa: E402
from .stats import MAX_Z, POOLED, Cell  # noqa: E402


def _label(c: Cell) -> str:
    return c.family if c.kind == "object" else f"{c.family} ({c.kind})"


#: How each source of scenes heads its sections.
SOURCES = {"stored": "stored sets", "fresh": "fresh scenes of the sampler"}


def summary(
    about: dict, cells: list[Cell], training: list[Cell], noises: Sequence[Noise] = ()
) -> dict:
    return {
        **about,
        "failed": [c.to_dict() for c in cells if c.failed],
        "cells": [c.to_dict() for c in cells],
        "training_scenes": [c.to_dict() for c in training],
        "noise": [n.to_dict() for n in noises],
    }


def _row(c: Cell) -> str:
    mark = " **failed**" if c.failed else ""
    return (
        f"| {c.split} | {c.robot} | {c.adversary} | {c.accuracy:.3f} "
        f"[{c.ci[0]:.2f}, {c.ci[1]:.2f}] | {c.chance:.3f} | {c.z:+.1f}{mark} |"
    )


def _noise(noises: Sequence[Noise]) -> list[str]:
    if not noises:
        return []
    draws = noises[0].draws
    return [
        "## Noise at this size",
        "",
        "The rules' largest pooled excess over chance on the stored answers, against the same "
        f"on {draws:,} sets of the same scenes whose answers a fair die redrew: what noise "
        "alone shows at this size.",
        "",
        "| family | scenes | largest excess | redrawn: median | redrawn: 95th percentile "
        "| redrawn at least as large |",
        "|---|---|---|---|---|---|",
        *(
            f"| {n.family if n.kind == 'object' else f'{n.family} ({n.kind})'} | {n.scenes} "
            f"| {n.observed:+.3f} | {n.median:+.3f} | {n.p95:+.3f} | {n.share:.0%} |"
            for n in noises
        ),
        "",
    ]


def markdown(
    about: dict, cells: list[Cell], training: list[Cell], noises: Sequence[Noise] = (), top: int = 8
) -> str:
    """The report: what was judged, what failed, each family's strongest adversaries and the
    noise yardstick of the stored sets (``noise``)."""
    failed = [c for c in cells if c.failed]
    lines = [
        "# Language-blind audit",
        "",
        *(f"- {k}: {v}" for k, v in about.items()),
        "",
        "Adversaries never read the instruction. With the robots pooled, a split fails when an "
        "adversary beats chance by more than 3 standard errors (counted by scene: a seed's "
        "scene is one scene on both robots), and a family pooled over its splits when it is "
        "also more than 0.03 above chance. Cells of one robot are reported, not gated.",
        "",
        f"**{len(failed)} of {sum(c.gated for c in cells)} gated cells failed.**"
        if failed
        else "**No cell failed.**",
        "",
    ]
    by_family: dict[str, list[Cell]] = defaultdict(list)
    for c in cells:
        by_family[f"{_label(c)}, {SOURCES[c.source]}"].append(c)
    header = [
        "| split | robot | adversary | accuracy [95%] | chance | z |",
        "|---|---|---|---|---|---|",
    ]
    for family, group in by_family.items():
        lines += [f"## {family}", "", *header]
        pooled = [c for c in group if c.robot == POOLED]
        shown = sorted(pooled, key=lambda c: (c.split, -c.z))
        per_split: dict[str, int] = defaultdict(int)
        for c in shown:
            if per_split[c.split] < top or c.failed:
                lines.append(_row(c))
            per_split[c.split] += 1
        lines.append("")
        robots = [c for c in group if c.robot != POOLED and c.z > MAX_Z]
        if robots:
            lines += ["Past 3 standard errors on one robot (not gated):", "", *header]
            lines += [*map(_row, robots), ""]
    lines += _noise(noises)
    if training:
        lines += [
            "## Rules on training scenes",
            "",
            "What the same rules find in training scenes (no visibility figures there).",
            "",
            *header,
            *(_row(c) for c in sorted(training, key=lambda c: (_label(c), -c.z))[: top * 5]),
            "",
        ]
    return "\n".join(lines)


def plot(family: str, cells: list[Cell], path: Path) -> Path:
    """Each adversary's accuracy with its 95% interval per split, robots pooled, against
    chance."""
    pooled = [c for c in cells if c.robot == POOLED]
    adversaries = sorted({c.adversary for c in pooled})
    splits = sorted({c.split for c in pooled})
    fig, ax = plt.subplots(figsize=(8, 0.25 * len(adversaries) + 1.5))
    for s, split in enumerate(splits):
        rows = {c.adversary: c for c in pooled if c.split == split}
        ys = [a + (s - len(splits) / 2) * 0.18 for a in range(len(adversaries))]
        xs = [rows[a].accuracy for a in adversaries]
        lo = [max(0.0, rows[a].accuracy - rows[a].ci[0]) for a in adversaries]
        hi = [max(0.0, rows[a].ci[1] - rows[a].accuracy) for a in adversaries]
        ax.errorbar(xs, ys, xerr=[lo, hi], fmt="o", ms=3, capsize=2, label=split)
        chance = rows[adversaries[0]].chance
        ax.axvline(chance, color=f"C{s}", lw=0.8, ls="--")
    ax.set_yticks(range(len(adversaries)), adversaries, fontsize=7)
    ax.set_xlim(0, 1)
    ax.set_xlabel("accuracy (dashed: chance)")
    ax.set_title(f"{family}: language-blind adversaries")
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    return path


def write(
    out: Path,
    about: dict,
    cells: list[Cell],
    training: list[Cell],
    noises: Sequence[Noise] = (),
) -> list[Path]:
    """Write the summary, the report and the plots under ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    paths = [
        write_json(out / "summary.json", summary(about, cells, training, noises), indent=1),
        write_text(out / "report.md", markdown(about, cells, training, noises)),
    ]
    by_family: dict[str, list[Cell]] = defaultdict(list)
    plotted = "stored" if any(c.source == "stored" for c in cells) else "fresh"
    for c in cells:
        if c.source == plotted:
            by_family[_label(c)].append(c)
    for family, group in by_family.items():
        name = family.replace(" ", "_").replace("(", "").replace(")", "")
        paths.append(plot(family, group, out / f"{name}.png"))
    return paths
