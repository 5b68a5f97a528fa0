"""``instructmove eval``: evaluate a policy on a held-out set or evaluator config."""

from __future__ import annotations

import argparse
import json

from instructmove_ms.cli.common import _add_set_version, _add_workers, _workers

SERVED = ("ws://", "wss://", "zmq://")  # a policy server's address
GROUNDED = "grounded"  # the grounding model's policy, with its checkpoint after a colon


def _load_policy(spec: str, args: argparse.Namespace):
    """A reference policy name, ``grounded[:CHECKPOINT]``, ``ws://HOST:PORT`` (openpi's
    server), ``zmq://HOST:PORT`` (GR00T's) or ``MODULE:CLASS``."""
    import importlib

    from instructmove_ms.policies import REFERENCE_POLICIES

    if spec in REFERENCE_POLICIES:
        return REFERENCE_POLICIES[spec]()
    if spec.startswith(f"{GROUNDED}:"):
        from instructmove_ms.policies import GroundedPolicy

        return GroundedPolicy(spec.partition(":")[2])
    if spec.startswith(SERVED):
        from instructmove_ms.remote import RemotePolicy

        return RemotePolicy(
            spec,
            obs_format=args.obs_format,
            control_mode=args.control_mode,
            replan_steps=args.replan_steps,
            obs_mode=args.obs_mode,
            image_size=args.image_size,
        )
    module, _, name = spec.partition(":")
    if not name:
        raise ValueError(
            f"unknown policy {spec!r}; allowed: {', '.join(sorted(REFERENCE_POLICIES))}, "
            "grounded:CHECKPOINT, ws://HOST:PORT, zmq://HOST:PORT or MODULE:CLASS"
        )
    try:
        found = importlib.import_module(module)
    except ImportError as exc:
        raise ValueError(f"policy {spec!r}: cannot import module {module!r} ({exc})") from None
    if not hasattr(found, name):
        raise ValueError(f"policy {spec!r}: module {module!r} has no {name!r}")
    try:
        return getattr(found, name)()
    except TypeError as exc:
        raise ValueError(f"policy {spec!r} cannot be made without arguments ({exc})") from None


def _image_size(text: str) -> tuple[int, int]:
    """``WxH`` -> (width, height)."""
    width, sep, height = text.lower().partition("x")
    if not (sep and width.isdigit() and height.isdigit()) or not int(width) * int(height):
        raise argparse.ArgumentTypeError(f"image size must be WxH, e.g. 128x96, got {text!r}")
    return int(width), int(height)


def _eval_configs(args: argparse.Namespace):
    """(output folder, evaluator config) of each evaluation the arguments ask for."""
    import dataclasses
    from pathlib import Path

    from instructmove_ms import heldout, robustness
    from instructmove_ms.episode import CONDITIONS

    perturbations = robustness.settings(args.perturb)
    if args.config or args.traj:
        if perturbations:
            raise ValueError(
                "--perturb applies to the stored sets (--task); write a perturbed config with "
                "--task ... --perturb AXIS:LEVEL --write-config FILE"
            )
        config = (
            heldout.EvaluatorConfig.load(Path(args.config))
            if args.config
            else heldout.EvaluatorConfig.from_trajectory(args.traj)
        )
        yield Path(args.out), dataclasses.replace(config, episodes=config.episodes[: args.episodes])
        return
    conditions = CONDITIONS if args.condition == "all" else (args.condition,)
    sweep = robustness.is_sweep(args.perturb)
    for condition in conditions:
        out = Path(args.out) / condition if len(conditions) > 1 else Path(args.out)
        for levels in perturbations or [{}]:
            yield (
                out / robustness.folder_name(levels) if sweep else out,
                heldout.evaluator_config(
                    args.task,
                    args.robot,
                    args.split,
                    condition,
                    args.episodes,
                    perturbation=levels,
                    version=args.set_version,
                ),
            )


def _check_format(args: argparse.Namespace, config) -> None:
    """The observation format of a served policy must fit the config's robot."""
    from instructmove_ms.obs_formats import FORMATS
    from instructmove_ms.validation import check_choice

    check_choice("--obs-format", args.obs_format, FORMATS)
    robot = config.env_kwargs.get("robot_uids")
    fits = FORMATS[args.obs_format].robots
    served = args.policy.startswith(SERVED)
    if served and args.num_envs > 1:
        raise ValueError("a served policy takes one episode at a time: --num-envs 1")
    if served and fits and robot not in fits:
        raise ValueError(
            f"--obs-format {args.obs_format} is for {', '.join(fits)}, not {robot!r}; "
            "instructmove and maniskill fit every robot"
        )


