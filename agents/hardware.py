"""What planners, scripted policies and converters need to know of a robot's hardware,
declared by each agent class: its gripper and its joints' speed limits."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sapien


@dataclass(frozen=True)
class Gripper:
    """A parallel gripper: its ``pd_joint_pos`` action value is ``offset + scale * width``
    for fingers ``width`` metres apart (up to ``max_width``); ``closed`` squeezes whatever is
    between them. ``tcp_in_grasp`` is the TCP frame in a grasp frame whose y axis is the
    fingers' closing axis and whose z axis is the approach."""

    max_width: float
    scale: float
    offset: float
    closed: float
    tcp_in_grasp: sapien.Pose

    def value(self, width):
        """The action value that opens the fingers ``width`` metres apart (a number or an
        array of them)."""
        return self.offset + self.scale * np.minimum(width, self.max_width)

    @property
    def open(self) -> float:
        return self.value(self.max_width)


@dataclass(frozen=True)
class JointLimits:
    """Per-joint velocity (rad/s) and acceleration (rad/s^2) bounds of one arm."""

    velocity: np.ndarray
    acceleration: np.ndarray

    def faster(self, factor: float) -> JointLimits:
        """These limits, both ``factor`` times higher (below 1: slower)."""
        return JointLimits(self.velocity * factor, self.acceleration * factor)
