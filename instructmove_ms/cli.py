"""InstructMove-MS from the command line: envs, episodes and the object library."""

from __future__ import annotations

import argparse
import json
import sys


def _add_workers(p: argparse.ArgumentParser, what: str) -> None:
    """``--workers`` and ``--ray`` of a long job (see ``executor``)."""
    p.add_argument("--workers", type=int, default=1, help=f"local processes ({what})")
    p.add_argument(
        "--ray",
        nargs="?",
        const="",
        default=None,
        metavar="ADDRESS",
        help="run the shards on a Ray cluster: 'auto', HOST:PORT, or no value for Ray's "
        "default (RAY_ADDRESS, a cluster started here, else a new local one)",
    )


def _workers(args: argparse.Namespace, gpus: float = 0.0):
    from instructmove_ms.executor import Workers

    return Workers(args.workers, args.ray, gpus=gpus)


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


def _assets(args: argparse.Namespace) -> list:
    from instructmove_ms.assets import load_snapshot

    catalog = load_snapshot(args.snapshot)
    return [i for i in catalog.instances if not args.category or i.category == args.category]


def _cmd_assets_list(args: argparse.Namespace) -> int:
    from instructmove_ms.assets.annotations import annotate
    from instructmove_ms.sampler import split_of

    for inst in _assets(args):
        record = annotate(inst, split_of(inst))
        if args.format == "jsonl":
            print(json.dumps(record))
        else:
            print(
                f"{inst.uuid}  {inst.category:18s} {'/'.join(inst.colors):18s} "
                f"{inst.material:9s} {inst.height * 100:5.1f} cm  {record['split']}"
            )
    return 0


TRIAL_TARGET = 0.95
INSTANCES_PER_CATEGORY = 10  # in the default snapshot


