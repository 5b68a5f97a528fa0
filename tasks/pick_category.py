"""PickCategory: pick up the object of the named category among cross-category distractors."""

from __future__ import annotations

from mani_skill.utils.registration import register_env

from instructmove_ms.sampler import EACH_OTHER, Constraint, RoleSpec

from .base import InstructMoveEnv
from .spec import TaskSpec

PICK_TEMPLATES = (
    "pick up the {target}",
    "pick the {target} up",
    "grab the {target}",
    "lift the {target}",
    "grasp the {target} and lift it",
    "take the {target} off the table",
    "raise the {target}",
    "please pick up the {target}",
    "can you lift the {target}",
    "get the {target} and hold it up",
)

PICK_CATEGORY = TaskSpec(
    env_id="PickCategory-InstructMove",
    family="pick_category",
    cue="category",
    default_robot="piperx",
    supported_robots=("franka", "piperx"),
    roles=(
        RoleSpec("target", 1, pool="target"),
        RoleSpec(
            "distractor",
            5,
            constraints=(
                Constraint("category", "differ", "target"),
                Constraint("category", "differ", EACH_OTHER),
                Constraint("name", "differ", "target"),
                Constraint("name", "differ", EACH_OTHER),
            ),
        ),
    ),
    count_limits={"distractor": (1, 5)},
    templates=PICK_TEMPLATES,
)


@register_env(PICK_CATEGORY.env_id, max_episode_steps=PICK_CATEGORY.max_episode_steps)
class PickCategoryEnv(InstructMoveEnv):
    """**Task Description:**
    Pick up the object whose category the instruction names. The table holds one target
    and ``num_distractors`` (default 5) distractors, each of a different category from the
    target and from each other, all graspable: only the instruction tells the target apart.

    **Randomizations:**
    - target and distractor categories and instances, drawn from the split's pool
    - object positions (reference workspace x 0.25..0.55 m, y -0.35..0.35 m, at least 0.05 m
      between footprints) and yaw
    - the instruction's template and the category noun
    - robot initial joints: rest pose plus Gaussian noise (``robot_init_qpos_noise``)

    **Success Conditions:**
    - ``reach``: the TCP came within 0.02 m of the target's box (latched)
    - ``lift``: after reach, the robot grasps the target and it is 0.03 m above its initial
      height (latched); ``success`` equals ``lift``
    """

    task = PICK_CATEGORY
