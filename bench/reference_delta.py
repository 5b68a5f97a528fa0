"""The reference policies' figures carried from one stored set version to the next.

The planner oracle, the language-blind policy and random actions never read the
instruction, and their randomness is seeded by the episode's seed, so an episode's row
depends on its scene alone. A new set version that keeps most scenes (the same seed,
objects, poses, joints and goal) moves the first ``--episodes`` figures only through the
scenes it drops and adds. This evaluates exactly those, on both versions, and prints for
every family and robot how many scenes changed and the change in mean S and success that
they make: the new figure is the old one plus this change. A scene names its objects by
uuid, and a revised generator builds assets with new uuids, so a scene whose asset a library
revision rebuilt counts as changed (two snapshots give one uuid the same content).
"""

from __future__ import annotations

import argparse
import json
import tempfile
from pathlib import Path

import instructmove_ms  # noqa: F401
from instructmove_ms import heldout
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.evaluation import evaluate_config
from instructmove_ms.policies import REFERENCE_POLICIES
from instructmove_ms.tasks import TASKS

POLICIES = ("oracle", "blind")


def scene(spec: EpisodeSpec) -> tuple:
    """What a reference policy's row depends on."""
    return (
        spec.seed,
        spec.objects,
        spec.target,
        spec.candidates,
        spec.destinations,
        spec.goal_destination,
        spec.robot_qpos,
    )


def rows(policy: str, env_id: str, robot: str, specs: list[EpisodeSpec], out: Path) -> list:
    """The result rows of ``policy`` on ``specs`` (none for none)."""
    if not specs:
        return []
    config = heldout.config_of(env_id, robot, specs[0].split, "normal", specs)
    evaluate_config(REFERENCE_POLICIES[policy](), config, out)
    return [json.loads(line) for line in (out / "episodes.jsonl").read_text().splitlines()]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--episodes", type=int, default=40, help="first N of each set")
    parser.add_argument("--split", default="seen")
    parser.add_argument("--old", type=int, default=2, help="the set version figures are on")
    parser.add_argument("--new", type=int, default=heldout.SET_VERSION)
    parser.add_argument("--robot", default=None, help="one robot (default: every supported)")
    args = parser.parse_args()
    n = args.episodes
    print("| family | robot | scenes changed | policy | change in S | change in success |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for env_id, task in TASKS.items():
            for robot in [args.robot] if args.robot else task.supported_robots:
                old = heldout.load_set(env_id, robot, args.split, version=args.old)[:n]
                new = heldout.load_set(env_id, robot, args.split, version=args.new)[:n]
                kept = {scene(s) for s in old} & {scene(s) for s in new}
                dropped = [s for s in old if scene(s) not in kept]
                added = [s for s in new if scene(s) not in kept]
                for policy in POLICIES:
                    base = Path(tmp) / env_id / robot / policy
                    before = rows(policy, env_id, robot, dropped, base / "old")
                    after = rows(policy, env_id, robot, added, base / "new")
                    d_s = sum(r["stage_score"] for r in after) - sum(
                        r["stage_score"] for r in before
                    )
                    d_win = sum(r["success"] for r in after) - sum(r["success"] for r in before)
                    print(
                        f"| {task.family} | {robot} | {len(added)}/{n} | {policy} | "
                        f"{d_s / n:+.3f} | {d_win / n:+.3f} |",
                        flush=True,
                    )


if __name__ == "__main__":
    main()
