"""Planned pick-and-place demos for PlaceA2B (``pd_joint_pos`` actions).

Recipe: the planned pick of ``demos.pick`` (grasp, lift, hold) runs first; the place is then
planned closed loop from the live state: the arm's configuration and the object's actual pose
in the hand. Release poses hold the object over the goal receptacle's interior, set upright
where the grasp tilted it (else as held), turned about the vertical to line up with the
interior (a few yaws), leaned with the hand away from the shoulder where a far receptacle
asks for it, as low as the hand clears the receptacle (deep bins: dropped from above the
rim). An OMPL path leads above the release pose, a straight descent reaches it, the gripper
opens and the hand retreats straight up.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import sapien

from instructmove_ms.planning import (
    CollisionWorld,
    PlanningScene,
    Rig,
    cartesian_path,
    plan_joint_path,
)

from .grasps import across, box_corners, lean_away
from .timing import Segment, fitted, hold

CLEARANCE = 0.01  # metres between the object's bottom and the receptacle floor at release
HEIGHT_STEP = 0.01  # release heights are tried upwards from the lowest, this far apart
ABOVE_RIM = 0.04  # the pre-place pose holds the object's bottom this far above the rim
PRE_PLACE = 0.04  # and at least this far above its release pose
RETREAT = 0.10  # metres the open hand moves up
FIT_MARGIN = 0.005  # metres kept between the object's footprint and the interior's walls
UPRIGHT = 0.05  # rad: releases tilted less count as upright (preferred)
YAW_OFFSETS = (0.0, 0.25, -0.25)  # rad, around each alignment with the interior's axes
#: Leans (rad) of the hand and object together away from the shoulder, tried in turn per
#: orientation where it has no release: a far receptacle is reached with a leaned hand. A
#: leaned object's footprint must fit the interior.
PLACE_LEANS = np.deg2rad([0.0, 15.0, 30.0, 45.0])
MAX_RELEASES = 8  # the best releases a path is planned to, at most
OPEN_STEPS = 12  # steps the gripper gets to open
RELEASE_GAP = 0.005  # metres each finger opens away from the released object
SETTLE_STEPS = 40  # steps at most for a dropped object to come to rest
#: Steps a pick leaves of the horizon for the place after it: a hurried place and settling.
PLACE_RESERVE = 120

#: Joint paths of a place: to the pre-place pose and the descent (closed gripper), then the
#: retreat and any further motions (open gripper).
Paths = tuple[np.ndarray, ...]


@dataclass(frozen=True)
class Interior:
    """The goal receptacle's interior in the robot's base frame: ``frame`` sits at the centre
    of its floor (receptacle orientation), ``half`` are its xy half extents and ``height``
    the rim's height above the floor."""

    frame: np.ndarray
    half: np.ndarray
    height: float


@dataclass(frozen=True)
class Release:
    """A collision-free configuration ``q`` holding the object at a place pose: the TCP at
    ``tcp``, the object's bottom ``height`` above the floor, its footprint inside the walls
    where ``fits``, ``tilt`` (rad) off its upright orientation; ``cost`` is the summed joint
    motion from the start."""

    q: np.ndarray
    tcp: sapien.Pose
    height: float
    fits: bool
    tilt: float
    cost: float


def goal_interior(scene: PlanningScene) -> Interior:
    """The destination's interior at the destination's observed pose."""
    region = scene.objects[scene.destination].instance.interior
    pose = scene.pose(scene.destination)
    frame = (pose * sapien.Pose(region.center)).to_transformation_matrix()
    return Interior(frame, np.asarray(region.half), region.height)


