"""The full annotation record of an instance, as `instructmove assets list` prints it."""

from __future__ import annotations

from dataclasses import asdict

from .affordances import grasp_affordances
from .catalog import Instance
from .expressions import expressions

#: Every instance is generated in its natural resting pose, verified by the settle check.
UPRIGHT = (1.0, 0.0, 0.0, 0.0)


def annotate(inst: Instance, split: str, max_opening: float = 0.08) -> dict:
    seen, unseen = expressions(inst)
    record = inst.annotation()
    record.update(
        split=split,
        stable_poses=[list(UPRIGHT)],
        grasps=[
            {
                k: [round(v, 5) for v in val] if isinstance(val, tuple) else round(val, 5)
                for k, val in asdict(g).items()
            }
            for g in grasp_affordances(inst, max_opening)
        ],
        expressions={"seen": list(seen), "unseen": list(unseen)},
    )
    return record