def _cmd_assets_check(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from instructmove_ms.assets.quality import check_instances

    instances = _assets(args)
    by_category: dict[str, list] = {}
    for inst in instances:
        by_category.setdefault(inst.category, []).append(inst)
    failed = 0
    for category in tqdm(sorted(by_category), desc="checking", unit="category"):
        for result in check_instances(by_category[category]):
            if not result.ok:
                failed += 1
                tqdm.write(f"FAIL {result.category} {result.uuid}: {'; '.join(result.failures)}")
    print(f"{len(instances) - failed}/{len(instances)} instances pass the quality checks")
    if args.trials:
        from instructmove_ms.assets.grasp_trial import grasp_trial

        results = []
        for category in tqdm(sorted(by_category), desc="grasp trials", unit="category"):
            results += grasp_trial(by_category[category])
        passed = sum(r.passed for r in results)
        for r in results:
            if not r.passed:
                tqdm.write(f"NO GRASP {r.category} {r.uuid} after {r.tries} tries")
        rate = passed / max(1, len(results))
        print(
            f"grasp trials: {passed}/{len(results)} graspable instances picked up ({rate:.1%}; "
            f"target >= {TRIAL_TARGET:.0%})"
        )
        failed += rate < TRIAL_TARGET
    return 1 if failed else 0


def _cmd_assets_sheet(args: argparse.Namespace) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from instructmove_ms.assets.sheet import contact_sheet

    groups: dict[str, list] = {}
    for inst in _assets(args):
        groups.setdefault(inst.super_category, []).append(inst)
    for name in tqdm(sorted(groups), desc="contact sheets", unit="sheet"):
        path = contact_sheet(groups[name], Path(args.out) / f"{name}.png")
        tqdm.write(str(path))
    return 0


def _cmd_assets_build(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from instructmove_ms.assets import snapshot as snap
    from instructmove_ms.assets.generators import GENERATORS

    categories = sorted(GENERATORS)
    entries = []
    for category in tqdm(categories, desc="generating", unit="category"):
        entries += snap.build_entries([category], args.per_category)
    folder = (
        snap.package_snapshot_dir()
        if args.name == snap.DEFAULT_SNAPSHOT
        else snap.user_snapshot_dir()
    )
    path = snap.write_snapshot(folder / f"{args.name}.json", args.name, entries)
    print(
        f"snapshot {args.name!r}: {len(entries)} instances of {len(categories)} categories "
        f"-> {path}"
    )
    if args.name == snap.DEFAULT_SNAPSHOT:  # other snapshots' colours are rendered on use
        from instructmove_ms.assets.appearance import table_path
        from instructmove_ms.assets.photometry import write_table

        instances = snap.load_snapshot(args.name).instances
        print(f"rendered colours -> {write_table(instances, table_path())}")
    return 0


def _cmd_assets_rehash(args: argparse.Namespace) -> int:
    from instructmove_ms.assets.snapshot import rehash

    count, kept = rehash(args.name)
    print(f"snapshot {args.name!r}: {count} instances re-hashed, {kept} stored colours kept")
    return 0


def _cmd_assets_import(args: argparse.Namespace) -> int:
    from pathlib import Path

    from instructmove_ms.assets.snapshot import import_folder

    report = import_folder(Path(args.source), args.name, args.extend or None)
    for asset_id, repairs in report.repaired:
        print(f"repaired {asset_id}: {'; '.join(repairs)}", file=sys.stderr)
    for asset_id, failures in report.rejected:
        print(f"left out {asset_id}: {'; '.join(failures)}", file=sys.stderr)
    print(f"snapshot {args.name!r} -> {report.path} ({len(report.rejected)} assets left out)")
    return 1 if report.rejected else 0


def _cmd_episodes_write(args: argparse.Namespace) -> int:
    from pathlib import Path

    import gymnasium as gym
    from tqdm import tqdm

    import instructmove_ms  # noqa: F401  (registration)
    from instructmove_ms import heldout
    from instructmove_ms.splits import EVAL_SPLITS
    from instructmove_ms.tasks import TASKS

    tasks = [args.task] if args.task else list(TASKS)
    out = Path(args.out) if args.out else None
    for env_id in tasks:
        for robot in [args.robot] if args.robot else TASKS[env_id].supported_robots:
            for split in EVAL_SPLITS:
                env = gym.make(env_id, robot_uids=robot, split=split, obs_mode="state")
                specs = list(
                    tqdm(
                        heldout.generate_set(env, args.n),
                        total=args.n,
                        desc=f"{env_id} {robot} {split}",
                        unit="episode",
                    )
                )
                env.close()
                path = heldout.write_set(heldout.set_path(env_id, robot, split, out), specs)
                tqdm.write(f"{len(specs)} episodes -> {path}")
    return 0


def _cmd_episodes_show(args: argparse.Namespace) -> int:
    from instructmove_ms import heldout
    from instructmove_ms.tasks import TASKS

    robot = args.robot or TASKS[args.task].default_robot
    specs = heldout.load_set(args.task, robot, args.split)
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
        tqdm.write(str(episode_sheet(args.task, robot, split, Path(args.out) / name, args.n)))
    return 0


def _cmd_quickstart(args: argparse.Namespace) -> int:
    from pathlib import Path

    from instructmove_ms.quickstart import QuickstartSettings, run

    settings = QuickstartSettings(args.demos, args.episodes, args.videos, args.workers)
    report = run(Path(args.out), settings)
    print(f"\nreport: {report}")
    return 0


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


def _cmd_serve_replay(args: argparse.Namespace) -> int:
    from instructmove_ms.serving import DatasetReplayPolicy, serve

    policy = DatasetReplayPolicy(args.dataset, args.chunk)
    print(f"serving the replay of {args.dataset} on ws://{args.host}:{args.port}", flush=True)
    serve(policy, args.host, args.port, {"policy": "dataset replay", "dataset": args.dataset})
    return 0


def _cmd_serve_lerobot(args: argparse.Namespace) -> int:
    import os
    from pathlib import Path

    from instructmove_ms import integrations

    program = Path(integrations.__file__).with_name("lerobot_server.py")  # run, not imported
    argv = [args.python, str(program), "--checkpoint", args.checkpoint]
    argv += ["--host", args.host, "--port", str(args.port), "--device", args.device]
    os.execv(args.python, argv)  # the server replaces this process (signals reach it)
    return 0


def _load_policy(spec: str, args: argparse.Namespace):
    """A reference policy name, ``ws://HOST:PORT`` or ``MODULE:CLASS``."""
    import importlib

    from instructmove_ms.policies import REFERENCE_POLICIES

    if spec in REFERENCE_POLICIES:
        return REFERENCE_POLICIES[spec]()
    if spec.startswith(("ws://", "wss://")):
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
            "ws://HOST:PORT or MODULE:CLASS"
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
                ),
            )


