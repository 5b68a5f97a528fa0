"""Export speed (MCAP and LeRobot) against ManiSkill's own replay of the same trajectory.

Generates a demo trajectory (or takes ``--traj``), then times, each in a fresh process:

- baseline: ``python -m mani_skill.trajectory.replay_trajectory -o rgbd --use-env-states
  --save-traj`` (replays the recorded states and stores the rgbd observations in an .h5), at
  the robot's default camera resolution;
- mcap: ``instructmove export mcap`` (renders the same cameras from the same states and
  writes one MCAP per episode: JPEG colour, PNG depth, joints, transforms, metadata), same
  resolution;
- lerobot: ``instructmove export lerobot`` at the same resolution (colour only, AV1 video,
  parquet frames, LeRobot's metadata and statistics), and lerobot-224 at its default
  224 x 224.

They alternate ``--repeats`` times (timings vary with load); medians are reported:
episodes/min, rendered states/s and output MB/s of each, and the ratios to the baseline.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TASK, ROBOT = "PickCategory-InstructMove", "franka"
DEFAULT = (160, 90)  # the robots' default camera resolution


def timed(cmd: list[str], cwd: Path) -> float:
    start = time.perf_counter()
    result = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if result.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{result.stderr[-3000:]}")
    return seconds


def report(name: str, seconds: float, episodes: int, states: int, size: int) -> dict:
    row = dict(
        size=size,
        episodes_per_min=episodes / seconds * 60,
        states_per_s=states / seconds,
        mb_per_s=size / 1e6 / seconds,
    )
    print(
        f"{name:11s} {seconds:7.1f} s  {row['episodes_per_min']:6.2f} episodes/min  "
        f"{row['states_per_s']:6.1f} states/s  {size / 1e6:7.1f} MB -> {row['mb_per_s']:5.2f} MB/s"
    )
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--traj", default=None, help="trajectory .h5 (default: generate demos)")
    parser.add_argument("--episodes", type=int, default=2, help="demos to generate")
    parser.add_argument("--workers", type=int, default=1, help="export worker processes")
    parser.add_argument("--repeats", type=int, default=2, help="timed runs of each")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        if args.traj is None:
            from instructmove_ms.demos.generate import generate

            traj = generate(TASK, ROBOT, args.episodes, work / "demos").path
        else:
            traj = Path(args.traj).resolve()
        for suffix in (".h5", ".json", ".episodes.json"):
            shutil.copy(traj.with_name(traj.stem + suffix), work / f"input{suffix}")
        meta = json.loads((work / "input.json").read_text())
        episodes = len(meta["episodes"])
        states = sum(e["elapsed_steps"] + 1 for e in meta["episodes"])
        print(f"{episodes} episodes, {states} states, {meta['env_info']['env_id']}")

        replay = [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
        replay += ["--traj-path", "input.h5", "-o", "rgbd", "-b", "physx_cpu"]
        replay += ["--use-env-states", "--save-traj"]
        cli = [sys.executable, "-m", "instructmove_ms.cli", "export"]
        common = ["--traj", "input.h5", "--workers", str(args.workers)]
        size = ["--width", str(DEFAULT[0]), "--height", str(DEFAULT[1])]
        lerobot = [*cli, "lerobot", *common, "--repo-id", "bench/demos"]
        exports = {
            "mcap": [*cli, "mcap", *common, "--out", "mcap"],
            "lerobot": [*lerobot, *size, "--out", "lerobot"],
            "lerobot-224": [*lerobot, "--out", "lerobot-224"],
        }
        replayed = work / "input.rgbd.pd_joint_pos.physx_cpu.h5"
        times: dict[str, list[float]] = {name: [] for name in ("baseline", *exports)}
        for _ in range(args.repeats):
            replayed.unlink(missing_ok=True)
            times["baseline"].append(timed(replay, work))
            for name, command in exports.items():
                shutil.rmtree(work / name, ignore_errors=True)  # else the export resumes
                times[name].append(timed(command, work))
        sizes = {"baseline": replayed.stat().st_size}
        sizes.update({name: folder_size(work / name) for name in exports})
        rows = {
            name: report(name, statistics.median(t), episodes, states, sizes[name])
            for name, t in times.items()
        }
    base = rows["baseline"]
    for name in exports:
        ours = rows[name]
        print(
            f"ratio {name}/baseline: {ours['episodes_per_min'] / base['episodes_per_min']:.2f}x "
            f"episodes/min, {ours['mb_per_s'] / base['mb_per_s']:.2f}x MB/s; "
            f"output {ours['size'] / base['size']:.3f}x the size"
        )


def folder_size(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())


if __name__ == "__main__":
    main()
