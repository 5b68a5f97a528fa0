"""InstructMove-MS from the command line: envs, episodes and the object library."""

from __future__ import annotations

import argparse
import sys

from instructmove_ms.cli import (
    assets,
    audit,
    demos,
    doctor,
    envs,
    episodes,
    evaluate,
    export,
    grounding,
    perturb,
    quickstart,
    readers,
    serve,
)

# in the order ``instructmove --help`` lists the verbs
VERBS = (
    quickstart,
    doctor,
    envs,
    episodes,
    demos,
    evaluate,
    audit,
    export,
    serve,
    perturb,
    assets,
    readers,
    grounding,
)


def version_line() -> str:
    """The package's version and the benchmark version its stored sets make."""
    from instructmove_ms import __version__
    from instructmove_ms.heldout import benchmark_name

    return f"instructmove-ms {__version__}; benchmark: {benchmark_name()}"


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="instructmove",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,  # the version line unwrapped
    )
    parser.add_argument("--version", action="version", version=version_line())
    sub = parser.add_subparsers(dest="command", required=True)
    for verb in VERBS:
        verb.add_parsers(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command of ``argv``; an error the input causes (a bad value, a missing or
    broken file, an unreachable policy server, an optional package not installed) prints one
    line and exits non-zero: 2 for bad input, 3 for a policy server that is gone (resume the
    run once it is back)."""
    from instructmove_ms.gpu_physics import GpuPhysicsUnavailable
    from instructmove_ms.guard import ServerError
    from instructmove_ms.integrations import MissingExtra

    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # output piped into a reader that stopped (head, less)
        sys.stderr.close()
        return 0
    except (MissingExtra, GpuPhysicsUnavailable) as exc:
        print(f"instructmove: error: {exc}", file=sys.stderr)
        return 2
    except ServerError as exc:
        print(f"instructmove: error: {exc}", file=sys.stderr)
        return 3
    except (ValueError, FileNotFoundError) as exc:
        print(f"instructmove: error: {exc}", file=sys.stderr)
        return 2
    except KeyError as exc:
        print(f"instructmove: error: {exc.args[0] if exc.args else exc}", file=sys.stderr)
        return 2
