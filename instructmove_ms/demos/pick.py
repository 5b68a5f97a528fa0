"""Planned picks of the episode's target (``pd_joint_pos`` actions), Franka or PiperX rig.

Recipe: the arm nearest the target first (the other one of a rig as fallback) -> grasp
candidates (affordances, leaned away where upright is out of reach, cheapest IK first) ->
OMPL path to the pre-grasp back along the approach -> straight descent -> close -> straight
lift (the object attached to the hand) as high as the arm reaches, up to ``LIFT``. The other
arm of a rig holds still.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from itertools import islice

import numpy as np
import sapien

from instructmove_ms.planning import (
    CollisionWorld,
    PlanningScene,
    Rig,
    cartesian_path,
    plan_joint_path,
)

from .grasps import (
    Candidate,
    across,
    back_off,
    below_hand,
    box_top,
    candidates,
    lean_away,
    opening,
    touches_only,
)
from .timing import Segment, fitted, hold

LIFT = 0.15  # metres the object is lifted where the arm reaches that high
MIN_LIFT = 0.06  # and at least this much
#: Leans (rad) added away from the shoulder along the lift, tried in turn: leaning helps a
#: stretched arm rise.
LIFT_LEANS = np.deg2rad([0.0, 15.0, 30.0])
#: Steps: before the plan, at the pre-grasp and at the grasp (the arm catches up with its
#: lagging PD targets before it goes on), closing the gripper, at the top.
SETTLE, PAUSE, CLOSE, HOLD = 5, 10, 20, 15
RAISE_STEP = 0.0015  # metres a grasp touching the table (or a container's floor) is raised
#: A grasp may rise until the TCP is this much short of the task's reach distance from the
#: object's box (the PD lags the targets a little).
REACH_MARGIN = 0.005
MAX_CANDIDATES = 30  # grasp candidates tried per arm
#: Metres the fingertips reach at least below the target's top (a flat object grasped with a
#: leaned hand, whose fingers cannot go lower without touching the table).
MIN_OVERLAP = 0.006


def _above(pose: sapien.Pose, dz: float) -> sapien.Pose:
    return sapien.Pose(pose.p + np.array([0.0, 0.0, dz]), pose.q)


def _grasp_height(
    scene: PlanningScene, rig: Rig, world: CollisionWorld, cand: Candidate
) -> sapien.Pose | None:
    """The candidate's grasp raised by the least multiple of ``RAISE_STEP`` that keeps the
    hand off the table and the target (a finger inside a low container), or None where that
    configuration touches anything else, the TCP would no longer reach the target's box
    (``REACH_MARGIN``) or the fingertips would end above both the affordance's grasp centre
    and ``MIN_OVERLAP`` below the target's top."""
    pose, lo, hi = scene.box(scene.target)
    top = box_top(pose, lo, hi)
    reach = scene.reach - REACH_MARGIN
    below = below_hand(scene)
    grasp = cand.tcp
    while True:
        local = (pose.inv() * grasp).p
        outside = np.linalg.norm(np.maximum(np.maximum(lo - local, local - hi), 0.0))
        tip = back_off(grasp, -rig.tip_depth).p[2]
        if outside > reach or tip > max(cand.tcp.p[2], top - MIN_OVERLAP):
            return None
        q = rig.kin.ik(grasp, seeds=[cand.q_pre], num_random=0)
        if q is None:
            return None
        contacts = world.contacts(q)
        if not contacts:
            return grasp
        if not touches_only(contacts, below):
            return None
        grasp = _above(grasp, RAISE_STEP)


def _grasp_and_lift(
    scene: PlanningScene, rig: Rig, cand: Candidate
) -> tuple[np.ndarray, np.ndarray] | None:
    """(descent, lift) joint paths from the candidate's pre-grasp, or None."""
    kin = rig.kin
    world = scene.world(kin)
    grasp = _grasp_height(scene, rig, world, cand)
    if grasp is None:
        return None
    descend = cartesian_path(kin, cand.q_pre, grasp, world)
    if descend is None:
        return None
    world.attach(scene.objects[scene.target].name, descend[-1])
    world.allow("attached", "table")  # it stands on the table when the lift begins
    lift = _lift(rig, world, descend[-1], grasp)
    return None if lift is None else (descend, lift)


