"""The InstructMove task families; importing registers their ManiSkill envs."""

from .base import InstructMoveEnv
from .pick_attribute import PICK_ATTRIBUTE, PickAttributeEnv
from .pick_category import PICK_CATEGORY, PickCategoryEnv
from .pick_spatial import PICK_SPATIAL, PickSpatialEnv
from .place_a2b import PLACE_A2B, PlaceA2BEnv
from .spec import TaskSpec, Thresholds

TASKS = {spec.env_id: spec for spec in (PICK_CATEGORY, PICK_ATTRIBUTE, PICK_SPATIAL, PLACE_A2B)}

__all__ = [
    "TASKS",
    "InstructMoveEnv",
    "PickAttributeEnv",
    "PickCategoryEnv",
    "PickSpatialEnv",
    "PlaceA2BEnv",
    "TaskSpec",
    "Thresholds",
]
