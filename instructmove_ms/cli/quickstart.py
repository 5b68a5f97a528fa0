"""``instructmove quickstart``: demos, MCAP, evaluation and report end to end."""

from __future__ import annotations

import argparse


def _cmd_quickstart(args: argparse.Namespace) -> int:
    from pathlib import Path

    from instructmove_ms.quickstart import QuickstartSettings, run

    settings = QuickstartSettings(args.demos, args.episodes, args.videos, args.workers)
    report = run(Path(args.out), settings)
    print(f"\nreport: {report}")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("quickstart", help="demos, MCAP, evaluation and report end to end")
    p.add_argument("--out", default="out/quickstart", help="output folder (resumable)")
    p.add_argument("--demos", type=int, default=2, help="planned demos per family")
    p.add_argument("--episodes", type=int, default=5, help="held-out episodes per policy")
    p.add_argument("--videos", type=int, default=1, help="oracle videos per family")
    p.add_argument("--workers", type=int, default=2, help="processes for demos and MCAP")
    p.set_defaults(func=_cmd_quickstart)
