"""Demo acceptance: generated demos replayed by ManiSkill's own command.

For every family and robot, writes ``-n`` demos with ``instructmove demos generate`` and
replays them with ``python -m mani_skill.trajectory.replay_trajectory --save-traj`` to the
rgb observation mode and to the ``pd_joint_delta_pos`` and ``pd_ee_delta_pose`` control
modes, printing the share of demos whose replay succeeds (target: at least 95%) next to the
valid-synthesis rate and the seconds each step took.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from instructmove_ms.demos.generate import generate
from instructmove_ms.tasks import TASKS

#: (observation mode, target control mode) of each replay.
REPLAYS = (("rgb", None), ("state", "pd_joint_delta_pos"), ("state", "pd_ee_delta_pose"))


def replay(traj: Path, obs_mode: str, control_mode: str | None, procs: int) -> str:
    """ManiSkill's replay; returns its ``saved/total`` figure or the error's last line."""
    cmd = [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
    cmd += ["--traj-path", traj.name, "-o", obs_mode, "--save-traj", "-b", "physx_cpu"]
    cmd += ["-n", str(procs)] + (["-c", control_mode] if control_mode else [])
    result = subprocess.run(cmd, cwd=traj.parent, capture_output=True, text=True)
    found = re.search(r"Replayed (\d+) episodes, (\d+)/\d+", result.stdout + result.stderr)
    if result.returncode or not found:
        lines = result.stderr.strip().splitlines() or ["?"]
        errors = [line for line in lines if re.match(r"\w+(Error|Exception)\b", line)]
        return "failed: " + (errors or lines)[-1][:120]
    return f"{found[2]}/{found[1]}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("-n", type=int, default=20, help="demos per family and robot")
    parser.add_argument("--task", default=None, help="one env id (default: every family)")
    parser.add_argument("--robot", default=None, help="one robot (default: both)")
    parser.add_argument("--workers", type=int, default=2, help="generator and replay processes")
    args = parser.parse_args()
    for task in [args.task] if args.task else list(TASKS):
        for robot in [args.robot] if args.robot else TASKS[task].supported_robots:
            with tempfile.TemporaryDirectory() as tmp:
                start = time.perf_counter()
                report = generate(task, robot, args.n, tmp, workers=args.workers)
                cells = [f"generated {report.rate:.0%} valid ({time.perf_counter() - start:.0f} s)"]
                for obs_mode, control_mode in REPLAYS:
                    start = time.perf_counter()
                    saved = replay(report.path, obs_mode, control_mode, args.workers)
                    took = time.perf_counter() - start
                    mode = f"{obs_mode}/{control_mode or 'pd_joint_pos'}"
                    cells.append(f"{mode} {saved} ({took:.0f} s)")
            print(f"{task:28s} {robot:7s} " + "; ".join(cells), flush=True)


if __name__ == "__main__":
    main()
