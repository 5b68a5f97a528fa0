"""Random non-overlapping table layouts of oriented rectangular footprints."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


class LayoutError(RuntimeError):
    """No layout satisfies the constraints within the search budget."""


@dataclass(frozen=True)
class Workspace:
    """Where object centres may go, in the robot's base frame (x forward, y left)."""

    x: tuple[float, float] = (0.25, 0.55)
    y: tuple[float, float] = (-0.35, 0.35)


@dataclass(frozen=True)
class Placement:
    x: float
    y: float
    yaw: float

    def pose(self, z: float) -> tuple[float, ...]:
        """The world pose (x, y, z, qw, qx, qy, qz) of this placement at height ``z``."""
        return (self.x, self.y, z, math.cos(self.yaw / 2), 0.0, 0.0, math.sin(self.yaw / 2))


#: Yaw (rad) either side of a back turned straight away from the robot.
BACK_SPREAD = math.pi / 4


def random_placement(
    rng: np.random.Generator, workspace: Workspace, back: float | None = None
) -> Placement:
    """A uniformly drawn centre in ``workspace`` and yaw; an object whose ``back`` (heading
    in its frame, see ``catalog.Instance.back``) is given turns it away from the robot's
    base, within ``BACK_SPREAD``, as a person sets down a bin with its open lid behind."""
    x, y = float(rng.uniform(*workspace.x)), float(rng.uniform(*workspace.y))
    if back is None:
        return Placement(x, y, float(rng.uniform(-math.pi, math.pi)))
    away = math.atan2(y, x) - back
    return Placement(x, y, away + float(rng.uniform(-BACK_SPREAD, BACK_SPREAD)))


def corners(half: tuple[float, float], p: Placement) -> np.ndarray:
    """The four footprint corners (4, 2) of a rectangle with ``half`` extents at ``p``."""
    c, s = math.cos(p.yaw), math.sin(p.yaw)
    local = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]], dtype=float) * np.asarray(half)
    return local @ np.array([[c, s], [-s, c]]) + np.array([p.x, p.y])


def _separated(a: np.ndarray, b: np.ndarray) -> bool:
    """Separating-axis test for two convex quads."""
    for poly in (a, b):
        for k in range(4):
            edge = poly[(k + 1) % 4] - poly[k]
            axis = np.array([-edge[1], edge[0]])
            pa, pb = a @ axis, b @ axis
            if pa.max() < pb.min() or pb.max() < pa.min():
                return True
    return False


def _point_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    ab = b - a
    t = np.clip(np.dot(p - a, ab) / np.dot(ab, ab), 0.0, 1.0)
    return float(np.linalg.norm(p - (a + t * ab)))


def gap(a: np.ndarray, b: np.ndarray) -> float:
    """Distance between two convex quads (0 when they overlap)."""
    if not _separated(a, b):
        return 0.0
    return min(
        _point_segment(p, q[k], q[(k + 1) % 4])
        for p_set, q in ((a, b), (b, a))
        for p in p_set
        for k in range(4)
    )


#: accept(index, placement, placed so far) -> whether the placement is allowed.
Accept = Callable[[int, Placement, dict[int, Placement]], bool]


def sample_layout(
    rng: np.random.Generator,
    halves: list[tuple[float, float]],
    workspace: Workspace,
    clearance: float,
    tries_per_object: int = 256,
    restarts: int = 64,
    order: list[int] | None = None,
    accept: Accept | None = None,
    backs: list[float | None] | None = None,
) -> list[Placement]:
    """Place every footprint with at least ``clearance`` between any two.

    Objects are placed in ``order`` (default: largest footprint first), each also passing
    ``accept`` (relation constraints), each with a ``backs`` entry turned with that back
    away from the robot (``random_placement``); the result follows the input order.
    """
    backs = backs or [None] * len(halves)
    if order is None:
        order = sorted(range(len(halves)), key=lambda i: -halves[i][0] * halves[i][1])
    pad = clearance / 2
    padded = [(h[0] + pad, h[1] + pad) for h in halves]
    for _ in range(restarts):
        placed: dict[int, tuple[Placement, np.ndarray]] = {}
        for i in order:
            for _ in range(tries_per_object):
                p = random_placement(rng, workspace, backs[i])
                quad = corners(padded[i], p)
                if all(_separated(quad, other) for _, other in placed.values()) and (
                    accept is None or accept(i, p, {k: v[0] for k, v in placed.items()})
                ):
                    placed[i] = (p, quad)
                    break
            else:
                break
        if len(placed) == len(halves):
            return [placed[i][0] for i in range(len(halves))]
    raise LayoutError(
        f"could not place {len(halves)} objects with {clearance} m clearance in "
        f"x {workspace.x}, y {workspace.y} after {restarts} restarts"
    )
