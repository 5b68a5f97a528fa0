"""Interpreter start-up cost of the autoload hook.

Prints, as medians over repeated runs measured in this run:
- ``python -c pass`` with the hook installed, and the hook's own import time from
  ``-X importtime`` (what every Python process pays), as a fraction of start-up;
- ``import mani_skill.envs`` with the hook (our envs get registered) against
  ``INSTRUCTMOVE_NO_AUTOLOAD=1`` (ManiSkill alone): the cost paid only by ManiSkill users.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import time


def wall(code: str, runs: int, env: dict | None = None) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(
            [sys.executable, "-c", code],
            check=True,
            env=env,
            cwd="/",
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def hook_import_us(runs: int) -> float:
    samples = []
    for _ in range(runs):
        out = subprocess.run(
            [sys.executable, "-X", "importtime", "-c", "pass"],
            check=True,
            capture_output=True,
            text=True,
            cwd="/",
        ).stderr
        m = re.search(r"\|\s*(\d+)\s*\|\s*instructmove_ms_autoload\s*$", out, re.M)
        if m is None:
            raise SystemExit("the autoload hook is not installed (pip install -e . first)")
        samples.append(float(m.group(1)))
    return statistics.median(samples)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--runs", type=int, default=15)
    args = parser.parse_args()
    bare = wall("pass", args.runs)
    hook_us = hook_import_us(args.runs)
    print(f"python -c pass:                 {bare * 1e3:8.1f} ms (hook installed)")
    print(
        f"  of which the hook's import:   {hook_us / 1e3:8.3f} ms "
        f"= {hook_us / 1e6 / bare:.2%} of start-up (ratio with/without "
        f"{bare / (bare - hook_us / 1e6):.4f})"
    )
    off = dict(os.environ, INSTRUCTMOVE_NO_AUTOLOAD="1")
    runs = max(3, args.runs // 3)
    ms_only = wall("import mani_skill.envs", runs, env=off)
    ms_ours = wall("import mani_skill.envs", runs)
    print(f"import mani_skill.envs:         {ms_only:8.2f} s without registration")
    print(f"  with our envs registered:     {ms_ours:8.2f} s (ratio {ms_ours / ms_only:.3f})")


if __name__ == "__main__":
    main()