def _cmd_eval(args: argparse.Namespace) -> int:
    from pathlib import Path

    from instructmove_ms import heldout, robustness
    from instructmove_ms.evaluation import check_backend, evaluate_config
    from instructmove_ms.metrics import markdown_table
    from instructmove_ms.video import VideoSettings

    if sum(map(bool, (args.task, args.config, args.traj))) != 1:
        raise ValueError("eval needs one of --task, --config or --traj")
    if args.episodes is not None and args.episodes < 1:
        raise ValueError(f"--episodes must be at least 1, got {args.episodes}")
    if args.write_config:
        if args.condition == "all":
            raise ValueError("--write-config writes one condition's episodes, not 'all'")
        if robustness.is_sweep(args.perturb):
            raise ValueError("--write-config writes one perturbation setting, not a sweep")
        config = heldout.evaluator_config(
            args.task,
            args.robot,
            args.split,
            args.condition,
            args.episodes,
            None,
            args.perturb,
            args.set_version,
        )
        print(f"{len(config.episodes)} episodes -> {config.write(Path(args.write_config))}")
        return 0
    if not (args.policy and args.out):
        raise ValueError("eval needs --policy and --out (or --write-config FILE)")
    check_backend(args.num_envs, args.sim_backend, args.ray is not None)
    video = VideoSettings(first=args.video_first) if args.video else None
    configs = list(_eval_configs(args))  # every input checked before the policy starts
    for _, config in configs:
        config.check()
        _check_format(args, config)
    workers = _workers(args, gpus=1.0 if args.num_envs > 1 else 0.0)  # GPU simulation
    policy = _load_policy(args.policy, args)
    rows, runs = [], []
    for out, config in configs:
        summary = evaluate_config(
            policy, config, out, args.num_envs, args.sim_backend, video, workers
        )
        rows += summary["groups"]
        runs.append((config.perturbation, summary["groups"]))
    if robustness.is_sweep(args.perturb):
        rows = robustness.write_robustness(Path(args.out), runs)
        print(markdown_table(rows, (*robustness.GROUP, "axis", "level")))
        return 0
    print(markdown_table(rows))
    if "policy" in summary:  # a served policy: its server's own timing
        print(f"policy: {json.dumps(summary['policy'])}")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("eval", help="evaluate a policy on a held-out set or evaluator config")
    p.add_argument("--task", default=None, help="env id (not with --config)")
    p.add_argument("--split", default="seen", help="seen, unseen_instance or unseen_category")
    p.add_argument(
        "--policy",
        help="oracle, blind, scripted, scripted-blind, random, grounded[:CHECKPOINT] (the "
        "learned grounding model, the planner acting), ws://HOST:PORT (openpi's server), "
        "zmq://HOST:PORT (GR00T's, with --obs-format groot) or MODULE:CLASS",
    )
    p.add_argument("--out", help="folder for the reports (resumable)")
    p.add_argument("--robot", default=None, help="robot uid (default: the task's)")
    p.add_argument(
        "--condition",
        default="normal",
        help="instruction condition, or 'all' for the five counterfactual ones",
    )
    p.add_argument(
        "--perturb",
        default=None,
        metavar="AXIS:LEVEL,...|sweep[=AXES]",
        help="perturb the stored scenes (levels 0-3), or sweep every axis (or AXES) at every "
        "level into OUT/<axis>-<level> with a robustness report in OUT",
    )
    p.add_argument("--episodes", type=int, default=None, help="first N episodes of the set")
    _add_set_version(p)
    p.add_argument(
        "--config", default=None, help="evaluate exactly the episodes of this evaluator config"
    )
    p.add_argument(
        "--write-config",
        default=None,
        metavar="FILE",
        help="write the evaluator config of --task/--robot/--split/--condition and stop",
    )
    p.add_argument("--num-envs", type=int, default=1, help="episodes at once (GPU sim only)")
    _add_workers(p, "one env each, a batch of --num-envs episodes at a time")
    p.add_argument("--sim-backend", default="auto", help="ManiSkill sim backend")
    p.add_argument("--video", action="store_true", help="an MP4 per episode in OUT/videos")
    p.add_argument("--video-first", type=int, default=None, help="videos of the first K only")
    p.add_argument(
        "--traj", default=None, help="evaluate the episodes of a recorded trajectory (demos)"
    )
    p.add_argument(
        "--obs-format",
        default="instructmove",
        help="what a served policy gets: instructmove, droid (Franka), aloha (PiperX), "
        "maniskill, groot (GR00T's server)",
    )
    p.add_argument(
        "--replan-steps", type=int, default=5, help="actions of a served chunk played per request"
    )
    p.add_argument(
        "--image-size",
        type=_image_size,
        default=None,
        metavar="WxH",
        help="camera size of the instructmove and groot formats (default 224x224; a LeRobot "
        "export's size)",
    )
    p.add_argument("--obs-mode", default="rgb", help="observation mode (--obs-format maniskill)")
    p.add_argument("--control-mode", default="pd_joint_pos", help="control mode of a remote policy")
    p.set_defaults(func=_cmd_eval)
