"""The end-to-end quickstart on the embedded assets, on a CPU: a few planned demos per family,
one trajectory exported to MCAP, every robot's demos exported to a LeRobot dataset (what a
VLA is fine-tuned on), the reference policies evaluated side by side on a small held-out
slice of every family, a report and videos with the instruction overlaid.

Every step resumes: re-running with the same ``out`` folder redoes only what is missing.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .demos.generate import generate
from .evaluation import evaluate
from .export import ExportSettings, export_trajectory
from .export.lerobot import LeRobotSettings, export_lerobot
from .files import write_json, write_text
from .metrics import comparison_table
from .policies import REFERENCE_POLICIES
from .tasks import TASKS
from .video import VideoSettings

SPLIT = "seen"
#: The upper bound, the learned grounding model (the planner acting), chance and the floor.
POLICIES = ("oracle", "grounded", "blind", "random")


@dataclass(frozen=True)
class QuickstartSettings:
    """How much work each step does."""

    demos: int = 2  # planned demos per family (its default robot)
    episodes: int = 5  # held-out episodes per family and policy
    videos: int = 1  # oracle videos per family
    workers: int = 2  # processes for demos and MCAP rendering
    export_size: int = 128  # camera resolution of the MCAP export
    lerobot_size: int = 224  # camera resolution of the LeRobot datasets

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if value < (0 if name == "videos" else 1):
                raise ValueError(f"quickstart {name} must be at least 1, got {value}")


def _step(text: str) -> None:
    print(f"\n== {text}", flush=True)


def run(out: Path, settings: QuickstartSettings = QuickstartSettings()) -> Path:
    """Run every step into ``out``; returns the path of the combined report."""
    out.mkdir(parents=True, exist_ok=True)
    lines = ["# InstructMove quickstart\n"]
    _step(f"1/4 planned demos: {settings.demos} per family")
    trajectories = {}
    for task, spec in TASKS.items():
        report = generate(
            task, spec.default_robot, settings.demos, out / "demos", workers=settings.workers
        )
        trajectories[task] = report.path
        lines.append(
            f"- demos `{report.path.relative_to(out)}`: {task} with {spec.default_robot}, "
            f"valid-synthesis rate {report.rate:.0%}"
        )
    _step("2/4 MCAP export of the PickCategory demos (cameras rendered)")
    first = next(iter(trajectories.values()))
    size = settings.export_size
    exported = export_trajectory(first, out / "mcap", settings.workers, ExportSettings(size, size))
    for path in sorted(exported.written + exported.skipped):
        lines.append(f"- MCAP `{path.relative_to(out)}`")
    _step("3/4 LeRobot v3.0 datasets of the demos, one per robot")
    robots: dict[str, list[Path]] = {}
    for task, path in trajectories.items():
        robots.setdefault(TASKS[task].default_robot, []).append(path)
    size = settings.lerobot_size
    for robot, paths in robots.items():
        folder = out / "lerobot" / robot
        export_lerobot(
            paths,
            folder,
            LeRobotSettings(f"instructmove/quickstart_{robot}", size, size),
            settings.workers,
        )
        lines.append(f"- LeRobot dataset `{folder.relative_to(out)}`: {robot}, {len(paths)} tasks")
    _step(f"4/4 evaluation: {', '.join(POLICIES)} on {settings.episodes} episodes per family")
    runs: dict[str, list[dict]] = {name: [] for name in POLICIES}
    for task in TASKS:
        for name in POLICIES:
            folder = out / "eval" / task / name
            video = VideoSettings(first=settings.videos, width=256, height=256)
            summary = evaluate(
                REFERENCE_POLICIES[name](),
                task,
                SPLIT,
                folder,
                episodes=settings.episodes,
                video=video if name == "oracle" and settings.videos else None,
            )
            runs[name] += summary["groups"]
            lines += [
                f"- video `{v.relative_to(out)}`" for v in sorted(folder.glob("videos/*.mp4"))
            ]
    lines += ["", "## Reference policies, Reach/Lift (S)", "", comparison_table(runs), ""]
    report = write_text(out / "report.md", "\n".join(lines[:1] + ["## Outputs", ""] + lines[1:]))
    write_json(out / "summary.json", runs)
    return report
