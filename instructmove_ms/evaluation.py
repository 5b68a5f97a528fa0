"""Batch evaluation of a policy on stored held-out episodes, resumable.

For each episode the env is reset to the stored spec (re-rendered for the requested
instruction condition: same scene, other instruction), the policy acts for the task's
horizon (stopping early once a task with a target has succeeded: stages latch), and the
last step's info is scored. Results append to ``episodes.jsonl`` as they finish, so an
interrupted run resumes where it stopped; ``summary.json`` and ``report.md`` are rewritten
at the end.
"""

from __future__ import annotations

import csv
import json
import os
from pathlib import Path

import gymnasium as gym
from tqdm import tqdm

from . import heldout
from .metrics import EpisodeResult, aggregate, markdown_table, score_episode
from .plots import grounding_attribution, stage_funnel
from .tasks import TASKS
from .validation import check_choice

STATE_MODES = ("state", "state_dict")  # observation modes that need no renderer


def _atomic_write(path: Path, text: str) -> None:
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def _done(path: Path) -> dict[int, dict]:
    """Finished episodes of an earlier run (a torn last line is dropped)."""
    done = {}
    if path.is_file():
        for line in path.read_text().splitlines():
            try:
                row = json.loads(line)
            except json.JSONDecodeError:
                continue
            done[row["episode_id"]] = row
    return done


def evaluate(
    policy,
    env_id: str,
    split: str,
    out: Path,
    robot: str | None = None,
    condition: str = "normal",
    episodes: int | None = None,
) -> dict:
    """Run ``policy`` on the held-out set of (env, robot, split) under ``condition``."""
    check_choice("task", env_id, TASKS)
    robot = robot or TASKS[env_id].default_robot
    specs = heldout.load_set(env_id, robot, split)[:episodes]
    out.mkdir(parents=True, exist_ok=True)
    log = out / "episodes.jsonl"
    done = _done(log)
    env = gym.make(
        env_id,
        robot_uids=robot,
        obs_mode=policy.get_obs_mode(),
        control_mode=policy.get_control_mode(),
        **({"render_backend": "none"} if policy.get_obs_mode() in STATE_MODES else {}),
        split=split,
        condition=condition,
    )
    u = env.unwrapped
    horizon = u.task.max_episode_steps
    with log.open("a") as sink:
        for k, stored in enumerate(
            tqdm(specs, desc=f"{env_id} {split} {condition}", unit="episode")
        ):
            if k in done:
                continue
            spec = u.sample_episode(stored.seed, condition)  # the same scene, re-rendered
            obs, _ = env.reset(options={"episode": spec.to_dict()})
            if hasattr(policy, "bind"):
                policy.bind(env)
            policy.reset(obs)
            for _ in range(horizon):
                obs, _, _, _, info = env.step(policy.act(obs))
                if spec.target >= 0 and bool(info["success"]):
                    break
            row = {"episode_id": k, **score_episode(spec, info, u.catalog).to_dict()}
            sink.write(json.dumps(row) + "\n")
            sink.flush()
            done[k] = row
    env.close()
    return write_reports(out, [done[k] for k in sorted(done)])


def write_reports(out: Path, rows: list[dict]) -> dict:
    """summary.json (rates with Wilson intervals), episodes.csv, report.md and its two
    figures (stage funnel, grounding-error attribution)."""
    results = [
        EpisodeResult(
            **{**{k: v for k, v in r.items() if k != "episode_id"}, "shared": tuple(r["shared"])}
        )
        for r in rows
    ]
    summary = {"groups": aggregate(results), "episodes": len(results)}
    stage_funnel(summary["groups"], out / "stage_funnel.png")
    grounding_attribution(results, out / "grounding_errors.png")
    _atomic_write(out / "summary.json", json.dumps(summary, indent=2))
    _atomic_write(
        out / "report.md",
        "# InstructMove evaluation\n\n"
        + markdown_table(summary["groups"])
        + "\n\n![stage funnel](stage_funnel.png)\n![grounding errors](grounding_errors.png)\n",
    )
    with (out / "episodes.csv.tmp").open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]) if rows else ["episode_id"])
        writer.writeheader()
        writer.writerows(rows)
    os.replace(out / "episodes.csv.tmp", out / "episodes.csv")
    return summary
