"""Spatial relations in the robot's frame (+x forward, +y left), with margins.

A relation holds when it holds by a margin a person would agree with; it fails clearly when
its opposite holds by the same margin. Layouts for PickSpatial put the target where the
relation holds and the same-category distractor where it clearly fails.
"""

from __future__ import annotations

import numpy as np

RELATIONS = ("left of", "right of", "in front of", "behind", "near", "far from")
#: Side relations: the offset along the axis beyond this margin, in metres.
SIDE_MARGIN = 0.06
#: near / far: the near object within NEAR of the reference, the far one beyond FAR.
NEAR, FAR = 0.16, 0.26
OPPOSITE = {
    "left of": "right of",
    "right of": "left of",
    "in front of": "behind",
    "behind": "in front of",
    "near": "far from",
    "far from": "near",
}
#: How instructions say each relation.
PHRASES = {
    "left of": ("to the left of", "left of", "on the left side of"),
    "right of": ("to the right of", "right of", "on the right side of"),
    "in front of": ("in front of",),
    "behind": ("behind",),
    "near": ("near", "next to", "closest to"),
    "far from": ("far from", "farthest from", "away from"),
}


def holds(relation: str, obj_xy, ref_xy) -> bool:
    """Whether ``obj`` is ``relation`` the reference, by the margin."""
    d = np.asarray(obj_xy, float) - np.asarray(ref_xy, float)
    if relation == "left of":
        return d[1] > SIDE_MARGIN
    if relation == "right of":
        return d[1] < -SIDE_MARGIN
    if relation == "in front of":  # between the robot and the reference
        return d[0] < -SIDE_MARGIN
    if relation == "behind":
        return d[0] > SIDE_MARGIN
    dist = float(np.linalg.norm(d))
    return dist < NEAR if relation == "near" else dist > FAR


def unique_holder(relation: str, candidates_xy: list, ref_xy) -> int | None:
    """The index of the one candidate for which ``relation`` holds while its opposite
    holds for every other one; None if that is not the case."""
    holders = [k for k, xy in enumerate(candidates_xy) if holds(relation, xy, ref_xy)]
    if len(holders) != 1:
        return None
    others_clear = all(
        holds(OPPOSITE[relation], xy, ref_xy)
        for k, xy in enumerate(candidates_xy)
        if k != holders[0]
    )
    return holders[0] if others_clear else None
