"""Robustness runs: the same stored episodes under each perturbation axis and level.

``settings`` reads the ``--perturb`` argument: one setting (``lighting:2,camera:1``) or a
sweep (``sweep``, ``sweep=lighting,camera``: level 0, then every named axis at levels 1-3).
Each setting is an ordinary evaluation in a folder of its own; ``write_robustness`` then
gathers their summaries into one table of stage scores per axis and level, with Wilson
intervals and the level-0 baseline of the same episodes (crossed with the instruction
conditions when several were run), as ``report.md``, ``summary.json`` and a plot of score
against level per axis.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .files import write_json, write_text  # noqa: E402
from .metrics import markdown_table  # noqa: E402
from .perturbation import AXES, MAX_LEVEL, levels_text, parse_levels  # noqa: E402

GROUP = ("family", "robot", "split", "condition")


def settings(value: str | None) -> list[dict[str, int]] | None:
    """The perturbation settings ``value`` asks for; None for a plain run."""
    if not value:
        return None
    if is_sweep(value):
        axes = value.partition("=")[2].split(",") if "=" in value else list(AXES)
        for axis in axes:
            parse_levels({axis: 1})  # names an unknown axis
        return [{}] + [{a: level} for a in axes for level in range(1, MAX_LEVEL + 1)]
    return [parse_levels(value)]


def is_sweep(value: str | None) -> bool:
    """Whether a ``--perturb`` value asks for a sweep."""
    return bool(value) and (value == "sweep" or value.startswith("sweep="))


def folder_name(levels: dict[str, int]) -> str:
    """A setting's output folder: ``none`` or ``lighting-2`` (``lighting-2_camera-1``)."""
    return "_".join(f"{a}-{v}" for a, v in levels.items()) or "none"


def _key(group: dict) -> tuple:
    return tuple(group[k] for k in GROUP)


def _row(group: dict, axis: str, level: int, base: dict | None) -> dict:
    return {
        **group,
        "axis": axis,
        "level": level,
        "baseline_success": base["success"] if base else None,
        "baseline_stage_score": base["stage_score"] if base else None,
    }


def robustness_rows(runs: list[tuple[dict[str, int], list[dict]]]) -> list[dict]:
    """One row per group (family, robot, split, condition), axis and level from each
    setting's summary groups; each axis's level 0 is the run without perturbation (a
    setting of several axes is named by all of them, at its highest level)."""
    base = {_key(g): g for levels, groups in runs if not levels for g in groups}
    rows = []
    for levels, groups in runs:
        if levels:
            axis = next(iter(levels)) if len(levels) == 1 else levels_text(levels)
            rows += [_row(g, axis, max(levels.values()), base.get(_key(g))) for g in groups]
    for axis in dict.fromkeys(r["axis"] for r in rows):
        rows += [_row(g, axis, 0, g) for g in base.values()]
    return sorted(rows, key=lambda r: (*_key(r), r["axis"], r["level"]))


def robustness_plot(rows: list[dict], path: Path) -> Path:
    """Stage score against level, one line per axis (and group), with success's interval."""
    fig, ax = plt.subplots(figsize=(7, 4))
    lines: dict[tuple, list[dict]] = {}
    for r in rows:
        lines.setdefault((r["axis"], *(r[k] for k in GROUP)), []).append(r)
    for (axis, *group), points in lines.items():
        points.sort(key=lambda r: r["level"])
        label = axis if len(lines) <= len(AXES) else f"{axis} {' '.join(map(str, group))}"
        ax.errorbar(
            [r["level"] for r in points],
            [r["stage_score"] for r in points],
            marker="o",
            capsize=3,
            label=label,
        )
    ax.set_xticks(range(MAX_LEVEL + 1))
    ax.set_xlabel("perturbation level")
    ax.set_ylabel("stage score S")
    ax.set_ylim(0, 1.05)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_robustness(out: Path, runs: list[tuple[dict[str, int], list[dict]]]) -> list[dict]:
    """``out/report.md``, ``out/summary.json`` and ``out/robustness.png`` of the runs."""
    rows = robustness_rows(runs)
    out.mkdir(parents=True, exist_ok=True)
    robustness_plot(rows, out / "robustness.png")
    write_json(out / "summary.json", {"robustness": rows}, indent=2)
    table = markdown_table(rows, (*GROUP, "axis", "level"))
    write_text(
        out / "report.md",
        "# InstructMove robustness\n\nEach axis's level 0 is the same episodes without "
        "perturbation; every setting's own report is in its folder.\n\n"
        + table
        + "\n\n![robustness](robustness.png)\n",
    )
    return rows
