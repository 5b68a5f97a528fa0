"""``instructmove serve-replay`` and ``serve-lerobot``: serve a policy with openpi's server."""

from __future__ import annotations

import argparse
import sys


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


def add_parsers(sub: argparse._SubParsersAction) -> None:
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
