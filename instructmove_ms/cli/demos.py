"""``instructmove demos``: planned demonstrations."""

from __future__ import annotations

import argparse

from instructmove_ms.cli.common import _add_group, _add_workers, _workers


def _cmd_demos_generate(args: argparse.Namespace) -> int:
    import instructmove_ms  # noqa: F401  (registration)
    from instructmove_ms.demos.generate import generate

    report = generate(
        args.task,
        args.robot,
        args.n,
        args.out,
        args.seed0,
        _workers(args),
        args.shard_size,
        args.perturb,
        args.sampler,
    )
    print(
        f"{report.kept} demos from {report.tried} seeds ({report.rollouts} rollouts): "
        f"valid-synthesis rate {report.rate:.1%}"
    )
    print("failures: " + ", ".join(f"{k}={v}" for k, v in report.failures.items()))
    print(f"-> {report.path}")
    return 0


def _cmd_demos_convert(args: argparse.Namespace) -> int:
    import instructmove_ms  # noqa: F401  (registration)
    from instructmove_ms.demos.ee_control import convert

    report = convert(args.traj, args.control_mode, args.obs_mode, args.out, args.count)
    print(f"{report.kept}/{report.total} episodes converted successfully -> {report.path}")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.sampler import SAMPLER, SAMPLERS

    demos = _add_group(sub, "demos", "planned demonstrations")
    p = demos.add_parser("generate", help="record successful planned demos (resumable)")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default="franka")
    p.add_argument("-n", type=int, default=100, help="demos to keep")
    p.add_argument("--out", default="out/demos", help="output folder")
    p.add_argument("--seed0", type=int, default=0, help="first training seed")
    _add_workers(p, "one shard of seeds each")
    p.add_argument("--shard-size", type=int, default=5, help="demos per resumable shard")
    p.add_argument(
        "--perturb", default=None, help="perturbation levels of the demos, e.g. lighting:1,table:2"
    )
    p.add_argument(
        "--sampler",
        type=int,
        default=SAMPLER,
        choices=SAMPLERS,
        help=f"the sampler that draws the scenes (default {SAMPLER}, the one of the current "
        "held-out sets; 1 is InstructMove 1.0's)",
    )
    p.set_defaults(func=_cmd_demos_generate)
    p = demos.add_parser(
        "convert", help="pd_joint_pos demos to end-effector control (every arm of the robot)"
    )
    p.add_argument("--traj", required=True, help="pd_joint_pos trajectory .h5 (with .json)")
    p.add_argument("-c", "--control-mode", default="pd_ee_delta_pose", help="target mode")
    p.add_argument("-o", "--obs-mode", default="state", help="observations to record")
    p.add_argument("--out", default=None, help="output folder (default: the trajectory's)")
    p.add_argument("--count", type=int, default=None, help="first episodes only")
    p.set_defaults(func=_cmd_demos_convert)
