"""``instructmove audit``: can a language-blind adversary tell the target apart?"""

from __future__ import annotations

import argparse


def _cmd_audit(args: argparse.Namespace) -> int:
    from pathlib import Path

    from instructmove_ms import audit

    folder = Path(args.sets) if args.sets else None
    cells, paths = audit.run(
        Path(args.out),
        args.set_version,
        folder,
        args.training_scenes,
        args.fresh_scenes,
        sampler=args.sampler,
        pixel_scenes=args.pixel_scenes,
    )
    failed = [c for c in cells if c.failed]
    for c in sorted(failed, key=lambda c: -c.z):
        print(
            f"failed: {c.family} {c.kind}, {c.source}, {c.split}: {c.adversary} "
            f"{c.accuracy:.2f} against chance {c.chance:.2f} (z {c.z:+.1f})"
        )
    gated = sum(c.gated for c in cells)
    print(f"{len(failed)} of {gated} gated cells failed; report: {paths[1]}")
    return 1 if failed else 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.audit import PIXEL_SCENES, TRAINING_SCENES
    from instructmove_ms.cli.common import _add_set_version
    from instructmove_ms.sampler import SAMPLERS

    p = sub.add_parser(
        "audit",
        help="language-blind adversaries (rules and learners that never read the instruction) "
        "against the stored sets: exits 1 when one beats chance",
    )
    _add_set_version(p)
    p.add_argument("--sets", help="audit the sets under this folder (episodes write --out)")
    p.add_argument("--out", default="out/audit", help="report folder (default out/audit)")
    p.add_argument(
        "--training-scenes",
        type=int,
        default=TRAINING_SCENES,
        help=f"training scenes per family the learners train on (default {TRAINING_SCENES}; "
        "0 skips them)",
    )
    p.add_argument(
        "--fresh-scenes",
        type=int,
        default=0,
        help="also judge the sampler on this many fresh evaluation scenes per family and split "
        "(seeds no stored set reaches; default 0)",
    )
    p.add_argument(
        "--pixel-scenes",
        type=int,
        default=0,
        help="also judge the sets with the pixel adversary (a network on each option's crops "
        "in the 224 x 224 cameras), trained on this many rendered training scenes per family "
        f"and robot (default 0: off; {PIXEL_SCENES} for the figures in docs/audit.md)",
    )
    p.add_argument(
        "--sampler",
        type=int,
        choices=SAMPLERS,
        help="audit this sampler's fresh scenes alone, no stored sets (with --fresh-scenes; "
        "1 is InstructMove 1.0's, 2 the symmetric one)",
    )
    p.set_defaults(func=_cmd_audit)
