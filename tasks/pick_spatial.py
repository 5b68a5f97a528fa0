"""PickSpatial: pick the object that stands in the named relation to a reference object."""

from __future__ import annotations

from mani_skill.utils.registration import register_env

from instructmove_ms.relations import RELATIONS
from instructmove_ms.sampler import Constraint, RoleSpec

from .base import InstructMoveEnv
from .pick_category import PICK_TEMPLATES
from .spec import TaskSpec

PICK_SPATIAL = TaskSpec(
    env_id="PickSpatial-InstructMove",
    family="pick_spatial",
    cue="spatial",
    default_robot="franka",
    supported_robots=("franka", "piperx"),
    roles=(
        RoleSpec("target", 1, pool="target"),
        RoleSpec(
            "distractor", 1, pool="any", constraints=(Constraint("category", "match", "target"),)
        ),
        RoleSpec(
            "reference",
            1,
            require=(),
            constraints=(
                Constraint("category", "differ", "target"),
                Constraint("name", "differ", "target"),
            ),
        ),
    ),
    count_limits={"distractor": (1, 1)},
    templates=PICK_TEMPLATES,
    relations=RELATIONS,
)


@register_env(PICK_SPATIAL.env_id, max_episode_steps=PICK_SPATIAL.max_episode_steps)
class PickSpatialEnv(InstructMoveEnv):
    """**Task Description:**
    Pick up the object in the named relation to a reference object ("the apple to the left of
    the bowl"). A target and a distractor of the same category stand on either side of the
    relation: only the relation tells them apart. Relations are in the robot's frame (+x
    forward, +y left): left of, right of, in front of (nearer the robot), behind, near, far
    from.

    **Randomizations:**
    - the category of target and distractor, their instances, the reference object and the
      relation
    - positions: the target holds the relation by a margin (0.06 m sideways; near < 0.16 m,
      far > 0.26 m from the reference) and the distractor holds its opposite by the same
      margin; yaw, template, robot joints

    **Success Conditions:**
    - ``reach``: the TCP came within 0.02 m of the target's box (latched)
    - ``lift``: after reach, the robot grasps the target and raises it 0.03 m (latched);
      ``success`` equals ``lift``
    """

    task = PICK_SPATIAL
