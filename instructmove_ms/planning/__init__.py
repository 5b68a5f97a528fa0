"""Motion planning for demo synthesis: a planning scene, kinematics, a collision world and
joint-space plans.

Everything works in the robot's base frame (the Franka base and the PiperX rig's middle
stand at the world origin). ``PlanningScene`` holds what the planners know of an episode;
``Rig`` bundles what a planner needs of one of its arms.
"""

from .collision import CollisionWorld
from .kinematics import ArmKinematics
from .planner import cartesian_path, densify, plan_joint_path, time_parametrize
from .rig import Rig
from .robot import ArmModel, RobotModel
from .scene import PlanningScene, SceneObject, SceneState

__all__ = [
    "ArmKinematics",
    "ArmModel",
    "CollisionWorld",
    "PlanningScene",
    "Rig",
    "RobotModel",
    "SceneObject",
    "SceneState",
    "cartesian_path",
    "densify",
    "plan_joint_path",
    "time_parametrize",
]
