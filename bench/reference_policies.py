"""The reference policies side by side on the stored held-out sets.

Evaluates the planner oracle, the language-blind policy and random actions on the first
``--episodes`` episodes of every family's set (its default robot unless ``--robot``) and
prints the paper's ``Reach/Lift (S)`` table next to chance (1/|G|), which the blind policy
should match (the acceptance table: the oracle's S at least 0.95 on every family).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import instructmove_ms  # noqa: F401
from instructmove_ms.evaluation import evaluate
from instructmove_ms.metrics import comparison_table
from instructmove_ms.policies import REFERENCE_POLICIES
from instructmove_ms.tasks import TASKS

POLICIES = ("oracle", "blind", "random")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--episodes", type=int, default=100, help="episodes per family")
    parser.add_argument("--split", default="seen")
    parser.add_argument("--robot", default=None, help="one robot (default: each family's)")
    parser.add_argument("--task", default=None, help="one env id (default: every family)")
    parser.add_argument("--workers", type=int, default=1, help="local worker processes")
    parser.add_argument(
        "--set-version", type=int, default=None, help="stored sets (default: the current ones)"
    )
    args = parser.parse_args()
    runs: dict[str, list[dict]] = {name: [] for name in POLICIES}
    with tempfile.TemporaryDirectory() as tmp:
        for task in [args.task] if args.task else TASKS:
            for name in POLICIES:
                out = Path(tmp) / task / name
                policy = REFERENCE_POLICIES[name]()
                n = args.episodes
                summary = evaluate(
                    policy,
                    task,
                    args.split,
                    out,
                    args.robot,
                    episodes=n,
                    workers=args.workers,
                    version=args.set_version,
                )
                runs[name] += summary["groups"]
    print(comparison_table(runs))


if __name__ == "__main__":
    main()
