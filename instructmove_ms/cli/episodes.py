"""``instructmove episodes``: the held-out evaluation episode sets."""

from __future__ import annotations

import argparse
import json

from instructmove_ms.cli.common import _add_group, _add_set_version


def _cmd_episodes_write(args: argparse.Namespace) -> int:
    from pathlib import Path

    import gymnasium as gym
    from tqdm import tqdm

    import instructmove_ms  # noqa: F401  (registration)
    from instructmove_ms import heldout
    from instructmove_ms.splits import EVAL_SPLITS
    from instructmove_ms.tasks import TASKS

    tasks = [args.task] if args.task else list(TASKS)
    out = Path(args.out)
    for env_id in tasks:
        for robot in [args.robot] if args.robot else TASKS[env_id].supported_robots:
            for split in EVAL_SPLITS:
                path = heldout.set_path(env_id, robot, split, out)
                if path.is_file() and len(heldout.load_set(env_id, robot, split, out)) == args.n:
                    tqdm.write(f"kept {path} (written before)")
                    continue
                env = gym.make(
                    env_id, robot_uids=robot, split=split, sampler=args.sampler, obs_mode="state"
                )
                measured = (
                    heldout.load_set(env_id, robot, split, version=args.measured_in)
                    if args.measured_in
                    else []
                )
                specs = list(
                    tqdm(
                        heldout.generate_set(env, args.n, tuple(measured)),
                        total=args.n,
                        desc=f"{env_id} {robot} {split}",
                        unit="episode",
                    )
                )
                env.close()
                path = heldout.write_set(path, specs)
                tqdm.write(f"{len(specs)} episodes -> {path}")
    heldout.write_checksums(out)
    return 0


def _cmd_episodes_show(args: argparse.Namespace) -> int:
    from instructmove_ms import heldout
    from instructmove_ms.tasks import TASKS

    robot = args.robot or TASKS[args.task].default_robot
    specs = heldout.load_set(args.task, robot, args.split, version=args.set_version)
    if not 0 <= args.index < len(specs):
        raise ValueError(f"--index {args.index} outside the set's 0..{len(specs) - 1}")
    print(json.dumps(specs[args.index].to_dict(), indent=2))
    return 0


def _cmd_episodes_sheet(args: argparse.Namespace) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from instructmove_ms.episode_sheet import episode_sheet
    from instructmove_ms.splits import EVAL_SPLITS
    from instructmove_ms.tasks import TASKS
    from instructmove_ms.validation import check_choice

    check_choice("task", args.task, TASKS)
    robot = args.robot or TASKS[args.task].default_robot
    for split in tqdm([args.split] if args.split else EVAL_SPLITS, desc="sheets", unit="sheet"):
        name = f"{TASKS[args.task].family}_{robot}_{split}.png"
        path = episode_sheet(
            args.task, robot, split, Path(args.out) / name, args.n, version=args.set_version
        )
        tqdm.write(str(path))
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.heldout import SET_VERSIONS

    episodes_sub = _add_group(sub, "episodes", "held-out evaluation episode sets")
    from instructmove_ms.sampler import SAMPLER, SAMPLERS

    p = episodes_sub.add_parser(
        "write",
        help="sample and store the held-out sets (a complete set file is kept: rerun to resume)",
    )
    p.add_argument("--task", default=None, help="one env id (default: every family)")
    p.add_argument("--robot", default=None, help="one robot (default: every supported one)")
    p.add_argument("--n", type=int, default=100, help="episodes per set")
    p.add_argument(
        "--out",
        required=True,
        help="folder for the sets (released sets in the package are never written over; a "
        "new benchmark version's sets go in a new tasks/episodes/v<N>)",
    )
    p.add_argument(
        "--measured-in",
        type=int,
        default=None,
        choices=SET_VERSIONS,
        help="a stored set version whose visibility figures are reused for the same scenes "
        "(only new scenes are rendered)",
    )
    p.add_argument(
        "--sampler",
        type=int,
        default=SAMPLER,
        choices=SAMPLERS,
        help=f"the sampler that draws the scenes (default {SAMPLER}, the symmetric one; "
        "1 is InstructMove 1.0's)",
    )
    p.set_defaults(func=_cmd_episodes_write)
    p = episodes_sub.add_parser("show", help="print one stored held-out episode spec")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default=None)
    p.add_argument("--split", default="seen")
    p.add_argument("--index", type=int, default=0)
    _add_set_version(p)
    p.set_defaults(func=_cmd_episodes_show)
    p = episodes_sub.add_parser(
        "sheet", help="contact sheet PNGs of stored episodes with their instructions"
    )
    p.add_argument("--task", required=True, help="env id")
    p.add_argument("--robot", default=None, help="default: the family's robot")
    p.add_argument("--split", default=None, help="one split (default: every one)")
    p.add_argument("--n", type=int, default=20, help="episodes per sheet")
    p.add_argument("--out", required=True, help="folder for <family>_<robot>_<split>.png")
    _add_set_version(p)
    p.set_defaults(func=_cmd_episodes_sheet)
