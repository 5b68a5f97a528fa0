"""Grasp affordances for a parallel gripper, computed from an instance's convex parts.

Each collision part offers top-down grasps at its top: the fingers close along a horizontal
axis of the part's cross-section. A grasp is kept when the part's width along that axis fits
the gripper's opening, the grasp centre is high enough for the fingertips to clear the table,
and no other part rises above the grasp inside the fingers' column. A container that fits
the hand is also held around its whole section.

Designed parts share faces and heights exactly (a lid's rim on a wall's top, pads that
touch a neighbour), where a comparison would be decided by the last bit of a float, which
BLAS kernels and CPUs change. Every comparison therefore keeps ``EPS`` on one side: a
point ``EPS`` inside a part's surface is inside, one on it touches and is outside; widths
and heights within ``EPS`` of a limit pass it; grasps are ordered by height and width
counted in ``ORDER_QUANTUM`` (``identity.quantise``), so equal heights keep the parts' own
order on every machine.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from .catalog import Instance
from .identity import quantise
from .parts import Part, quat_to_matrix, union_bounds

DOWN = (0.0, 0.0, -1.0)
MARGIN = 0.005  # free opening left on each side of a grasp, metres
FINGER_DEPTH = 0.02  # how far below a part's top the grasp centre goes at most
MIN_HEIGHT = 0.004  # grasp centres lower than this would put the fingertips into the table
FINGER_HALF_WIDTH = 0.012
PALM_HEIGHT = 0.045  # the palm sits this far above the grasp centre
MIN_PART_HEIGHT = 0.004  # thinner parts (a pull tab) give the fingers nothing to hold
#: Geometric tolerance of every comparison (m): far above float noise, far below a part.
EPS = 1e-7
#: Heights and widths that order the grasps are counted in this (m).
ORDER_QUANTUM = 1e-6


@dataclass(frozen=True)
class Grasp:
    """A grasp in the object frame: the TCP goes to ``center`` moving along ``approach`` and
    the fingers close along ``closing``; ``width`` is the object's width between them."""

    center: tuple[float, float, float]
    approach: tuple[float, float, float]
    closing: tuple[float, float, float]
    width: float

    @property
    def yaw(self) -> float:
        """Rotation about z of the closing axis (the gripper's finger axis)."""
        return math.atan2(self.closing[1], self.closing[0])


def _horizontal_widths(part: Part) -> list[tuple[np.ndarray, float]]:
    """(unit horizontal axis, width of the part's horizontal cross-section along it)."""
    rot = quat_to_matrix(part.quat)
    s = part.size
    if part.shape == "sphere":
        return [(np.array([1.0, 0.0, 0.0]), 2 * s[0]), (np.array([0.0, 1.0, 0.0]), 2 * s[0])]
    if part.shape in ("box", "ellipsoid", "mesh"):
        axes = [(rot[:, k], 2 * s[k]) for k in range(3)]
    else:  # cylinder or capsule along local x: round cross-section in local y-z
        length = 2 * (s[1] + s[0]) if part.shape == "capsule" else 2 * s[1]
        axes = [(rot[:, 1], 2 * s[0]), (rot[:, 2], 2 * s[0]), (rot[:, 0], length)]
    out = []
    for axis, width in axes:
        tilt = math.asin(min(1.0, abs(float(axis[2]))))
        if tilt < math.radians(45) - EPS:  # a slanted wall is cut wider at a fixed height
            flat = np.array([axis[0], axis[1], 0.0])
            out.append((flat / np.linalg.norm(flat), float(width) / math.cos(tilt)))
    return out


def section_center(part: Part, z: float) -> np.ndarray:
    """Centre of the part's horizontal cross-section at height ``z`` (a slanted wall's
    section moves sideways with height)."""
    rot = quat_to_matrix(part.quat)
    upright = np.abs(rot[2])
    k = int(np.flatnonzero(upright >= upright.max() - EPS)[0])  # the first of equal ones
    slope = rot[:, k] / rot[2, k]
    return np.asarray(part.pos) + slope * (z - part.pos[2])


def contains(part: Part, points: np.ndarray) -> np.ndarray:
    """Which of ``points`` (M, 3), in the object frame, lie inside ``part`` by more than
    ``EPS`` (a point on its surface touches it)."""
    local = (points - np.asarray(part.pos)) @ quat_to_matrix(part.quat)
    s = np.asarray(part.size) - EPS
    if part.shape in ("box", "mesh"):  # a mesh piece counts as its bounding box
        return np.all(np.abs(local) < s, axis=1)
    if part.shape == "sphere":
        return np.linalg.norm(local, axis=1) < s[0]
    if part.shape == "ellipsoid":
        return np.sum((local / s) ** 2, axis=1) < 1.0
    radial = np.linalg.norm(local[:, 1:], axis=1)
    if part.shape == "cylinder":
        return (np.abs(local[:, 0]) < s[1]) & (radial < s[0])
    along = np.clip(np.abs(local[:, 0]) - s[1], 0.0, None)  # capsule
    return np.hypot(along, radial) < s[0]


def _grip_height(top: float, height: float) -> float:
    """Height of a grasp centre on a part (or section) whose top is at ``top`` and which is
    ``height`` tall: ``FINGER_DEPTH`` below the top, or halfway down a lower one."""
    return top - min(FINGER_DEPTH, height / 2)


