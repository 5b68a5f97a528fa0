"""``instructmove export``: convert recorded trajectories (MCAP, LeRobot)."""

from __future__ import annotations

import argparse

from instructmove_ms.cli.common import _add_group, _add_workers, _workers


def _cmd_export_mcap(args: argparse.Namespace) -> int:
    from instructmove_ms.export import ExportSettings, export_trajectory

    settings = ExportSettings(args.width, args.height, args.jpeg_quality)
    report = export_trajectory(args.traj, args.out, _workers(args), settings)
    print(
        f"{len(report.written)} episodes written ({report.bytes / 1e6:.1f} MB in "
        f"{report.seconds:.0f} s), {len(report.skipped)} already there -> {args.out}"
    )
    return 0


def _cmd_export_lerobot(args: argparse.Namespace) -> int:
    from instructmove_ms.export.lerobot import LeRobotSettings, export_lerobot

    settings = LeRobotSettings(args.repo_id, args.width, args.height, args.format)
    report = export_lerobot(args.traj, args.out, settings, _workers(args))
    print(
        f"{len(report.written)} episodes written ({report.frames} frames, "
        f"{report.bytes / 1e6:.1f} MB in {report.seconds:.0f} s), {len(report.skipped)} already "
        f"there -> LeRobot {args.format} dataset {args.out}"
    )
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.export.lerobot_formats import DEFAULT_FORMAT, FORMATS

    export = _add_group(sub, "export", "convert recorded trajectories")
    p = export.add_parser("mcap", help="one MCAP per episode (Foxglove schemas, cameras rendered)")
    p.add_argument("--traj", required=True, help="trajectory .h5 (with .json, .episodes.json)")
    p.add_argument("--out", required=True, help="output folder (resumable)")
    _add_workers(p, "rendering one episode at a time each")
    p.add_argument("--width", type=int, default=None, help="camera width (default: robot's)")
    p.add_argument("--height", type=int, default=None, help="camera height (default: robot's)")
    p.add_argument("--jpeg-quality", type=int, default=90, help="colour image JPEG quality")
    p.set_defaults(func=_cmd_export_mcap)
    p = export.add_parser(
        "lerobot", help="one LeRobot dataset (parquet + MP4) from trajectories of one robot"
    )
    p.add_argument(
        "--traj", required=True, action="append", help="trajectory .h5 (repeat for several)"
    )
    p.add_argument("--out", required=True, help="dataset folder (resumable)")
    p.add_argument("--repo-id", required=True, help="the dataset's name, e.g. me/instructmove")
    p.add_argument("--width", type=int, default=224, help="camera width")
    p.add_argument("--height", type=int, default=224, help="camera height")
    p.add_argument(
        "--format",
        choices=FORMATS,
        default=DEFAULT_FORMAT,
        help="LeRobot format: v3.0 (lerobot >= 0.4) or v2.1 (openpi, GR00T, lerobot 0.3)",
    )
    _add_workers(p, "rendering one episode at a time each")
    p.set_defaults(func=_cmd_export_lerobot)
