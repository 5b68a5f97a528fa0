"""Spatial relations in the robot's frame (+x forward, +y left), as a person reads them.

A direction relation ("left of", "behind", ...) holds when the object lies within ``CONE``
degrees of the relation's direction from the reference, at least ``MARGIN`` along it and
within ``REACH`` of it: "behind the hex key" is something roughly behind it, not beside
it. "near" and "far from" are distances with a clear gap between them. A relation fails
clearly when the opposite relation holds: PickSpatial puts the target where its relation
holds and the same-category distractor where the opposite one does.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

RELATIONS = ("left of", "right of", "in front of", "behind", "near", "far from")
#: Unit direction of each direction relation; "in front of" is nearer the robot.
DIRECTIONS = {
    "left of": (0.0, 1.0),
    "right of": (0.0, -1.0),
    "in front of": (-1.0, 0.0),
    "behind": (1.0, 0.0),
}
#: Largest angle, in degrees, between the object's bearing and the relation's direction.
CONE = 45.0
#: Smallest offset along the direction, and largest distance from the reference, in metres.
MARGIN, REACH = 0.06, 0.35
#: near: within NEAR of the reference; far from: beyond FAR (a gap of FAR - NEAR between).
NEAR, FAR = 0.16, 0.26
OPPOSITE = {
    "left of": "right of",
    "right of": "left of",
    "in front of": "behind",
    "behind": "in front of",
    "near": "far from",
    "far from": "near",
}
#: How instructions say each relation: every phrase reads as where the object is, never
#: as where to move it ("lift the chips farther from the bin" also reads as "move them
#: farther away": distance is said only in the superlative).
PHRASES = {
    "left of": ("to the left of", "on the left side of"),
    "right of": ("to the right of", "on the right side of"),
    "in front of": ("in front of",),
    "behind": ("behind",),
    "near": ("near", "next to", "closest to"),
    "far from": ("farthest from", "furthest from"),
}
#: Phrases InstructMove 1.0's sampler (1) still says and later samplers do not: "on the
#: right side of the chopping board" may mean lying on it.
RETIRED_PHRASES = frozenset({"on the left side of", "on the right side of"})


@dataclass(frozen=True)
class Bearing:
    """Where an object lies from the reference, read for one relation: its offset along the
    relation's direction (m; for near/far, the distance), the angle off that direction
    (degrees; 0 for near/far) and its distance (m)."""

    offset: float
    angle: float
    distance: float

    def as_dict(self) -> dict:
        return {k: round(v, 4) for k, v in asdict(self).items()}


def bearing(relation: str, obj_xy, ref_xy) -> Bearing:
    """How ``obj`` lies from the reference with respect to ``relation``."""
    d = np.asarray(obj_xy, float)[:2] - np.asarray(ref_xy, float)[:2]
    distance = float(np.hypot(*d))
    if relation not in DIRECTIONS:
        return Bearing(distance, 0.0, distance)
    u = np.asarray(DIRECTIONS[relation])
    along = float(d @ u)
    across = float(d[0] * u[1] - d[1] * u[0])
    return Bearing(along, math.degrees(math.atan2(abs(across), along)), distance)


def holds(relation: str, obj_xy, ref_xy) -> bool:
    """Whether ``obj`` is ``relation`` the reference, by the margin and within the cone."""
    b = bearing(relation, obj_xy, ref_xy)
    if relation == "near":
        return b.distance < NEAR
    if relation == "far from":
        return b.distance > FAR
    return b.offset > MARGIN and b.angle <= CONE and b.distance <= REACH


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
