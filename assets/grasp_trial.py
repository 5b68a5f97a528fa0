"""Physics grasp trials: a free-floating Franka gripper picks each instance up.

The gripper (ManiSkill's Panda hand with its fingers, on six driven root joints) approaches a
settled instance from above along one of its affordances, closes, and lifts. A trial passes
when the object rose with the gripper and both fingers touch it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import sapien
import sapien.physx as physx
from mani_skill import PACKAGE_ASSET_DIR

from .affordances import Grasp, grasp_affordances
from .catalog import Instance
from .parts import quat_to_matrix
from .sim import TIMESTEP, spawn, table_scene

GRIPPER_URDF = f"{PACKAGE_ASSET_DIR}/robots/panda/panda_v2_gripper.urdf"
TCP_OFFSET = 0.1034  # panda_hand to panda_hand_tcp along the hand's z axis
LIFT = 0.12
PASS_RISE = 0.08
OPEN, CLOSED = 0.04, -0.01


@dataclass(frozen=True)
class TrialResult:
    uuid: str
    category: str
    passed: bool
    tries: int
    rise: float


class FloatingGripper:
    def __init__(self, scene: sapien.Scene) -> None:
        loader = scene.create_urdf_loader()
        loader.fix_root_link = True
        self.robot = loader.load(GRIPPER_URDF)
        grip = physx.PhysxMaterial(2.0, 2.0, 0.0)
        for link in self.robot.links:
            link.disable_gravity = True
            if "finger" in link.name:
                for shape in link.collision_shapes:
                    shape.set_physical_material(grip)
        self.joints = self.robot.active_joints
        for joint in self.joints[:6]:
            joint.set_drive_properties(4000.0, 400.0, 1000.0)
        for joint in self.joints[6:]:
            joint.set_drive_properties(1000.0, 100.0, 100.0)
        self.fingers = [lk for lk in self.robot.links if lk.name.endswith("finger")]

    def pose_qpos(self, tcp: np.ndarray, closing_yaw: float, finger: float) -> np.ndarray:
        """Root joints putting the TCP at ``tcp``, fingers down, closing along the yaw."""
        rz = math.atan2(-math.cos(closing_yaw), -math.sin(closing_yaw))
        return np.array([tcp[0], tcp[1], tcp[2] + TCP_OFFSET, math.pi, 0.0, rz, finger, finger])

    def drive(self, qpos: np.ndarray) -> None:
        for joint, q in zip(self.joints, qpos, strict=True):
            joint.set_drive_target(float(q))

    def teleport(self, qpos: np.ndarray) -> None:
        self.robot.set_qpos(qpos)
        self.robot.set_qvel(np.zeros_like(qpos))
        self.drive(qpos)


def _move(
    scene, gripper: FloatingGripper, start: np.ndarray, goal: np.ndarray, seconds: float
) -> None:
    steps = max(1, int(seconds / TIMESTEP))
    for k in range(1, steps + 1):
        gripper.drive(start + (goal - start) * k / steps)
        scene.step()


def _touches_both(scene: sapien.Scene, gripper: FloatingGripper, entity) -> bool:
    touching = set()
    for contact in scene.get_contacts():
        bodies = {contact.bodies[0].entity, contact.bodies[1].entity}
        if entity in bodies:
            for finger in gripper.fingers:
                if finger.entity in bodies and any(
                    np.linalg.norm(p.impulse) > 1e-6 for p in contact.points
                ):
                    touching.add(finger.name)
    return len(touching) == 2


def _attempt(scene, gripper: FloatingGripper, inst: Instance, grasp: Grasp) -> float:
    """One pick along ``grasp``; returns the object's rise (negative if it was not held)."""
    entity = spawn(scene, inst)
    for _ in range(int(0.25 / TIMESTEP)):
        scene.step()
    pose = entity.pose
    rot = quat_to_matrix(tuple(pose.q))
    center = np.asarray(pose.p) + rot @ np.asarray(grasp.center)
    closing = rot @ np.asarray(grasp.closing)
    yaw = math.atan2(closing[1], closing[0])
    z0 = float(pose.p[2])
    above = gripper.pose_qpos(center + [0, 0, 0.1], yaw, OPEN)
    at = gripper.pose_qpos(center, yaw, OPEN)
    shut = gripper.pose_qpos(center, yaw, CLOSED)
    lifted = gripper.pose_qpos(center + [0, 0, LIFT], yaw, CLOSED)
    gripper.teleport(above)
    _move(scene, gripper, above, at, 0.4)
    _move(scene, gripper, at, shut, 0.3)
    _move(scene, gripper, shut, lifted, 0.5)
    _move(scene, gripper, lifted, lifted, 0.25)
    rise = float(entity.pose.p[2]) - z0
    held = _touches_both(scene, gripper, entity)
    scene.remove_entity(entity)
    return rise if held else -1.0


def grasp_trial(instances: list[Instance], max_tries: int = 3) -> list[TrialResult]:
    """Try up to ``max_tries`` affordances per graspable instance (highest first)."""
    scene = table_scene()
    gripper = FloatingGripper(scene)
    parked = gripper.pose_qpos(np.array([0.0, 0.0, 1.0]), 0.0, OPEN)
    gripper.teleport(parked)  # out of the way before the first object spawns
    results = []
    for inst in instances:
        if not inst.is_graspable:
            continue
        grasps = grasp_affordances(inst)[:max_tries]
        rise, tries = -1.0, 0
        for tries, grasp in enumerate(grasps, start=1):  # noqa: B007  (tries is reported)
            rise = _attempt(scene, gripper, inst, grasp)
            gripper.teleport(parked)
            if rise >= PASS_RISE:
                break
        results.append(TrialResult(inst.uuid, inst.category, rise >= PASS_RISE, tries, rise))
    return results
