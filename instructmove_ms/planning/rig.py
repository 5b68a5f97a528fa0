"""One arm of the robot as the planners see it at a scene state: kinematics, joint limits,
gripper values and the ``pd_joint_pos`` action layout of the whole robot.

The other arm of a dual-arm rig holds the configuration it had in that state.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from instructmove_ms.agents.hardware import Gripper, JointLimits

from .kinematics import ArmKinematics
from .robot import RobotModel


@dataclass(frozen=True)
class Rig:
    """Arm ``arm`` of a robot (the Franka's only arm; the PiperX's 0 left, 1 right).

    ``shoulder`` is the position (base frame) of the link the arm's first joint turns;
    ``limits`` the joint limits at the demos' pace. ``hold`` is the full ``pd_joint_pos``
    action that keeps the robot where it was in the state the rig was built at;
    ``arm_slots`` and ``gripper_slot`` say where this arm's joint targets and gripper value
    go in it. ``fingers`` lists (index in ``kin.qpos``, direction it opens) of the arm's
    finger joints; ``tip_depth`` is how far the fingertips reach beyond the TCP along the
    approach.
    """

    arm: int
    kin: ArmKinematics
    shoulder: np.ndarray
    limits: JointLimits
    gripper: Gripper
    hold: np.ndarray
    arm_slots: np.ndarray
    gripper_slot: int
    fingers: tuple[tuple[int, float], ...]
    tip_depth: float

    @classmethod
    def of(cls, robot: RobotModel, arm: int, qpos: np.ndarray) -> Rig:
        """Arm ``arm`` of ``robot`` at the full configuration ``qpos``."""
        model = robot.arms[arm]
        return cls(
            arm,
            ArmKinematics(robot, arm, qpos),
            model.shoulder,
            robot.limits,
            robot.gripper,
            robot.hold(qpos),
            np.asarray(model.slots.command),
            model.slots.gripper,
            model.fingers,
            model.tip_depth,
        )

    @property
    def start(self) -> np.ndarray:
        """The arm's configuration in the state the rig was built at."""
        return self.kin.qpos[self.kin.arm]

    @property
    def width(self) -> float:
        """How far apart the arm's fingers are in ``kin`` (metres)."""
        k, sign = self.fingers[0]
        return 2.0 * sign * float(self.kin.qpos[k])

    def opened(self, width: float) -> Rig:
        """This rig with its fingers ``width`` metres apart in ``kin`` (what collision checks
        see)."""
        qpos = self.kin.qpos.copy()
        for k, sign in self.fingers:
            qpos[k] = sign * 0.5 * min(width, self.gripper.max_width)
        return replace(self, kin=self.kin.with_qpos(qpos))

    def actions(self, targets: np.ndarray, gripper: float) -> np.ndarray:
        """``pd_joint_pos`` actions: each row of this arm's joint ``targets`` with its gripper
        action value ``gripper``; the rest of the robot holds still."""
        out = np.repeat(self.hold[None], len(targets), axis=0)
        out[:, self.arm_slots] = targets
        out[:, self.gripper_slot] = gripper
        return out.astype(np.float32)
