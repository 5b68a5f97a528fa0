"""Evaluation reports from the rows of ``episodes.jsonl``.

Writes ``summary.json`` (rates with Wilson intervals, episode and error counts),
``episodes.csv``, ``report.md`` with its two figures (stage funnel, grounding-error
attribution) and the outputs of ManiSkill's evaluator convention: ``episode_results.json``
(per episode id, its scalar metrics) and ``average_metrics.json`` (their means).
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

from .files import write_json, write_text
from .metrics import EpisodeResult, aggregate, markdown_table
from .plots import grounding_attribution, stage_funnel

SCALARS = ("success", "stage_score", "any_reach", "any_lift", "grounding_error", "control_error")


def episode_result(row: dict) -> EpisodeResult:
    """The scored episode of a row (rows also hold ``episode_id`` and ``error``)."""
    fields = {k: v for k, v in row.items() if k not in ("episode_id", "error")}
    return EpisodeResult(**{**fields, "shared": tuple(row["shared"])})


def maniskill_metrics(row: dict) -> dict:
    """A row's metrics as ManiSkill's evaluator reports them: stage flags and scalars, and
    the policy's error where there was one."""
    metrics = {**row["stages"], **{k: row[k] for k in SCALARS}, "success_once": row["success"]}
    if row.get("success_at_end") is not None:
        metrics["success_at_end"] = row["success_at_end"]
    if row.get("error"):
        metrics["error"] = row["error"]
    return metrics


def write_maniskill_results(out: Path, rows: list[dict]) -> None:
    per_episode = {str(r["episode_id"]): maniskill_metrics(r) for r in rows}
    numeric = dict.fromkeys(
        k for m in per_episode.values() for k, v in m.items() if not isinstance(v, str)
    )
    average = {}
    for key in numeric:
        values = [float(m[key]) for m in per_episode.values() if key in m]
        average[key] = sum(values) / len(values)
    write_json(out / "episode_results.json", per_episode, indent=2)
    write_json(out / "average_metrics.json", average, indent=2)


def write_csv(path: Path, rows: list[dict]) -> None:
    fields = list(dict.fromkeys(k for r in rows for k in r)) or ["episode_id"]
    text = io.StringIO(newline="")
    writer = csv.DictWriter(text, fieldnames=fields, restval="")
    writer.writeheader()
    writer.writerows(rows)
    write_text(path, text.getvalue())


def write_reports(
    out: Path, rows: list[dict], policy: dict | None = None, about: dict | None = None
) -> dict:
    """Every report of ``rows``; returns the summary (with ``policy``: what the policy
    reports of itself, a served one its server's timing; with ``about``: what the numbers
    measured, which a reported number must name)."""
    results = [episode_result(r) for r in rows]
    errors = sum(bool(r.get("error")) for r in rows)
    summary = {"groups": aggregate(results), "episodes": len(results), "errors": errors}
    if about:
        summary["about"] = about
    if policy:
        summary["policy"] = policy
    stage_funnel(summary["groups"], out / "stage_funnel.png")
    grounding_attribution(results, out / "grounding_errors.png")
    write_json(out / "summary.json", summary, indent=2)
    note = (
        f"\n{errors} episode(s) ended in a policy error and count as failures "
        "(see the `error` column of episodes.csv).\n"
        if errors
        else ""
    )
    write_text(
        out / "report.md",
        "# InstructMove evaluation\n\n"
        + _measured(about)
        + markdown_table(summary["groups"])
        + "\n"
        + note
        + "\n![stage funnel](stage_funnel.png)\n![grounding errors](grounding_errors.png)\n",
    )
    write_csv(out / "episodes.csv", rows)
    write_maniskill_results(out, rows)
    return summary


def _measured(about: dict | None) -> str:
    """The list of what was measured, which a reported number names with its S and
    interval."""
    if not about:
        return ""
    lines = "".join(f"- {key.replace('_', ' ')}: {value}\n" for key, value in about.items())
    return (
        "What was measured (a reported number names these, with its S and 95% interval):\n\n"
        + lines
        + "\n"
    )
