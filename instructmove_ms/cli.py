"""The ``instructmove`` command line."""

from __future__ import annotations

import argparse
import json
import sys


def _cmd_envs(args: argparse.Namespace) -> int:
    from instructmove_ms.tasks import TASKS

    for env_id, spec in TASKS.items():
        print(
            f"{env_id}\tfamily={spec.family}\trobots={','.join(spec.supported_robots)}"
            f"\thorizon={spec.max_episode_steps}"
        )
    return 0


def _cmd_episode(args: argparse.Namespace) -> int:
    import gymnasium as gym

    import instructmove_ms  # noqa: F401  (registration)

    env = gym.make(
        args.task,
        robot_uids=args.robot,
        split=args.split,
        obs_mode="state",
        render_backend="none" if args.no_render else "cpu",
    )
    env.reset(seed=args.seed)
    print(json.dumps(env.unwrapped.episode.to_dict(), indent=2))
    env.close()
    return 0


def _cmd_assets(args: argparse.Namespace) -> int:
    from instructmove_ms.assets import load_snapshot

    catalog = load_snapshot(args.snapshot)
    for inst in catalog.instances:
        if args.category and inst.category != args.category:
            continue
        print(json.dumps(inst.annotation()))
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="instructmove", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("envs", help="list the registered InstructMove envs")
    p.set_defaults(func=_cmd_envs)
    p = sub.add_parser("episode", help="print the episode spec a seed gives, as JSON")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default=None, help="robot uid (default: the task's)")
    p.add_argument("--split", default="train")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--no-render", action="store_true", help="build the scene without a renderer")
    p.set_defaults(func=_cmd_episode)
    p = sub.add_parser("assets", help="print the annotations of a snapshot, one JSON per line")
    p.add_argument("--snapshot", default="default")
    p.add_argument("--category", default=None)
    p.set_defaults(func=_cmd_assets)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, KeyError) as exc:
        print(f"instructmove: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
