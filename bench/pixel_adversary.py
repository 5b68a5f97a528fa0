"""What the pixel adversaries find in one family: on the sampler that made InstructMove
1.0's shortcuts (sampler 1, sets v7) and on the symmetric one (sampler 2, sets v8).

Per sampler: the pixel adversaries (``audit.pixels``: the image-only grounding network, and
trees on image statistics; never the instruction) train on ``--scenes`` rendered training
scenes of the family per robot, then pick on the stored sets of that sampler's version.
Printed per split (robots pooled): each one's accuracy against chance as a ratio, with the
standard error counted by scene (``audit.stats``). Renders and models are kept under
``--cache``, so a rerun only trains what changed.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import instructmove_ms  # noqa: F401
from instructmove_ms.audit.pixels import judge
from instructmove_ms.audit.stats import POOLED
from instructmove_ms.tasks import TASKS

#: (sampler, the set version it drew).
VERSIONS = ((1, 7), (2, 8))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--family", default="PickAttribute-InstructMove", choices=sorted(TASKS))
    parser.add_argument("--scenes", type=int, default=400, help="training scenes per robot")
    parser.add_argument("--cache", default="out/pixels/cache")
    args = parser.parse_args()
    for sampler, version in VERSIONS:
        cells, losses = judge(
            Path(args.cache), args.scenes, sampler, version, families=(args.family,)
        )
        print(
            f"sampler {sampler}, sets v{version}: network's training loss "
            f"{losses[0]:.3f} -> {losses[-1]:.3f}"
        )
        for c in cells:
            if c.robot == POOLED:
                print(
                    f"  {c.adversary:32s} {c.kind:10s} {c.split:16s} {c.accuracy:.3f} vs "
                    f"chance {c.chance:.3f}: {c.accuracy / c.chance:.2f}x (z {c.z:+.1f}, "
                    f"{c.scenes} scenes)"
                )


if __name__ == "__main__":
    main()
