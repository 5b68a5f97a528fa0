"""``instructmove envs`` and ``instructmove episode``: the registered envs and a seed's episode."""

from __future__ import annotations

import argparse
import json


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
    from instructmove_ms.tasks import TASKS
    from instructmove_ms.validation import check_choice

    check_choice("task", args.task, TASKS)

    env = gym.make(
        args.task,
        robot_uids=args.robot,
        split=args.split,
        condition=args.condition,
        perturbation=args.perturb,
        obs_mode="state",
        render_backend="none" if args.no_render else "cpu",
    )
    env.reset(seed=args.seed)
    print(json.dumps(env.unwrapped.episode.to_dict(), indent=2))
    env.close()
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("envs", help="list the registered InstructMove envs")
    p.set_defaults(func=_cmd_envs)
    p = sub.add_parser("episode", help="print the episode spec a seed gives, as JSON")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default=None, help="robot uid (default: the task's)")
    p.add_argument("--split", default="train")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--condition", default="normal", help="instruction condition")
    p.add_argument("--no-render", action="store_true", help="build the scene without a renderer")
    p.add_argument("--perturb", default=None, help="perturbation levels, e.g. lighting:2,camera:1")
    p.set_defaults(func=_cmd_episode)
