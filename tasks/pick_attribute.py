"""PickAttribute: pick the object of a category that has the named attribute."""

from __future__ import annotations

from mani_skill.utils.registration import register_env

from instructmove_ms.sampler import Constraint, RoleSpec

from .base import InstructMoveEnv
from .pick_category import PICK_TEMPLATES
from .spec import TaskSpec

PICK_ATTRIBUTE = TaskSpec(
    env_id="PickAttribute-InstructMove",
    family="pick_attribute",
    cue="attribute",
    default_robot="piperx",
    supported_robots=("franka", "piperx"),
    roles=(
        RoleSpec("target", 1, pool="target"),
        RoleSpec(
            "distractor", 2, pool="any", constraints=(Constraint("category", "match", "target"),)
        ),
    ),
    count_limits={"distractor": (1, 3)},
    templates=PICK_TEMPLATES,
    attributes=("color", "size", "shape", "material"),
)


@register_env(PICK_ATTRIBUTE.env_id, max_episode_steps=PICK_ATTRIBUTE.max_episode_steps)
class PickAttributeEnv(InstructMoveEnv):
    """**Task Description:**
    Pick up the object the instruction describes by an attribute ("the red mug", "the biggest
    apple", "the wooden bowl"). The target and ``num_distractors`` (default 2) distractors
    share one category; every distractor differs from the target in the named attribute
    (colour, size, shape or material), so only the attribute tells them apart.

    **Randomizations:**
    - the category, the instances and the attribute named (among those that tell the target
      apart); sizes differ by at least 1.3x in the largest dimension; colours are pairwise
      distinct so that every candidate can be named
    - positions (reference workspace, 0.05 m between footprints), yaw, template, robot joints

    **Success Conditions:**
    - ``reach``: the TCP came within 0.02 m of the target's box (latched)
    - ``lift``: after reach, the robot grasps the target and raises it 0.03 m (latched);
      ``success`` equals ``lift``
    """

    task = PICK_ATTRIBUTE
