"""What several verbs share: the options and executor of a long job, and verbs with verbs."""

from __future__ import annotations

import argparse


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


def _add_set_version(p: argparse.ArgumentParser) -> None:
    """``--set-version`` of the stored held-out sets a verb reads."""
    from instructmove_ms.heldout import SET_VERSION, SET_VERSIONS, benchmark_name

    p.add_argument(
        "--set-version",
        type=int,
        choices=SET_VERSIONS,
        default=SET_VERSION,
        help=f"stored held-out sets to read (default {SET_VERSION}, {benchmark_name()}; each "
        "released benchmark version stays loadable)",
    )


def _workers(args: argparse.Namespace, gpus: float = 0.0):
    from instructmove_ms.executor import Workers

    return Workers(args.workers, args.ray, gpus=gpus)


def _add_group(sub: argparse._SubParsersAction, name: str, text: str) -> argparse._SubParsersAction:
    """A verb with verbs of its own (``instructmove NAME VERB``), parsed into
    ``NAME_command``."""
    return sub.add_parser(name, help=text).add_subparsers(dest=f"{name}_command", required=True)
