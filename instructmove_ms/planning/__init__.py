"""Motion planning for demo synthesis: kinematics, a collision world and joint-space plans.

Everything works in the robot's base frame (the Franka base and the PiperX rig's middle
stand at the world origin). ``Rig`` bundles what a planner needs of one arm of a live env.
"""

from .collision import CollisionWorld
from .kinematics import ArmKinematics, arm_joint_names
from .planner import (
    JointLimits,
    cartesian_path,
    densify,
    plan_joint_path,
    time_parametrize,
    to_actions,
)
from .rig import ROBOTS, Gripper, Rig, arm_order

__all__ = [
    "ArmKinematics",
    "CollisionWorld",
    "Gripper",
    "JointLimits",
    "ROBOTS",
    "Rig",
    "arm_joint_names",
    "arm_order",
    "cartesian_path",
    "densify",
    "plan_joint_path",
    "time_parametrize",
    "to_actions",
]
