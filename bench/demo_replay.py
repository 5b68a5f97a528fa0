"""Demo acceptance: generated demos replayed by ManiSkill's own command.

For every family and robot, writes ``-n`` demos with ``instructmove demos generate``,
replays them with ``python -m mani_skill.trajectory.replay_trajectory --save-traj`` to the
rgb observation mode and to the ``pd_joint_delta_pos`` control mode, and converts them to
``pd_ee_delta_pose`` with ``instructmove demos convert`` (every arm; ManiSkill's converter
drives one), printing the share of demos whose replay or conversion succeeds (target: at
least 95%) next to the valid-synthesis rate and the seconds each step took.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from instructmove_ms.demos.ee_control import convert
from instructmove_ms.demos.generate import generate
from instructmove_ms.tasks import TASKS

#: (observation mode, target control mode) of each replay by ManiSkill's command.
REPLAYS = {"rgb": ("rgb", None), "pd_joint_delta_pos": ("state", "pd_joint_delta_pos")}
EE_MODE = "pd_ee_delta_pose"  # converted with our converter


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
    parser.add_argument(
        "--modes",
        nargs="+",
        default=[*REPLAYS, EE_MODE],
        choices=[*REPLAYS, EE_MODE],
        help="replays to run (default: all)",
    )
    args = parser.parse_args()
    for task in [args.task] if args.task else list(TASKS):
        for robot in [args.robot] if args.robot else TASKS[task].supported_robots:
            with tempfile.TemporaryDirectory() as tmp:
                start = time.perf_counter()
                report = generate(task, robot, args.n, tmp, workers=args.workers)
                failed = ", ".join(f"{k} {v}" for k, v in report.failures.items() if v)
                took = time.perf_counter() - start
                cells = [
                    f"generated {report.rate:.0%} valid [{failed or 'no failures'}] ({took:.0f} s)"
                ]
                for mode in args.modes:
                    start = time.perf_counter()
                    if mode == EE_MODE:
                        converted = convert(report.path, EE_MODE)
                        saved = f"{converted.kept}/{converted.total}"
                    else:
                        saved = replay(report.path, *REPLAYS[mode], args.workers)
                    cells.append(f"{mode} {saved} ({time.perf_counter() - start:.0f} s)")
            print(f"{task:28s} {robot:7s} " + "; ".join(cells), flush=True)


if __name__ == "__main__":
    main()