def _turn(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _heading(rotation: np.ndarray) -> float:
    """Heading of the rotation's x axis (its y axis where x is near vertical)."""
    axis = rotation[:, 0] if np.linalg.norm(rotation[:2, 0]) > 0.3 else rotation[:, 1]
    return float(np.arctan2(axis[1], axis[0]))


def _upright(rotation: np.ndarray) -> np.ndarray:
    """``rotation`` tilted back by the least rotation that turns its z axis straight up."""
    z = rotation[:, 2]
    axis = np.cross(z, [0.0, 0.0, 1.0])
    sin, cos = float(np.linalg.norm(axis)), float(z[2])
    if sin < 1e-9:
        return rotation
    k = axis / sin
    skew = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return (np.eye(3) + sin * skew + (1.0 - cos) * skew @ skew) @ rotation


def _orientations(interior: Interior, held: np.ndarray) -> Iterator[tuple[np.ndarray, float]]:
    """(orientation, tilt in rad) of the object to release: set upright, and as held where
    that tilts; each turned about the vertical to line up with each of the interior's four
    axis directions, each with ``YAW_OFFSETS``."""
    frame = interior.frame[:3, :3]
    held_tilt = float(np.arccos(np.clip(held[2, 2], -1.0, 1.0)))
    for rotation, tilt in [(_upright(held), 0.0)] + [(held, held_tilt)] * (held_tilt > UPRIGHT):
        misalignment = _heading(frame.T @ rotation)
        for quarter in range(4):
            for offset in YAW_OFFSETS:
                turn = frame @ _turn(quarter * np.pi / 2 + offset - misalignment) @ frame.T
                yield turn @ rotation, tilt


def _object_pose(
    interior: Interior, rotation: np.ndarray, corners: np.ndarray, height: float
) -> sapien.Pose:
    """The object pose with orientation ``rotation`` whose bounding box (``corners`` in the
    object's frame) is centred over the interior, its bottom ``height`` above the floor."""
    frame = interior.frame
    centre = corners.mean(axis=0)
    lowest = (frame[:3, :3].T @ rotation @ (corners - centre).T)[2].min()
    matrix = np.eye(4)
    matrix[:3, :3] = rotation
    matrix[:3, 3] = frame[:3, :3] @ [0.0, 0.0, height - lowest] + frame[:3, 3] - rotation @ centre
    return sapien.Pose(matrix)


def _fits(interior: Interior, rotation: np.ndarray, corners: np.ndarray) -> bool:
    """The footprint of the box ``corners``, turned by ``rotation`` and centred over the
    interior, keeps ``FIT_MARGIN`` from its walls."""
    local = interior.frame[:3, :3].T @ rotation @ (corners - corners.mean(axis=0)).T
    margin = interior.half[:, None] - np.abs(local[:2])
    return bool(np.all(margin >= FIT_MARGIN))


def releases(
    scene: PlanningScene, rig: Rig, world: CollisionWorld, interior: Interior
) -> list[Release]:
    """The lowest collision-free release of every orientation, at the least of
    ``PLACE_LEANS`` that has one, best first: the footprint fits, then the object stands
    upright, then the lowest, then the least joint motion."""
    held, lo, hi = scene.box(scene.target)
    corners = box_corners(lo, hi)
    grip_inv = held.inv() * rig.kin.fk(rig.start)  # the TCP in the object's frame
    heights = np.arange(CLEARANCE, interior.height + ABOVE_RIM, HEIGHT_STEP)
    grip = grip_inv.to_transformation_matrix()[:3, :3]
    found = []
    for rotation, tilt in _orientations(interior, held.to_transformation_matrix()[:3, :3]):
        for lean in PLACE_LEANS:
            turned = _lean(interior.frame[:3, 3], rotation @ grip, rig, lean) @ rotation
            fits = _fits(interior, turned, corners)
            if lean > 0.0 and not fits:
                break  # leaning further only widens the footprint
            hit = _lowest(rig, world, interior, turned, corners, grip_inv, heights)
            if hit is not None:
                q, tcp, height = hit
                cost = float(np.abs(q - rig.start).sum())
                found.append(Release(q, tcp, height, fits, tilt + lean, cost))
                break
    return sorted(found, key=lambda r: (not r.fits, r.tilt > UPRIGHT, r.height, r.cost))


def _lowest(
    rig: Rig,
    world: CollisionWorld,
    interior: Interior,
    rotation: np.ndarray,
    corners: np.ndarray,
    grip_inv: sapien.Pose,
    heights: np.ndarray,
) -> tuple[np.ndarray, sapien.Pose, float] | None:
    """(configuration, TCP, height) of the lowest of ``heights`` at which the object, turned
    to ``rotation`` and held by ``grip_inv`` (the TCP in its frame), has a collision-free
    IK solution over the interior; None where none has."""
    for height in heights:
        tcp = _object_pose(interior, rotation, corners, height) * grip_inv
        q = rig.kin.ik(tcp, seeds=[rig.start], accept=lambda q: not world.in_collision(q))
        if q is not None:
            return q, tcp, float(height)
    return None


def _lean(point: np.ndarray, hand: np.ndarray, rig: Rig, angle: float) -> np.ndarray:
    """The rotation (base frame) that leans a hand at ``point`` with orientation ``hand``
    away from the shoulder by ``angle`` rad."""
    frame = np.eye(4)
    frame[:3, :3], frame[:3, 3] = hand, point
    tcp = sapien.Pose(frame)
    leaned = lean_away(tcp, across(tcp, rig.shoulder), rig.shoulder, angle)
    return leaned.to_transformation_matrix()[:3, :3] @ hand.T


def _above(pose: sapien.Pose, dz: float) -> sapien.Pose:
    return sapien.Pose(pose.p + np.array([0.0, 0.0, dz]), pose.q)


def place_paths(
    rig: Rig, world: CollisionWorld, release: Release, rim: float, home: np.ndarray | None = None
) -> Paths | None:
    """(path to the pre-place pose, descent, retreat[, path home]) joint paths for one
    release, or None. Where the pre-place pose above the rim is out of reach, the path leads
    to the release itself and the descent is that one configuration. The retreat holds still
    where the open hand cannot move straight up; with ``home`` (an arm configuration) the
    open hand then goes there, or the release fails."""
    kin = rig.kin
    rise = max(PRE_PLACE, rim + ABOVE_RIM - release.height)
    q_pre = kin.ik(
        _above(release.tcp, rise), seeds=[release.q], accept=lambda q: not world.in_collision(q)
    )
    if q_pre is None:  # too high to reach: a path straight to the release, over the rim
        to_pre = plan_joint_path(world, rig.start, release.q)
        descend = None if to_pre is None else to_pre[-1:]
    else:
        to_pre = plan_joint_path(world, rig.start, q_pre)
        descend = None if to_pre is None else cartesian_path(kin, q_pre, release.tcp, world)
    if descend is None:
        return None
    name = world.detach(descend[-1])
    for link in world.gripper_links:  # the open fingers leave the object
        world.allow(link, name)
    retreat = cartesian_path(kin, descend[-1], _above(kin.fk(descend[-1]), RETREAT), world)
    retreat = descend[-1:] if retreat is None else retreat
    back = None if home is None else plan_joint_path(world, retreat[-1], home)
    world.attach(name, descend[-1])  # as it was, for the next release
    if home is None:
        return to_pre, descend, retreat
    return None if back is None else (to_pre, descend, retreat, back)


def segments(rig: Rig, paths: Paths) -> list[Segment]:
    """The place motions of ``paths``: to the pre-place pose and the descent holding, the
    fingers opening ``RELEASE_GAP`` off the object, the motions after with them so."""
    to_pre, descend, *after = paths
    # the fingers open just clear of the object: wide open they press on a pot's walls
    open_, closed = rig.gripper.value(rig.width + 2 * RELEASE_GAP), rig.gripper.closed
    return [
        Segment(to_pre, closed),
        Segment(descend, closed),
        hold(descend[-1], OPEN_STEPS, open_),
        *(Segment(p, open_) for p in after),
    ]


def held_world(scene: PlanningScene, rig: Rig) -> CollisionWorld:
    """The collision world of ``rig`` with the target attached to its hand."""
    world = scene.world(rig.kin)
    target = scene.objects[scene.target].name
    for link in world.gripper_links:
        world.allow(link, target)
    world.attach(target, rig.start)
    return world


def plan_release(
    scene: PlanningScene, rig: Rig, interior: Interior, steps: int, home: np.ndarray | None = None
) -> np.ndarray | str:
    """Actions that set the held target down in ``interior`` (see ``place_paths`` for
    ``home``), fitted into ``steps`` where the speed-ups allow, or the failure reason:
    ``"no_ik"`` (no collision-free release configuration) or ``"no_plan"`` (no
    collision-free path to the ``MAX_RELEASES`` best)."""
    world = held_world(scene, rig)
    found = releases(scene, rig, world, interior)
    if not found:
        return "no_ik"
    for release in found[:MAX_RELEASES]:
        paths = place_paths(rig, world, release, interior.height, home)
        if paths is not None:
            return fitted(rig, segments(rig, paths), steps)
    return "no_plan"


def plan_place(scene: PlanningScene) -> np.ndarray | str:
    """``pd_joint_pos`` actions that place the held target in the destination from the
    scene's observed state, or the failure reason (``plan_release``). The motion is sped up
    where needed to leave ``SETTLE_STEPS`` of the episode's horizon."""
    rig = scene.rig(scene.holding_arm())
    return plan_release(scene, rig, goal_interior(scene), scene.steps_left - SETTLE_STEPS)
