"""Motion planning for demo synthesis: kinematics, a collision world and joint-space plans.

Everything works in the robot's base frame (the Franka base stands at the world origin).
"""

from .collision import CollisionWorld
from .kinematics import ArmKinematics
from .planner import (
    JointLimits,
    cartesian_path,
    densify,
    plan_joint_path,
    time_parametrize,
    to_actions,
)

__all__ = [
    "ArmKinematics",
    "CollisionWorld",
    "JointLimits",
    "cartesian_path",
    "densify",
    "plan_joint_path",
    "time_parametrize",
    "to_actions",
]
