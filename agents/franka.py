"""Franka Panda with a DROID-style camera rig (robot uid ``franka``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import sapien
from mani_skill.agents.base_agent import Keyframe
from mani_skill.agents.registration import register_agent
from mani_skill.agents.robots.panda.panda import Panda
from mani_skill.utils import sapien_utils

from instructmove_ms.layout import Workspace

from .cameras import DEFAULT_HEIGHT, DEFAULT_WIDTH, Intrinsics, PublishedCameraConfig
from .hardware import Gripper, JointLimits
from .interface import InstructMoveAgent

#: Rest pose of the reference setup: 7 arm joints, then both fingers open (0.04 m).
FRANKA_REST_QPOS = np.array([0.0, -0.569, 0.0, -1.97, 0.0, 1.5, 0.741, 0.04, 0.04])
#: Point the external cameras look at: the centre of the reference workspace.
WORKSPACE_CENTER = (0.40, 0.0, 0.05)

EXT1 = Intrinsics(fx=500.0, fy=500.0)
EXT2 = Intrinsics(fx=531.9, fy=531.9)
WRIST = Intrinsics(fx=666.7, fy=666.7)
WRIST_EYE = (0.124, -0.0018, -0.049)
#: Joint limits from the datasheet: velocity (rad/s) and acceleration (rad/s^2).
VELOCITY = np.array([2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61])
ACCELERATION = np.array([15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0])


@register_agent()
class FrankaInstructMove(InstructMoveAgent, Panda):
    """Franka Panda for InstructMove.

    Control modes are ManiSkill's Panda ones; the default ``pd_joint_pos`` is the 8-D policy
    interface: 7 absolute joint positions (rad) and 1 gripper value in [-1, 1] (ManiSkill's
    normalised Panda gripper: 1 opens each finger to 0.04 m, -1 closes).
    ``pd_joint_delta_pos`` and ``pd_ee_delta_pose`` keep the arm controller under the key
    ``arm``, so ManiSkill's replay converts between them.

    Cameras (published intrinsics at 1280x720; default resolution 160x90):
    ``ext1_camera`` and ``ext2_camera`` on the base frame looking at the workspace, and
    ``wrist_camera`` on the hand looking along the fingers.
    """

    uid = "franka"
    #: ManiSkill's Panda with lighter visual meshes (descriptions/franka/PROVENANCE.md):
    #: the same physics, a third of the render.
    urdf_path = str(
        Path(__file__).resolve().parent / "descriptions" / "franka" / "panda_light.urdf"
    )
    #: A top-down grasp stays well conditioned from 0.3 m in front of the base.
    workspace = Workspace(x=(0.3, 0.6), y=(-0.35, 0.35))
    scene_cameras = ("ext1_camera", "ext2_camera")
    keyframes = dict(rest=Keyframe(qpos=FRANKA_REST_QPOS.copy(), pose=sapien.Pose()))
    #: ManiSkill's normalised Panda gripper: [-1, 1] spans finger targets -0.01..0.04 m; the
    #: TCP's y axis is the fingers' axis.
    gripper = Gripper(0.08, 20.0, -0.6, -1.0, sapien.Pose())
    joint_limits = JointLimits(VELOCITY, ACCELERATION)
    demo_pace = 0.3  # demos move calmly and the PD tracks them

    @property
    def tcp_links(self) -> list:
        return [self.tcp]

    @property
    def finger_pairs(self) -> list:
        """The hand's fingers: finger1 opens along its y axis, finger2 against it."""
        return [((self.finger1_link, 1.0), (self.finger2_link, -1.0))]

    @property
    def _sensor_configs(self):
        base = self.robot.links_map["panda_link0"]
        hand = self.robot.links_map["panda_hand"]
        configs = []
        for uid, eye, intr in (
            ("ext1_camera", (0.404, 0.473, 0.272), EXT1),
            ("ext2_camera", (0.260, -0.366, 0.248), EXT2),
        ):
            pose = sapien_utils.look_at(eye=eye, target=WORKSPACE_CENTER)
            configs.append(
                PublishedCameraConfig(
                    uid,
                    pose,
                    DEFAULT_WIDTH,
                    DEFAULT_HEIGHT,
                    near=0.01,
                    far=10.0,
                    mount=base,
                    published=intr,
                )
            )
        # Published mount on the hand; the hand's z axis points through the fingertips and the
        # camera looks at the grasp region between them.
        wrist_pose = sapien_utils.look_at(eye=WRIST_EYE, target=(0.0, 0.0, 0.15))
        configs.append(
            PublishedCameraConfig(
                "wrist_camera",
                wrist_pose,
                DEFAULT_WIDTH,
                DEFAULT_HEIGHT,
                near=0.01,
                far=10.0,
                mount=hand,
                published=WRIST,
            )
        )
        return configs
