"""The robot as the planners see it, read once per episode from the env's agent.

Its links and joints, their collision geometry and a pinocchio model come from the
articulation; per arm, the joints, end effector, shoulder, fingers and ``pd_joint_pos``
action slots from the agent (``InstructMoveAgent``); the gripper, the joint speed limits
and the demos' pace from the agent class. Poses are in the robot's base frame.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import sapien.physx as physx

from instructmove_ms.agents.hardware import Gripper, JointLimits
from instructmove_ms.agents.interface import ArmSlots, PolicyInterface

from .geometry import Geometry, body_geometry


@dataclass(frozen=True)
class ArmModel:
    """One arm: its ``joints`` and end-effector link ``ee_link``; ``shoulder`` is the
    position of the link its first joint turns; ``fingers`` lists (index among the robot's
    active joints, direction it opens) of its finger joints; ``tip_depth`` is how far the
    fingertips reach beyond the TCP along the approach; ``slots`` where its joint targets
    and gripper value go in a ``pd_joint_pos`` action (None where the agent runs another
    control mode: nothing can be planned for it then)."""

    joints: tuple[str, ...]
    ee_link: str
    shoulder: np.ndarray
    fingers: tuple[tuple[int, float], ...]
    tip_depth: float
    slots: ArmSlots | None


@dataclass(frozen=True)
class RobotModel:
    """The robot's kinematic tree (``parent``: child link -> parent link; ``joint_child``:
    joint -> the link it moves), the collision ``geometry`` of every link that has one, a
    pinocchio ``model``, the active joints' limits, its arms and hardware, its joint-space
    policy ``interface`` (the ``pd_joint_pos`` action layout), whether the agent runs
    ``pd_joint_pos`` (``joint_control``: only then can plans be played) and the rest
    configuration."""

    uid: str
    links: tuple[str, ...]
    joints: tuple[str, ...]
    parent: dict[str, str]
    joint_child: dict[str, str]
    geometry: dict[str, Geometry]
    model: Any
    lower: np.ndarray
    upper: np.ndarray
    arms: tuple[ArmModel, ...]
    gripper: Gripper
    limits: JointLimits
    interface: PolicyInterface
    joint_control: bool
    rest: np.ndarray

    @classmethod
    def from_agent(cls, agent) -> RobotModel:
        """The model of ``agent`` (sub-scene 0)."""
        robot = agent.robot
        joints = tuple(j.name for j in robot.get_active_joints())
        limits = robot.get_qlimits()[0].cpu().numpy().astype(float)
        base_inv = robot.pose.sp.inv()
        geometry = {}
        for link in robot.get_links():
            shapes = body_geometry(link._objs[0].get_collision_shapes())
            if shapes:
                geometry[link.name] = shapes
        joint_control = agent.control_mode == "pd_joint_pos"
        layout = agent.action_layout() if joint_control else (None,) * len(agent.tcp_links)
        grippers = [c for c in agent.controller.controllers.values() if not _drives_arm(agent, c)]
        arms = []
        for k, tcp in enumerate(agent.tcp_links):
            names = [j.name for j in grippers[k].joints]
            fingers = tuple(
                (joints.index(n), float(np.sign(limits[joints.index(n)].sum()))) for n in names
            )
            tips = [robot.joints_map[n].child_link for n in names]
            first = robot.joints_map[agent.arm_joints(k)[0]].parent_link
            arms.append(
                ArmModel(
                    joints=tuple(agent.arm_joints(k)),
                    ee_link=tcp.name,
                    shoulder=np.asarray((base_inv * first.pose.sp).p, dtype=float),
                    fingers=fingers,
                    tip_depth=_reach_along(tips, tcp),
                    slots=layout[k],
                )
            )
        return cls(
            uid=agent.uid,
            links=tuple(link.name for link in robot.get_links()),
            joints=joints,
            parent={
                j.child_link.name: j.parent_link.name
                for j in robot.get_joints()
                if j.parent_link is not None
            },
            joint_child={j.name: j.child_link.name for j in robot.get_joints()},
            geometry=geometry,
            model=robot._objs[0].create_pinocchio_model(),
            lower=limits[:, 0],
            upper=limits[:, 1],
            arms=tuple(arms),
            gripper=agent.gripper,
            limits=agent.joint_limits.faster(agent.demo_pace),
            interface=agent.policy_interface(),
            joint_control=joint_control,
            rest=np.asarray(agent.keyframes["rest"].qpos, dtype=float),
        )

    def hold(self, qpos: np.ndarray) -> np.ndarray:
        """The ``pd_joint_pos`` action that keeps the robot at ``qpos``: every arm joint at
        its position, every gripper at its current opening."""
        if not self.joint_control:
            raise ValueError("planned actions need the pd_joint_pos control mode")
        return self.interface.state(qpos)


def _drives_arm(agent, controller) -> bool:
    return bool(set(agent.arm_joint_names) & {j.name for j in controller.joints})


def _reach_along(links, tcp) -> float:
    """How far the collision boxes and meshes of ``links`` reach along ``tcp``'s z axis."""
    frame = tcp.pose.sp.inv()
    reach = 0.0
    for link in links:
        for shape in link._objs[0].get_collision_shapes():
            if isinstance(shape, physx.PhysxCollisionShapeBox):
                corners = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)])
                points = corners * np.asarray(shape.half_size)
            else:
                points = np.asarray(shape.get_vertices()) * np.asarray(shape.get_scale())
            m = (frame * link.pose.sp * shape.get_local_pose()).to_transformation_matrix()
            reach = max(reach, float((points @ m[2, :3] + m[2, 3]).max()))
    return reach
