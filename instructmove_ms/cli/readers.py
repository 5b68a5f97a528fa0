"""``instructmove readers``: material for fresh readers, drawn from a seed, and the scorer
of their answers (docs/readers.md)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from instructmove_ms.cli.common import _add_group, _add_set_version


def _cmd_draw(args: argparse.Namespace) -> int:
    from instructmove_ms.readers import material

    out = Path(args.out)
    kind = args.readers_command.replace("-", "_")
    if kind == "close_ups":
        from instructmove_ms.assets.snapshot import load_snapshot

        catalog = load_snapshot(args.snapshot)
        if args.library:
            catalog = material.at_revision(catalog, args.library)
        key = material.close_ups(catalog, args.seed, out, args.only, args.every_instance)
    elif kind == "in_scene":
        import instructmove_ms  # noqa: F401  (registration)
        from instructmove_ms.assets.snapshot import load_snapshot

        key = material.in_scene(
            load_snapshot(args.snapshot),
            args.seed,
            out,
            args.set_version,
            args.only,
            args.cameras,
            args.resolution,
        )
    elif kind == "instructions":
        import instructmove_ms  # noqa: F401  (registration)

        key = material.instructions(args.seed, out, args.n, args.set_version, args.source)
    else:
        import instructmove_ms  # noqa: F401  (registration)

        key = material.episodes(args.seed, out, args.n, args.set_version)
    print(f"give a reader {out / 'reader'} (its BRIEF.txt says what to do); keep {key} apart")
    return 0


def _cmd_brief(args: argparse.Namespace) -> int:
    from instructmove_ms.readers.briefs import brief

    print(brief(args.kind.replace("-", "_")), end="")
    return 0


def _cmd_score(args: argparse.Namespace) -> int:
    from instructmove_ms.readers.score import score

    result = score(Path(args.key), [Path(p) for p in args.answers], args.agreement)
    if args.json:
        print(json.dumps(result, indent=1))
        return 0
    print(
        f"{result['kind']} (seed {result['seed']}): {result['passed']} of {result['items']} "
        f"with at least {result['agreement']} of {result['readers']} readers; per reader "
        f"{', '.join(map(str, result['per_reader']))}"
    )
    for row in result.get("judgements", []):
        print("  " + ", ".join(f"{k} {v}" for k, v in row.items()))
    for item in result["detail"]:
        if not item["passed"]:
            what = item.get("category") or item.get("instruction")
            print(f"  missed {item['n']}: {what}: {' | '.join(item['answers'])}")
    return 0


KINDS = ("close-ups", "in-scene", "instructions", "episodes")


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.assets.snapshot import DEFAULT_SNAPSHOT
    from instructmove_ms.readers import CAMERAS, POLICY_RESOLUTION, SOURCES

    group = _add_group(sub, "readers", "material for fresh readers and the scorer of answers")
    helps = {
        "close-ups": "a close-up of a random instance of every category",
        "in-scene": "every category boxed in a stored scene at the policy's 224 x 224",
        "instructions": "a random sample of instructions, stored and of training seeds",
        "episodes": "random stored episodes from every camera at 224 x 224",
    }
    for kind in KINDS:
        p = group.add_parser(kind, help=helps[kind])
        p.add_argument("--seed", type=int, required=True, help="a new seed every round")
        p.add_argument("--out", required=True, help="folder: reader/ for the reader, key.json")
        if kind in ("close-ups", "in-scene"):
            p.add_argument("--snapshot", default=DEFAULT_SNAPSHOT, help="(default: %(default)s)")
            p.add_argument(
                "--only", nargs="+", metavar="CATEGORY", help="these categories (default: all)"
            )
        if kind == "in-scene":
            p.add_argument(
                "--cameras",
                choices=CAMERAS,
                default="scene",
                help="show each object in the scene camera that shows most of it, or in any "
                "camera the policy reads, wrist cameras too (default: %(default)s)",
            )
            p.add_argument(
                "--resolution",
                type=int,
                default=POLICY_RESOLUTION,
                metavar="PIXELS",
                help="side of the square pictures: the policy's by default; a larger one "
                "tells what the objects show from what the policy's pixels keep of them "
                "(default: %(default)s)",
            )
        if kind == "close-ups":
            p.add_argument(
                "--library",
                type=int,
                metavar="N",
                help="the snapshot's instances as library revision N builds them (to judge "
                "a revision before a snapshot freezes it)",
            )
            p.add_argument(
                "--every-instance",
                action="store_true",
                help="every instance of the categories, not one random one (to screen a "
                "library instance by instance)",
            )
        else:
            _add_set_version(p)
        if kind in ("instructions", "episodes"):
            p.add_argument(
                "--n",
                type=int,
                default=200 if kind == "instructions" else 40,
                help="how many (default: %(default)s)",
            )
        if kind == "instructions":
            p.add_argument(
                "--source",
                choices=SOURCES,
                default="both",
                help="stored sets, training seeds, or half of each (default: %(default)s)",
            )
        p.set_defaults(func=_cmd_draw)
    p = group.add_parser("brief", help="print what a reader of KIND is told")
    p.add_argument("kind", choices=KINDS)
    p.set_defaults(func=_cmd_brief)
    p = group.add_parser("score", help="score readers' answer files against a key")
    p.add_argument("key", help="key.json of the material the readers saw")
    p.add_argument("answers", nargs="+", help="one answer file per reader (N: answer lines)")
    p.add_argument("--agreement", type=int, help="readers who must agree (default: 2/3)")
    p.add_argument("--json", action="store_true", help="every figure and answer as JSON")
    p.set_defaults(func=_cmd_score)
