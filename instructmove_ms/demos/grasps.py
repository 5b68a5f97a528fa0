"""Grasp candidates for a planned pick: the target's grasp affordances as TCP poses (both
closing signs, a few turns about the approach), leaned away from the arm where it cannot
reach them upright, ranked by IK feasibility and joint-space cost."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from itertools import product

import numpy as np
import sapien

from instructmove_ms.assets.affordances import (
    enveloping_grasps,
    grasp_affordances,
    rim_grasps,
    section_grasps,
)
from instructmove_ms.planning import CollisionWorld, PlanningScene, Rig
from instructmove_ms.planning.scene import TABLE

#: Leans (rad) of the approach away from the arm's shoulder, tried in this order: a far or
#: high grasp that the hand cannot reach pointing straight down it reaches leaned.
LEANS = np.deg2rad([0.0, 4.0, 8.0, 12.0, 16.0, 20.0, 25.0, 30.0, 37.5, 45.0])
#: Distances (m) back along the approach from the grasp to the pre-grasp, longest first.
PRE_GRASP = (0.10, 0.07, 0.05, 0.03)
#: Metres the fingertips clear the target's top by at the pre-grasp (the arm lags its plan).
PRE_CLEARANCE = 0.01
#: Cost (rad of joint motion) per metre between a grasp and the middle of the target's box
#: in the table plane: grasps far off the middle let the object turn out of the fingers.
OFF_CENTRE_COST = 20.0
#: Turns (rad) of the closing axis about the approach, tried besides the affordance's own:
#: fingers closing askew on a bar align it, and a turned hand can lean with level fingers.
YAWS = np.deg2rad([30.0, -30.0])
YAW_COST = 2.0  # cost (rad of joint motion) per radian of turn
FINGER_CLEARANCE = 0.015  # metres between each open finger and the object at the grasp
#: Grasp kinds tried in turn, each at every lean: around a container's whole section, across
#: its rim (a container too wide for the hand), on one part, around the whole section of
#: parts lying side by side (``GraspFrame.tier``).
TIERS = ("enveloping", "rim", "part", "section")


@dataclass(frozen=True)
class GraspFrame:
    """A grasp affordance of the target in the robot's base frame: ``pose`` has its y axis
    along the closing axis and its z axis along the approach; ``width`` is the object's
    width between the fingers, ``cost`` its ranking cost besides joint motion (off the
    box's middle, turned); ``tier``: which go first (``TIERS``)."""

    pose: sapien.Pose
    width: float
    cost: float
    tier: int


@dataclass(frozen=True)
class Candidate:
    """A grasp reachable from the rig's start: the TCP at the grasp (base frame), the
    object's width between the fingers, a collision-free configuration ``q_pre`` at the
    pre-grasp and its cost (summed joint motion from the start plus the frame's cost);
    ``lands``: the open hand at the grasp touches the target, a finger on a part beside the
    one it should close on (a thick finger between sticks lying close)."""

    tcp: sapien.Pose
    width: float
    q_pre: np.ndarray
    cost: float
    lands: bool


def box_corners(lo, hi) -> np.ndarray:
    """The 8 corners (8, 3) of the box with lowest and highest corners ``lo`` and ``hi``."""
    return np.array(list(product(*zip(lo, hi, strict=True))), dtype=float)


def box_top(pose: sapien.Pose, lo: np.ndarray, hi: np.ndarray) -> float:
    """Height of the highest corner of the box ``lo``..``hi`` at ``pose`` (the object may lie
    turned: an egg rolled over after a relay)."""
    rotation = pose.to_transformation_matrix()[:3, :3]
    return float((box_corners(lo, hi) @ rotation.T)[:, 2].max() + pose.p[2])


def grasp_frames(scene: PlanningScene, max_width: float) -> list[GraspFrame]:
    """The target's grasp affordances for fingers opening ``max_width``, a container's rim
    grasps and, for an object that is no container, its grasps around the whole section
    (parts lying side by side), each with both closing-axis signs, as given and turned by
    ``YAWS`` (the width across a turned bar grows as 1 / cos), with their ``TIERS``."""
    inst = scene.objects[scene.target].instance
    obj, lo, hi = scene.box(scene.target)
    rot = obj.to_transformation_matrix()[:3, :3]
    middle = (obj * sapien.Pose(0.5 * (lo + hi))).p
    whole = set(enveloping_grasps(inst, max_opening=max_width))
    rim = rim_grasps(inst, max_opening=max_width)
    parts = grasp_affordances(inst, max_opening=max_width)
    around = [] if inst.is_container else section_grasps(inst, max_opening=max_width)
    frames = []
    for grasp in dict.fromkeys((*parts, *rim, *around)):
        tier = 0 if grasp in whole else 1 if grasp in rim else 2 if grasp in parts else 3
        z = rot @ np.asarray(grasp.approach)
        center = (obj * sapien.Pose(grasp.center)).p
        offset = OFF_CENTRE_COST * float(np.linalg.norm((center - middle)[:2]))
        for yaw in (0.0, *YAWS):
            width = grasp.width / np.cos(yaw)
            if width > max_width:
                continue
            turn = sapien.Pose(q=[np.cos(yaw / 2), *(np.sin(yaw / 2) * z)])
            closing = turn.to_transformation_matrix()[:3, :3] @ rot @ np.asarray(grasp.closing)
            for sign in (1.0, -1.0):
                y = sign * closing
                matrix = np.eye(4)
                matrix[:3, :3] = np.stack([np.cross(y, z), y, z], axis=1)
                matrix[:3, 3] = center
                cost = offset + YAW_COST * abs(yaw)
                frames.append(GraspFrame(sapien.Pose(matrix), width, cost, tier))
    return frames


def back_off(tcp: sapien.Pose, distance: float) -> sapien.Pose:
    """``tcp`` moved ``distance`` metres back along its approach (its z axis)."""
    approach = tcp.to_transformation_matrix()[:3, 2]
    return sapien.Pose(tcp.p - distance * approach, tcp.q)


def lean_away(
    frame: sapien.Pose, axis: np.ndarray, shoulder: np.ndarray, angle: float
) -> sapien.Pose:
    """``frame`` turned about its origin and ``axis`` (unit, base frame) by ``angle`` rad, the
    way that leans its z axis away from ``shoulder``."""
    radial = np.asarray(frame.p, dtype=float) - shoulder
    z = frame.to_transformation_matrix()[:3, 2]
    # Turning z about the axis moves it along axis x z: pick the sign that moves it away.
    half = 0.5 * angle * (-1.0 if float(np.cross(axis, z)[:2] @ radial[:2]) < 0.0 else 1.0)
    turn = sapien.Pose(q=[np.cos(half), *(np.sin(half) * np.asarray(axis))])
    return sapien.Pose(frame.p) * turn * sapien.Pose(q=frame.q)


def across(frame: sapien.Pose, shoulder: np.ndarray) -> np.ndarray:
    """The horizontal axis across the shoulder-to-frame direction: turning about it leans
    straight away from the shoulder."""
    radial = np.asarray(frame.p, dtype=float)[:2] - shoulder[:2]
    radial /= max(float(np.linalg.norm(radial)), 1e-9)
    return np.array([-radial[1], radial[0], 0.0])


def leaned(frame: sapien.Pose, shoulder: np.ndarray, angle: float) -> list[sapien.Pose]:
    """``frame`` leaned away from ``shoulder`` by ``angle`` rad about its closing (y) axis,
    which keeps the fingers level, and about the axis ``across``, which leans straight away
    (one pose when upright)."""
    if angle == 0.0:
        return [frame]
    closing = frame.to_transformation_matrix()[:3, 1]
    return [lean_away(frame, a, shoulder, angle) for a in (closing, across(frame, shoulder))]


def below_hand(scene: PlanningScene) -> set[str]:
    """What a hand grasping the target may touch: the table and the target."""
    return {TABLE, scene.objects[scene.target].name}


def touches_only(contacts: set[tuple[str, str]], allowed: set[str]) -> bool:
    """Every pair of ``contacts`` (a collision world's) involves one of ``allowed``."""
    return all(allowed.intersection(pair) for pair in contacts)


class Descent:
    """IK acceptance for a pre-grasp: collision-free, and the hand reaches ``tcp`` from it
    (IK seeded there) touching nothing outside ``allowed``. Keeps what the hand at ``tcp``
    touches from each configuration it accepted, for ``lands_on``."""

    def __init__(self, rig: Rig, world: CollisionWorld, tcp: sapien.Pose, allowed: set[str]):
        self.rig, self.world, self.tcp, self.allowed = rig, world, tcp, allowed
        self.touched: dict[bytes, set[tuple[str, str]]] = {}

    def __call__(self, q: np.ndarray) -> bool:
        if self.world.in_collision(q):
            return False
        down = self.rig.kin.ik(self.tcp, seeds=[q], num_random=0)
        if down is None:
            return False
        contacts = self.world.contacts(down)
        if not touches_only(contacts, self.allowed):
            return False
        self.touched[q.tobytes()] = contacts
        return True

    def lands_on(self, q_pre: np.ndarray, name: str) -> bool:
        """Whether the open hand at ``tcp`` from the accepted pre-grasp ``q_pre`` touches
        ``name``: the fingers open a clearance wider than the part they close on, so a touch
        is a finger on another part of the object."""
        return any(name in pair for pair in self.touched[q_pre.tobytes()])


def opening(width: float) -> float:
    """How far apart the fingers open to grasp an object ``width`` metres across."""
    return width + 2.0 * FINGER_CLEARANCE


def candidates(scene: PlanningScene, rig: Rig) -> Iterator[Candidate]:
    """Grasp frames (``grasp_frames``) leaned by each of ``LEANS`` in turn (``leaned``)
    whose pre-grasp (the farthest of ``PRE_GRASP`` with one whose fingertips clear the
    target by ``PRE_CLEARANCE``) has a collision-free IK solution from which the hand,
    its fingers at the grasp's ``opening``, reaches the grasp touching nothing but the
    table and the target (a 7-joint arm's elbow kept off a tall neighbour, a finger off a
    neighbour lying close); within a lean, the cheapest first. The ``TIERS`` go in turn at
    every lean; those whose hand lands beside the target's part (``Descent.lands_on``) go after all
    of them, in the same order. Each lean is solved only when asked for."""
    frames = grasp_frames(scene, rig.gripper.max_width)
    worlds: dict[float, CollisionWorld] = {}
    clear = box_top(*scene.box(scene.target)) + PRE_CLEARANCE
    start = rig.start
    below = below_hand(scene)
    name = scene.objects[scene.target].name
    landing: list[Candidate] = []
    for tier, lean in product(range(len(TIERS)), LEANS):
        found = []
        for frame in (f for f in frames if f.tier == tier):
            width = round(opening(frame.width), 3)
            if width not in worlds:
                worlds[width] = scene.world(rig.opened(width).kin)
            for grasp in leaned(frame.pose, rig.shoulder, lean):
                tcp = grasp * rig.gripper.tcp_in_grasp
                for distance in PRE_GRASP:
                    pre = back_off(tcp, distance)
                    if back_off(pre, -rig.tip_depth).p[2] < clear:
                        break
                    descent = Descent(rig, worlds[width], tcp, below)
                    q_pre = rig.kin.ik(pre, seeds=[start], accept=descent)
                    if q_pre is not None:
                        cost = float(np.abs(q_pre - start).sum()) + frame.cost
                        lands = descent.lands_on(q_pre, name)
                        found.append(Candidate(tcp, frame.width, q_pre, cost, lands))
                        break
        found.sort(key=lambda c: c.cost)
        yield from (c for c in found if not c.lands)
        landing += (c for c in found if c.lands)
    yield from landing
