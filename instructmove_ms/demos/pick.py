"""Planned picks of the episode's target with the Franka (``pd_joint_pos`` actions).

Recipe: a grasp affordance of the target -> IK pre-grasp 10 cm above it -> OMPL path there ->
straight-line descent -> close -> straight lift (the object attached to the hand).
"""

from __future__ import annotations

import numpy as np
import sapien
import torch

from instructmove_ms.assets.affordances import grasp_affordances
from instructmove_ms.planning import (
    ArmKinematics,
    CollisionWorld,
    JointLimits,
    cartesian_path,
    plan_joint_path,
    time_parametrize,
    to_actions,
)

PICK_TASKS = ("PickCategory-InstructMove", "PickAttribute-InstructMove", "PickSpatial-InstructMove")
OPEN, CLOSED = 1.0, -1.0
PRE_GRASP = 0.10  # metres above the grasp
LIFT = 0.15  # metres the object is lifted
SETTLE, CLOSE, HOLD = 5, 20, 15  # steps: before the plan, closing the gripper, at the top
#: Heights (m) tried above a grasp whose fingertips would touch the table (low objects).
RAISE = (0.0, 0.003, 0.006, 0.009, 0.012)
STAGES = ("reach", "lift", "success")


def _grasp_poses(env) -> list[sapien.Pose]:
    """Top-down TCP poses at the target's grasp affordances (highest first), each with both
    closing-axis signs, in the robot's base frame."""
    u = env.unwrapped
    spec = u.episode
    inst = u.catalog[spec.objects[spec.target].uuid]
    obj = u.agent.robot.pose.sp.inv() * u.objects[spec.target].pose.sp
    rot = obj.to_transformation_matrix()[:3, :3]
    poses = []
    for grasp in grasp_affordances(inst):
        z = rot @ np.asarray(grasp.approach)
        for sign in (1.0, -1.0):
            y = sign * (rot @ np.asarray(grasp.closing))
            matrix = np.eye(4)
            matrix[:3, :3] = np.stack([np.cross(y, z), y, z], axis=1)
            matrix[:3, 3] = (obj * sapien.Pose(grasp.center)).p
            poses.append(sapien.Pose(matrix))
    return poses


def _above(pose: sapien.Pose, dz: float) -> sapien.Pose:
    return sapien.Pose(pose.p + np.array([0.0, 0.0, dz]), pose.q)


def _pick_path(env, kin: ArmKinematics, start: np.ndarray, grasp: sapien.Pose, q_pre):
    """(path to the pre-grasp, descent, lift) joint paths for one grasp, or None."""
    world = CollisionWorld.from_env(env, kin)
    to_pre = plan_joint_path(world, start, q_pre, time_limit=1.0, attempts=2)
    if to_pre is None:
        return None
    target = f"object_{env.unwrapped.episode.target}"
    for link in world.gripper_links:
        world.allow(link, target)
    for dz in RAISE:  # the lowest grasp whose fingertips clear the table
        descend = cartesian_path(kin, q_pre, _above(grasp, dz), world)
        if descend is not None:
            break
    else:
        return None
    world.attach(target, descend[-1])
    world.allow("attached", "table")  # it stands on the table when the lift begins
    lift = cartesian_path(kin, descend[-1], _above(grasp, dz + LIFT), world)
    return None if lift is None else (to_pre, descend, lift)


def plan_pick(env, limits: JointLimits | None = None) -> np.ndarray | str:
    """``pd_joint_pos`` actions that pick up the episode's target from the env's current
    state, or the failure reason: ``"no_ik"`` (no collision-free pre-grasp configuration for
    any grasp) or ``"no_plan"`` (no collision-free path for any grasp with one)."""
    limits = limits or JointLimits.franka()
    kin = ArmKinematics.from_env(env)
    start = kin.qpos[kin.arm]
    free = CollisionWorld.from_env(env, kin)
    candidates = []
    for grasp in _grasp_poses(env):
        q_pre = kin.ik(
            _above(grasp, PRE_GRASP), seeds=[start], accept=lambda q: not free.in_collision(q)
        )
        if q_pre is not None:
            candidates.append((grasp, q_pre))
    if not candidates:
        return "no_ik"
    for grasp, q_pre in candidates:
        paths = _pick_path(env, kin, start, grasp, q_pre)
        if paths is None:
            continue
        to_pre, descend, lift = paths
        grip = descend[-1:]
        return np.vstack(
            [
                to_actions(np.repeat(start[None], SETTLE, axis=0), OPEN),
                to_actions(time_parametrize(to_pre, limits), OPEN),
                to_actions(time_parametrize(descend, limits), OPEN),
                to_actions(np.repeat(grip, CLOSE, axis=0), CLOSED),
                to_actions(time_parametrize(lift, limits), CLOSED),
                to_actions(np.repeat(lift[-1:], HOLD, axis=0), CLOSED),
            ]
        )
    return "no_plan"


def rollout(env, actions: np.ndarray) -> list[dict[str, bool]]:
    """Step ``env`` through ``actions``; returns each step's stage flags (reach, lift,
    success) of the single sub-scene; the last one is the outcome. Stops early at truncation."""
    flags = []
    for action in actions:
        _, _, _, truncated, info = env.step(torch.from_numpy(action)[None])
        flags.append({k: bool(info[k][0]) for k in STAGES})
        if bool(truncated):
            break
    return flags
