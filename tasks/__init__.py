"""The InstructMove task families; importing registers their ManiSkill envs."""

from .base import InstructMoveEnv
from .pick_category import PICK_CATEGORY, PickCategoryEnv
from .spec import TaskSpec, Thresholds

TASKS = {spec.env_id: spec for spec in (PICK_CATEGORY,)}

__all__ = ["TASKS", "InstructMoveEnv", "PickCategoryEnv", "TaskSpec", "Thresholds"]
