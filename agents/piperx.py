"""AgileX PiperX arms: the dual-arm rig (robot uid ``piperx``) and one arm (``piperx_single``).

Our own descriptions (``descriptions/piperx/*.urdf``, written by its ``generate.py`` from
the published joint table, masses and gripper sizes).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import ClassVar

import numpy as np
import sapien
import torch
from mani_skill.agents.base_agent import BaseAgent, Keyframe
from mani_skill.agents.controllers import (
    PDEEPosControllerConfig,
    PDEEPoseControllerConfig,
    PDJointPosControllerConfig,
    PDJointPosMimicController,
    PDJointPosMimicControllerConfig,
    PDJointVelControllerConfig,
    deepcopy_dict,
)
from mani_skill.agents.registration import register_agent
from mani_skill.sensors.camera import CameraConfig
from mani_skill.utils.structs.link import Link

from .cameras import DEFAULT_HEIGHT, DEFAULT_WIDTH, Intrinsics, PublishedCameraConfig
from .hardware import Gripper, JointLimits
from .interface import InstructMoveAgent

URDF_DIR = Path(__file__).resolve().parent / "descriptions" / "piperx"
#: Initial arm joints j1..j6 of the reference setup; j1 turns each arm toward the middle.
REST_ARM = (0.3197, 0.8987, -1.4058, 1.3924, 0.0308, 0.05)
FINGER_OPEN = 0.05  # finger1 opening (m); the gripper action is twice this

D455 = Intrinsics(fx=640.0, fy=565.1)
D405 = Intrinsics(fx=710.8, fy=649.5)
#: D455 above the middle of the rig (published relative to the left base: (0, -0.3, 0.6036)),
#: optical frame at ROS rpy (-145, 0, -90) deg: looking forward (+x) and 55 deg down.
STATIC_EYE = np.array([0.0, 0.0, 0.6036])
STATIC_RPY = np.deg2rad([-145.0, 0.0, -90.0])
#: D405 on link6, optical frame turned -20 deg about x: looks along the fingers (link6 z),
#: tilted toward the gripper axis; the fingers are at the bottom of the image.
HAND_EYE = (-0.00965, -0.0801, 0.0428)
HAND_TILT = np.deg2rad(-20.0)
#: Joint velocity limit of the vendor description (rad/s), every joint. No acceleration
#: limit is published: ours is 5 times the velocity, within the Franka's ratios (3.4 to 7.7).
VELOCITY = np.full(6, 5.0)
ACCELERATION = np.full(6, 25.0)


def _rot(axis: int, angle: float) -> np.ndarray:
    """Rotation by ``angle`` rad about axis ``axis`` (0 x, 1 y, 2 z)."""
    c, s = np.cos(angle), np.sin(angle)
    i, j = (axis + 1) % 3, (axis + 2) % 3
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def optical_pose(xyz: Sequence[float], rotation: np.ndarray) -> sapien.Pose:
    """Pose of a SAPIEN camera (x forward, y left, z up) from an optical frame (x right,
    y down, z forward) given as a rotation matrix."""
    frame = np.eye(4)
    frame[:3, :3] = np.stack([rotation[:, 2], -rotation[:, 0], -rotation[:, 1]], axis=1)
    frame[:3, 3] = xyz
    return sapien.Pose(frame)


class GripperWidthController(PDJointPosMimicController):
    """One value per gripper, the width between the fingers (2 x finger1 opening, metres);
    finger1 follows half of it and finger2 mirrors finger1."""

    def _get_joint_limits(self) -> np.ndarray:
        return 2.0 * super()._get_joint_limits()

    def _preprocess_action(self, action: torch.Tensor) -> torch.Tensor:
        return 0.5 * super()._preprocess_action(action)


@dataclass
class GripperWidthControllerConfig(PDJointPosMimicControllerConfig):
    controller_cls = GripperWidthController


def _prefix(side: str) -> str:
    return f"{side}_" if side else ""


def _suffix(side: str) -> str:
    return f"_{side}" if side else ""


def _finger_materials(sides: tuple[str, ...]) -> dict:
    pad = dict(material="gripper", patch_radius=0.1, min_patch_radius=0.1)
    return dict(
        _materials=dict(gripper=dict(static_friction=2.0, dynamic_friction=2.0, restitution=0.0)),
        link={f"{_prefix(s)}finger{k}": dict(pad) for s in sides for k in (1, 2)},
    )


def joint_order(sides: tuple[str, ...]) -> list[str]:
    """Active joints in articulation order (SAPIEN orders them breadth-first)."""
    arms = [f"{_prefix(s)}joint{j}" for j in range(1, 7) for s in sides]
    return arms + [f"{_prefix(s)}finger_joint{k}" for s in sides for k in (1, 2)]


def rest_qpos(sides: tuple[str, ...]) -> np.ndarray:
    """The reference rest pose, fingers open; a left arm turns right (-j1) and vice versa."""
    values = {}
    for side in sides:
        sign = {"left": -1.0, "right": 1.0}.get(side, 0.0)
        for j, q in enumerate(REST_ARM, start=1):
            values[f"{_prefix(side)}joint{j}"] = sign * q if j == 1 else q
        values[f"{_prefix(side)}finger_joint1"] = FINGER_OPEN
        values[f"{_prefix(side)}finger_joint2"] = -FINGER_OPEN
    return np.array([values[name] for name in joint_order(sides)])


@register_agent()
class PiperX(InstructMoveAgent, BaseAgent):
    """Dual-arm AgileX PiperX rig: two arms facing +x, bases at y = +0.3 (left) and -0.3
    (right) on the table top, one articulation with a fixed root.

    Control modes (the gripper value is always the finger width in metres, 2 x finger1
    opening: 0.1 open, 0 closed, decoded mirrored onto both fingers):

    - ``pd_joint_pos`` (default), the 14-D policy interface: ``arm`` = left j1..j6, right
      j1..j6 (absolute, rad), then ``gripper_left``, ``gripper_right`` (the reference's
      per-arm order, left 6 + 1 then right 6 + 1, with the two gripper values moved last).
    - ``pd_joint_delta_pos``: the same layout with joint deltas in [-1, 1] (x 0.1 rad), so
      ManiSkill's replay converts between the two (both keep the arm under ``arm``).
    - ``pd_ee_delta_pose``: ``arm_left`` (6: TCP translation, rotation in [-1, 1] x 0.1 m /
      rad, rig frame), ``arm_right`` (6), ``gripper_left``, ``gripper_right``.
    - as ManiSkill's Panda: ``pd_joint_target_delta_pos``, ``pd_joint_vel`` (``arm`` as
      above), ``pd_ee_delta_pos`` (3 per arm), ``pd_ee_target_delta_pos``,
      ``pd_ee_target_delta_pose`` and ``pd_ee_pose`` (absolute TCP pose per arm, rig frame).

    Cameras (published focal lengths at 1280x720, default 160x90): ``static_camera`` (D455
    above the rig looking at the workspace), ``left_hand_camera`` and ``right_hand_camera``
    (D405 on each link6 looking along the fingers). TCPs (``left_tcp``, ``right_tcp``) sit
    0.13 m along link6's z, 2 cm above the fingertips, where a grasped object sits.
    """

    uid = "piperx"
    sides: ClassVar[tuple[str, ...]] = ("left", "right")
    base_offsets: ClassVar[tuple[tuple[float, float, float], ...]] = ((0, 0.3, 0), (0, -0.3, 0))
    urdf_path = str(URDF_DIR / "piperx_dual.urdf")
    urdf_config = _finger_materials(sides)
    keyframes = dict(rest=Keyframe(qpos=rest_qpos(sides), pose=sapien.Pose()))
    scene_cameras = ("static_camera",)
    mount_links = ("left_base_link", "right_base_link")

    #: The action value is the width itself; the fingers slide along link6's (and the
    #: TCP's) x axis.
    gripper = Gripper(0.1, 1.0, 0.0, 0.0, sapien.Pose(q=[np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)]))
    joint_limits = JointLimits(VELOCITY, ACCELERATION)
    demo_pace = 0.15  # about the Franka demos' joint speeds

    arm_stiffness, arm_damping, arm_force_limit = 2e3, 3e2, 100.0
    gripper_stiffness, gripper_damping, gripper_force_limit = 2e3, 1e2, 100.0

    @property
    def arm_joint_names(self) -> list[str]:
        return [f"{_prefix(s)}joint{j}" for s in self.sides for j in range(1, 7)]

    def _arm_joints(self, side: str) -> list[str]:
        return [f"{_prefix(side)}joint{j}" for j in range(1, 7)]

    def _end_effectors(self, config: type, **kwargs) -> dict:
        """One end-effector controller ``config`` per arm, keyed ``arm_<side>`` (``arm``
        for a single arm)."""
        return {
            f"arm{_suffix(s)}": config(
                joint_names=self._arm_joints(s),
                ee_link=f"{_prefix(s)}tcp",
                urdf_path=self.urdf_path,
                stiffness=self.arm_stiffness,
                damping=self.arm_damping,
                force_limit=self.arm_force_limit,
                **kwargs,
            )
            for s in self.sides
        }

    @property
    def _controller_configs(self) -> dict:
        """ManiSkill's Panda modes that make sense for parallel-finger arms (no velocity
        variants of joint position control): joint modes drive every arm joint under ``arm``,
        end-effector modes one controller per arm."""
        drive = dict(
            stiffness=self.arm_stiffness, damping=self.arm_damping, force_limit=self.arm_force_limit
        )
        joint_pos = PDJointPosControllerConfig(
            self.arm_joint_names, None, None, normalize_action=False, **drive
        )
        joint_delta = PDJointPosControllerConfig(
            self.arm_joint_names, -0.1, 0.1, use_delta=True, **drive
        )
        joint_target_delta = PDJointPosControllerConfig(
            self.arm_joint_names, -0.1, 0.1, use_delta=True, use_target=True, **drive
        )
        joint_vel = PDJointVelControllerConfig(
            self.arm_joint_names, -1.0, 1.0, self.arm_damping, self.arm_force_limit
        )
        delta = dict(pos_lower=-0.1, pos_upper=0.1)
        rotation = dict(rot_lower=-0.1, rot_upper=0.1)
        absolute = dict(pos_lower=-2.0, pos_upper=2.0, use_delta=False, normalize_action=False)
        grippers = {
            f"gripper{_suffix(s)}": GripperWidthControllerConfig(
                [f"{_prefix(s)}finger_joint1", f"{_prefix(s)}finger_joint2"],
                None,
                None,
                self.gripper_stiffness,
                self.gripper_damping,
                self.gripper_force_limit,
                normalize_action=False,
                mimic={
                    f"{_prefix(s)}finger_joint2": {
                        "joint": f"{_prefix(s)}finger_joint1",
                        "multiplier": -1.0,
                    }
                },
            )
            for s in self.sides
        }
        pos, pose = PDEEPosControllerConfig, PDEEPoseControllerConfig
        modes = dict(
            pd_joint_pos=dict(arm=joint_pos),
            pd_joint_delta_pos=dict(arm=joint_delta),
            pd_joint_target_delta_pos=dict(arm=joint_target_delta),
            pd_joint_vel=dict(arm=joint_vel),
            pd_ee_delta_pos=self._end_effectors(pos, **delta),
            pd_ee_target_delta_pos=self._end_effectors(pos, **delta, use_target=True),
            pd_ee_delta_pose=self._end_effectors(pose, **delta, **rotation),
            pd_ee_target_delta_pose=self._end_effectors(pose, **delta, **rotation, use_target=True),
            pd_ee_pose=self._end_effectors(pose, **absolute),
        )
        return deepcopy_dict({mode: {**arms, **grippers} for mode, arms in modes.items()})

    def _after_init(self) -> None:
        links = self.robot.links_map
        self._tcps = [links[f"{_prefix(s)}tcp"] for s in self.sides]
        self.finger_links: list[tuple[Link, Link]] = [
            (links[f"{_prefix(s)}finger1"], links[f"{_prefix(s)}finger2"]) for s in self.sides
        ]
        names = [j.name for j in self.robot.get_active_joints()]
        self._arm_index = torch.tensor(
            [names.index(n) for n in self.arm_joint_names], device=self.device
        )

    @property
    def tcp_links(self) -> list[Link]:
        return self._tcps

    @property
    def finger_pairs(self) -> list[tuple[tuple[Link, float], tuple[Link, float]]]:
        """Per arm (0 left, 1 right): finger1 opens along its y axis, finger2 against it."""
        return [((one, 1.0), (two, -1.0)) for one, two in self.finger_links]

    def is_static(self, threshold: float = 0.2) -> torch.Tensor:
        """(N,) true where every arm joint moves slower than ``threshold`` rad/s."""
        qvel = self.robot.get_qvel()[..., self._arm_index]
        return torch.max(torch.abs(qvel), dim=1)[0] <= threshold

    @property
    def _sensor_configs(self) -> list[CameraConfig]:
        links = self.robot.links_map
        first = self.sides[0]
        static_rotation = _rot(2, STATIC_RPY[2]) @ _rot(1, STATIC_RPY[1]) @ _rot(0, STATIC_RPY[0])
        eye = STATIC_EYE - np.asarray(self.base_offsets[0])
        configs = [
            PublishedCameraConfig(
                "static_camera",
                optical_pose(eye, static_rotation),
                DEFAULT_WIDTH,
                DEFAULT_HEIGHT,
                near=0.01,
                far=10.0,
                mount=links[f"{_prefix(first)}base_link"],
                published=D455,
            )
        ]
        for side in self.sides:
            configs.append(
                PublishedCameraConfig(
                    f"{_prefix(side)}hand_camera",
                    optical_pose(HAND_EYE, _rot(0, HAND_TILT)),
                    DEFAULT_WIDTH,
                    DEFAULT_HEIGHT,
                    near=0.01,
                    far=10.0,
                    mount=links[f"{_prefix(side)}link6"],
                    published=D405,
                )
            )
        return configs


@register_agent()
class PiperXSingle(PiperX):
    """One AgileX PiperX arm with its base at the origin, facing +x.

    Control modes as :class:`PiperX` with one arm: ``pd_joint_pos`` (7-D: ``arm`` j1..j6 in
    rad, ``gripper`` width in m), ``pd_joint_delta_pos`` and ``pd_ee_delta_pose`` (``arm``,
    ``gripper``). Cameras: ``static_camera`` (D455 0.6036 m above the base, as in the rig)
    and ``hand_camera`` (D405 on link6).
    """

    uid = "piperx_single"
    sides = ("",)
    base_offsets = ((0, 0, 0),)
    urdf_path = str(URDF_DIR / "piperx_arm.urdf")
    urdf_config = _finger_materials(sides)
    keyframes = dict(rest=Keyframe(qpos=rest_qpos(sides), pose=sapien.Pose()))
