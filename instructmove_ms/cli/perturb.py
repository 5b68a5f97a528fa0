"""``instructmove perturb``: the perturbation axes."""

from __future__ import annotations

import argparse

from instructmove_ms.cli.common import _add_group


def _cmd_perturb_sheet(args: argparse.Namespace) -> int:
    from pathlib import Path

    import instructmove_ms  # noqa: F401  (registration)
    from instructmove_ms.perturb_sheet import sheets
    from instructmove_ms.perturbation import AXES
    from instructmove_ms.tasks import TASKS
    from instructmove_ms.validation import check_choice

    check_choice("task", args.task, TASKS)
    axes = args.axes.split(",") if args.axes else AXES
    for path in sheets(args.task, args.robot, args.seed, Path(args.out), axes):
        print(path)
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    perturb = _add_group(sub, "perturb", "perturbation axes")
    p = perturb.add_parser("sheet", help="one PNG per axis: a scene at levels 0-3")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default=None, help="robot uid (default: the task's)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--axes", default=None, help="comma-separated axes (default: every one)")
    p.add_argument("--out", required=True, help="folder for <axis>.png")
    p.set_defaults(func=_cmd_perturb_sheet)