def _check_format(args: argparse.Namespace, config) -> None:
    """The observation format of a served policy must fit the config's robot."""
    from instructmove_ms.obs_formats import FORMATS
    from instructmove_ms.validation import check_choice

    check_choice("--obs-format", args.obs_format, FORMATS)
    robot = config.env_kwargs.get("robot_uids")
    fits = FORMATS[args.obs_format].robots
    served = args.policy.startswith(("ws://", "wss://"))
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
            args.task, args.robot, args.split, args.condition, args.episodes, None, args.perturb
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


def build_parser() -> argparse.ArgumentParser:
    from instructmove_ms.export.lerobot_formats import DEFAULT_FORMAT, FORMATS

    parser = argparse.ArgumentParser(prog="instructmove", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("quickstart", help="demos, MCAP, evaluation and report end to end")
    p.add_argument("--out", default="out/quickstart", help="output folder (resumable)")
    p.add_argument("--demos", type=int, default=2, help="planned demos per family")
    p.add_argument("--episodes", type=int, default=5, help="held-out episodes per policy")
    p.add_argument("--videos", type=int, default=1, help="oracle videos per family")
    p.add_argument("--workers", type=int, default=2, help="processes for demos and MCAP")
    p.set_defaults(func=_cmd_quickstart)
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
    episodes = sub.add_parser("episodes", help="held-out evaluation episode sets")
    episodes_sub = episodes.add_subparsers(dest="episodes_command", required=True)
    p = episodes_sub.add_parser("write", help="sample and store the held-out sets")
    p.add_argument("--task", default=None, help="one env id (default: every family)")
    p.add_argument("--robot", default=None, help="one robot (default: every supported one)")
    p.add_argument("--n", type=int, default=100, help="episodes per set")
    p.add_argument("--out", default=None, help="folder (default: the package's own)")
    p.set_defaults(func=_cmd_episodes_write)
    p = episodes_sub.add_parser("show", help="print one stored held-out episode spec")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default=None)
    p.add_argument("--split", default="seen")
    p.add_argument("--index", type=int, default=0)
    p.set_defaults(func=_cmd_episodes_show)
    p = episodes_sub.add_parser(
        "sheet", help="contact sheet PNGs of stored episodes with their instructions"
    )
    p.add_argument("--task", required=True, help="env id")
    p.add_argument("--robot", default=None, help="default: the family's robot")
    p.add_argument("--split", default=None, help="one split (default: every one)")
    p.add_argument("--n", type=int, default=20, help="episodes per sheet")
    p.add_argument("--out", required=True, help="folder for <family>_<robot>_<split>.png")
    p.set_defaults(func=_cmd_episodes_sheet)
    demos = sub.add_parser("demos", help="planned demonstrations").add_subparsers(
        dest="demos_command", required=True
    )
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
    p = sub.add_parser("eval", help="evaluate a policy on a held-out set or evaluator config")
    p.add_argument("--task", default=None, help="env id (not with --config)")
    p.add_argument("--split", default="seen", help="seen, unseen_instance or unseen_category")
    p.add_argument(
        "--policy",
        help="oracle, blind, scripted, scripted-blind, random, ws://HOST:PORT or MODULE:CLASS",
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
        help="what a served policy gets: instructmove, droid (Franka), aloha (PiperX), maniskill",
    )
    p.add_argument(
        "--replan-steps", type=int, default=5, help="actions of a served chunk played per request"
    )
    p.add_argument(
        "--image-size",
        type=_image_size,
        default=None,
        metavar="WxH",
        help="camera size of the instructmove format (default 224x224; a LeRobot export's size)",
    )
    p.add_argument("--obs-mode", default="rgb", help="observation mode (--obs-format maniskill)")
    p.add_argument("--control-mode", default="pd_joint_pos", help="control mode of a remote policy")
    p.set_defaults(func=_cmd_eval)
    export = sub.add_parser("export", help="convert recorded trajectories").add_subparsers(
        dest="export_command", required=True
    )
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
    p = sub.add_parser(
        "serve-replay", help="serve a LeRobot dataset's recorded actions with openpi's server"
    )
    p.add_argument("--dataset", required=True, help="a LeRobot dataset of ours")
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=8000)
    p.add_argument("--chunk", type=int, default=50, help="actions per answer")
    p.set_defaults(func=_cmd_serve_replay)
    p = sub.add_parser(
        "serve-lerobot",
        help="serve a LeRobot checkpoint with openpi's server (in an env with lerobot >= 0.4)",
    )
    p.add_argument("--checkpoint", required=True, help="a checkpoint's pretrained_model folder")
    p.add_argument(
        "--python",
        default=sys.executable,
        help="interpreter of an env with lerobot and openpi's server "
        "(scripts/lerobot_env.sh: .cache/lerobot-env/bin/python); default: this one",
    )
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=8000)
    p.add_argument("--device", default="cpu", help="torch device of the policy")
    p.set_defaults(func=_cmd_serve_lerobot)
    perturb = sub.add_parser("perturb", help="perturbation axes").add_subparsers(
        dest="perturb_command", required=True
    )
    p = perturb.add_parser("sheet", help="one PNG per axis: a scene at levels 0-3")
    p.add_argument("--task", default="PickCategory-InstructMove")
    p.add_argument("--robot", default=None, help="robot uid (default: the task's)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--axes", default=None, help="comma-separated axes (default: every one)")
    p.add_argument("--out", required=True, help="folder for <axis>.png")
    p.set_defaults(func=_cmd_perturb_sheet)
    assets = sub.add_parser("assets", help="the object library").add_subparsers(
        dest="assets_command", required=True
    )
    p = assets.add_parser("build", help="generate the library and freeze it as a snapshot")
    p.add_argument("--name", default="default", help="snapshot name (default: the shipped one)")
    p.add_argument("--per-category", type=int, default=INSTANCES_PER_CATEGORY)
    p.set_defaults(func=_cmd_assets_build)
    p = assets.add_parser(
        "rehash", help="re-hash a snapshot written by an older identity scheme (same assets)"
    )
    p.add_argument("name", help="snapshot name")
    p.set_defaults(func=_cmd_assets_rehash)
    p = assets.add_parser("import", help="import a folder of meshes + metadata.json")
    p.add_argument("source", help="folder with metadata.json and the mesh files")
    p.add_argument("--name", required=True, help="name of the new snapshot")
    p.add_argument(
        "--extend", default="default", help="snapshot to add the assets to ('' for none)"
    )
    p.set_defaults(func=_cmd_assets_import)
    for name, func, text in (
        ("list", _cmd_assets_list, "print every asset with its annotations"),
        ("check", _cmd_assets_check, "run the quality checks (geometry, size, settling, grasps)"),
        ("sheet", _cmd_assets_sheet, "write a labelled contact sheet PNG per super-category"),
    ):
        p = assets.add_parser(name, help=text)
        p.add_argument("--snapshot", default="default")
        p.add_argument("--category", default=None, help="only this category")
        p.set_defaults(func=func)
        if name == "list":
            p.add_argument("--format", choices=("table", "jsonl"), default="table")
        if name == "check":
            p.add_argument(
                "--trials",
                action="store_true",
                help="also pick every graspable instance up with a floating gripper",
            )
        if name == "sheet":
            p.add_argument("--out", default="out/sheets", help="folder for the PNGs")
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command of ``argv``; an error the input causes (a bad value, a missing or
    broken file, an unreachable policy server) prints one line and exits non-zero: 2 for
    bad input, 3 for a policy server that is gone (resume the run once it is back)."""
    from instructmove_ms.guard import ServerError

    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # output piped into a reader that stopped (head, less)
        sys.stderr.close()
        return 0
    except ServerError as exc:
        print(f"instructmove: error: {exc}", file=sys.stderr)
        return 3
    except (ValueError, FileNotFoundError) as exc:
        print(f"instructmove: error: {exc}", file=sys.stderr)
        return 2
    except KeyError as exc:
        print(f"instructmove: error: {exc.args[0] if exc.args else exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