def _blocked(
    center: np.ndarray, top: float, z: float, axis: np.ndarray, width: float, others: list[Part]
) -> bool:
    """A finger or the palm would be inside one of ``others``: sample the finger pads beside
    the section at ``center`` (height ``z``, ``width`` along ``axis``, its top at ``top``)
    and the palm above the grasp."""
    normal = np.array([-axis[1], axis[0], 0.0])
    pads = [
        center + a * axis * (width / 2 + 0.006) + b * normal + np.array([0, 0, h])
        for a in (-1, 1)
        for b in (-0.5 * FINGER_HALF_WIDTH, 0.0, 0.5 * FINGER_HALF_WIDTH)
        for h in (0.0, (top - z) / 2)
    ]
    palm = [
        center + a * axis * (width / 2) + b * normal + np.array([0, 0, PALM_HEIGHT])
        for a in (-1, 0, 1)
        for b in (-FINGER_HALF_WIDTH, 0.0, FINGER_HALF_WIDTH)
    ]
    points = np.array(pads + palm)
    return any(contains(other, points).any() for other in others)


def grasp_affordances(inst: Instance, max_opening: float = 0.08) -> list[Grasp]:
    """Top-down grasps of ``inst`` for a gripper opening at most ``max_opening`` metres,
    highest first."""
    solids = [p for p in inst.parts if not p.visual_only]
    grasps = enveloping_grasps(inst, max_opening)
    for part in solids:
        lo, hi = part.bounds()
        top, height = float(hi[2]), float(hi[2] - lo[2])
        z = _grip_height(top, height)
        if z < MIN_HEIGHT - EPS or height < MIN_PART_HEIGHT - EPS:
            continue
        others = [p for p in solids if p is not part]
        center = section_center(part, z)
        for axis, width in _horizontal_widths(part):
            if (
                width >= 0.003 - EPS
                and _fits(width, max_opening)
                and not _blocked(center, top, z, axis, width, others)
            ):
                grasps.append(_grasp(center, axis, width))
    return sorted(
        grasps,
        key=lambda g: (-quantise(g.center[2], ORDER_QUANTUM), quantise(g.width, ORDER_QUANTUM)),
    )


@cache
def graspable(inst: Instance, max_opening: float) -> bool:
    """Whether ``inst`` offers a top-down grasp to fingers opening ``max_opening`` metres
    (remembered per instance and opening: the verifier asks it of every candidate)."""
    return bool(grasp_affordances(inst, max_opening))


def _fits(width: float, max_opening: float) -> bool:
    """Whether fingers opening ``max_opening`` close on ``width`` with ``MARGIN`` free on
    each side."""
    return width <= max_opening - 2 * MARGIN + EPS


def _grasp(center: np.ndarray, axis: np.ndarray, width: float) -> Grasp:
    return Grasp(tuple(float(v) for v in center), DOWN, tuple(float(v) for v in axis), width)


def enveloping_grasps(inst: Instance, max_opening: float = 0.08) -> list[Grasp]:
    """A container's grasps around its whole section just below its top (``section_grasps``):
    a cup's ring of wall pieces held from outside rather than by one piece of its rim (which a
    heavy cup turns out of)."""
    return section_grasps(inst, max_opening) if inst.is_container else []


def section_grasps(inst: Instance, max_opening: float = 0.08) -> list[Grasp]:
    """Grasps around the whole section of ``inst`` just below its top, along its x and y
    axes, where two or more parts make that section: a container's walls, or parts lying
    side by side (sticks in a pack) whose gaps a finger cannot enter."""
    solids = [p for p in inst.parts if not p.visual_only]
    lo, hi = union_bounds(solids)
    top = float(hi[2])
    z = _grip_height(top, float(hi[2] - lo[2]))
    section = [p for p in solids if p.bounds()[0][2] - EPS <= z <= p.bounds()[1][2] + EPS]
    if len(section) < 2 or z < MIN_HEIGHT - EPS:
        return []
    slo, shi = union_bounds(section)
    center = np.array([*(0.5 * (slo[:2] + shi[:2])), z])
    grasps = []
    for k in (0, 1):
        axis, width = np.eye(3)[k], float(shi[k] - slo[k])
        if _fits(width, max_opening) and not _blocked(center, top, z, axis, width, solids):
            grasps.append(_grasp(center, axis, width))
    return grasps


def rim_grasps(inst: Instance, max_opening: float = 0.08) -> list[Grasp]:
    """A container's grasps across one piece of its wall at the top, closing towards the
    middle (one finger inside, one outside): the hold that keeps a container too wide for
    the hand from turning out of the fingers (a pinch along the rim holds it only by the
    friction of its pads against the turn)."""
    if not inst.is_container:
        return []
    solids = [p for p in inst.parts if not p.visual_only]
    lo, hi = union_bounds(solids)
    middle = 0.5 * (lo[:2] + hi[:2])
    grasps = []
    for part in solids:
        plo, phi = part.bounds()
        top, height = float(phi[2]), float(phi[2] - plo[2])
        z = _grip_height(top, height)
        if top < float(hi[2]) - FINGER_DEPTH or z < MIN_HEIGHT - EPS:
            continue  # not a wall reaching the rim
        center = section_center(part, z)
        inward = middle - center[:2]
        if float(np.linalg.norm(inward)) < FINGER_HALF_WIDTH:
            continue  # a part at the middle (a handle's post, a divider)
        axis, width = max(_horizontal_widths(part), key=lambda aw: abs(float(aw[0][:2] @ inward)))
        others = [p for p in solids if p is not part]
        if _fits(width, max_opening) and not _blocked(center, top, z, axis, width, others):
            grasps.append(_grasp(center, axis, width))
    return grasps
