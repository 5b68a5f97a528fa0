"""The InstructMove task families, one file each; importing registers their ManiSkill envs.

``TASKS`` maps each env id, and ``FAMILIES`` each family name (``EpisodeSpec.family``), to
the family's ``TaskSpec``.
"""

from instructmove_ms.family import Cue, StageSchema, TaskSpec, Thresholds

from .base import InstructMoveEnv
from .pick_attribute import PICK_ATTRIBUTE, AttributeCue, PickAttributeEnv
from .pick_category import PICK_CATEGORY, PICK_STAGES, CategoryCue, PickCategoryEnv
from .pick_spatial import PICK_SPATIAL, PickSpatialEnv, RelationCue
from .place_a2b import PLACE_A2B, PLACE_STAGES, PlaceA2BEnv

TASKS = {spec.env_id: spec for spec in (PICK_CATEGORY, PICK_ATTRIBUTE, PICK_SPATIAL, PLACE_A2B)}
FAMILIES = {spec.family: spec for spec in TASKS.values()}

__all__ = [
    "FAMILIES",
    "PICK_ATTRIBUTE",
    "PICK_CATEGORY",
    "PICK_SPATIAL",
    "PICK_STAGES",
    "PLACE_A2B",
    "PLACE_STAGES",
    "TASKS",
    "AttributeCue",
    "CategoryCue",
    "Cue",
    "InstructMoveEnv",
    "PickAttributeEnv",
    "PickCategoryEnv",
    "PickSpatialEnv",
    "PlaceA2BEnv",
    "RelationCue",
    "StageSchema",
    "TaskSpec",
    "Thresholds",
]