def _lift(rig: Rig, world: CollisionWorld, q: np.ndarray, grasp: sapien.Pose) -> np.ndarray | None:
    """A straight lift of ``LIFT`` from configuration ``q`` at ``grasp``, leaning by the first
    of ``LIFT_LEANS`` that gets there, else the highest lift of ``MIN_LIFT`` at least; None
    where none rises that far."""
    best, top = None, grasp.p[2] + MIN_LIFT
    axis = across(grasp, rig.shoulder)
    for lean in LIFT_LEANS:
        goal = _above(lean_away(grasp, axis, rig.shoulder, lean), LIFT)
        lift = cartesian_path(rig.kin, q, goal, world, partial=True)
        height = rig.kin.fk(lift[-1]).p[2]
        if height >= top:
            best, top = lift, height
        if height >= goal.p[2] - 1e-3:
            break
    return best


def _arm_plans(
    scene: PlanningScene, rig: Rig, free: CollisionWorld, ranked: list[Candidate], steps: int
) -> Iterator[np.ndarray]:
    """The pick actions with ``rig``'s arm for each of the ``ranked`` candidates that has a
    collision-free plan in ``free`` (the arm's world), in order, fitted into ``steps``. The
    fingers open to the grasp's ``opening`` (a clearance each side of the object); fully
    only where no candidate works so (a finger inside a container)."""
    start, closed = rig.start, rig.gripper.closed
    for wide in (False, True):
        planned = False
        for cand in ranked:
            width = rig.gripper.max_width if wide else opening(cand.width)
            paths = _grasp_and_lift(scene, rig.opened(width), cand)
            if paths is None:
                continue
            to_pre = plan_joint_path(free, start, cand.q_pre)
            if to_pre is None:
                continue
            planned = True
            descend, lift = paths
            open_ = rig.gripper.value(width)
            segments = [
                hold(start, SETTLE, open_),
                Segment(to_pre, open_),
                hold(to_pre[-1], PAUSE, open_),
                Segment(descend, open_),
                hold(descend[-1], PAUSE, open_),
                hold(descend[-1], CLOSE, closed),
                Segment(lift, closed),
                hold(lift[-1], HOLD, closed),
            ]
            yield fitted(rig, segments, steps)
        if planned:
            return


def plan_pick(
    scene: PlanningScene,
    arms: Sequence[int] | None = None,
    steps: int | None = None,
    skip: int = 0,
) -> np.ndarray | str:
    """``pd_joint_pos`` actions that pick up the scene's target from its observed state, or
    the failure reason: ``"no_ik"`` (no collision-free pre-grasp configuration for
    any grasp with any arm) or ``"no_plan"`` (no collision-free path for any grasp with one,
    or fewer than ``skip + 1`` plans). ``arms`` (default: all) are tried nearest the target
    first; for a scene with a destination, nearest the middle between both, so that the arm
    can carry the target there. Each arm's grasp candidates go cheapest first; the
    first ``skip`` plans are passed over (another grasp after one that slipped). The motions
    are sped up where needed to fit into ``steps`` (default: the rest of the horizon)."""
    steps = scene.steps_left if steps is None else steps
    point = scene.pose(scene.target).p
    if scene.destination >= 0:
        point = (point + scene.pose(scene.destination).p) / 2
    reason = "no_ik"
    for arm in scene.arm_order(point):
        if arms is not None and arm not in arms:
            continue
        rig = scene.rig(arm)
        free = scene.world(rig.kin)
        ranked = list(islice(candidates(scene, rig), MAX_CANDIDATES))
        if ranked:
            reason = "no_plan"
        for actions in _arm_plans(scene, rig, free, ranked, steps):
            if skip == 0:
                return actions
            skip -= 1
    return reason
