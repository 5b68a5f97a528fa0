"""The privileged oracle under every perturbation axis and level, on both robots.

For each family and robot it runs ``instructmove eval --policy oracle --perturb sweep`` on
the first ``--episodes`` stored ``seen`` episodes (the same episodes at every level) and
prints the oracle's stage score S per axis and level, its lowest S, and every setting where
S falls below the target of 0.95 (a drop there would measure the scene, not a policy).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import tempfile
from pathlib import Path

from instructmove_ms.cli import main as cli
from instructmove_ms.perturbation import AXES, MAX_LEVEL
from instructmove_ms.tasks import TASKS

TARGET = 0.95


def sweep(task: str, robot: str, episodes: int, workers: int, out: Path) -> list[dict]:
    argv = ["eval", "--task", task, "--robot", robot, "--policy", "oracle", "--perturb", "sweep"]
    argv += ["--episodes", str(episodes), "--workers", str(workers), "--out", str(out)]
    with contextlib.redirect_stdout(io.StringIO()):
        if cli(argv) != 0:
            raise RuntimeError(f"eval failed: {' '.join(argv)}")
    return json.loads((out / "summary.json").read_text())["robustness"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--episodes", type=int, default=10, help="stored episodes per set")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--robots", default="franka,piperx")
    args = parser.parse_args()
    print(f"oracle S per axis at levels 0..{MAX_LEVEL} ({args.episodes} episodes each)")
    below = []
    with tempfile.TemporaryDirectory() as tmp:
        for robot in args.robots.split(","):
            for task in sorted(TASKS):
                if robot not in TASKS[task].supported_robots:
                    continue
                rows = sweep(task, robot, args.episodes, args.workers, Path(tmp) / task / robot)
                score = {(r["axis"], r["level"]): r["stage_score"] for r in rows}
                cells = [
                    f"{axis} " + "/".join(f"{score[axis, k]:.2f}" for k in range(MAX_LEVEL + 1))
                    for axis in AXES
                ]
                print(f"{task:<28} {robot:<7} min {min(score.values()):.2f}  " + "  ".join(cells))
                below += [(task, robot, *key, s) for key, s in score.items() if s < TARGET]
    print(f"settings below {TARGET}: {len(below)}")
    for task, robot, axis, level, s in below:
        print(f"  {task} {robot} {axis}:{level} S {s:.2f}")


if __name__ == "__main__":
    main()
