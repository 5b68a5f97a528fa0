"""PickCategory: pick up the object of the named category among cross-category distractors.

Declares what the other pick families share: the pick stage schema (reach, then lift) and
the pick templates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from mani_skill.utils.registration import register_env

from instructmove_ms.assets.catalog import Catalog
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.family import Cue, Members, StageSchema, TaskSpec
from instructmove_ms.language import names, referring_expression
from instructmove_ms.sampler import EACH_OTHER, Constraint, RoleSpec

from .base import InstructMoveEnv

#: S_pick = 0.5 reach + 0.5 lift; success is the lift.
PICK_STAGES = StageSchema(("reach", "lift"), success="lift")

PICK_TEMPLATES = (
    "pick up the {target}",
    "pick the {target} up",
    "grab the {target}",
    "lift the {target}",
    "take the {target}",
    "please pick up the {target}",
    "can you pick up the {target}?",
    "could you grab the {target}?",
    "pick up the {target}, please",
    "take the {target} off the table",
)
#: Pick templates of InstructMove 1.0 that later samplers drop: "lift" reads oddly of small,
#: light things (a comb, floss, a pear).
RETIRED_PICK_TEMPLATES = ("lift the {target}",)
#: The pick templates that cannot read as "move it there" after a relation ("take the mug
#: to the left of the bowl").
RELATION_TEMPLATES = tuple(t for t in PICK_TEMPLATES if not t.startswith("take "))


@dataclass(frozen=True)
class CategoryCue(Cue):
    """The instruction names the goal by a referring expression of its own (category nouns
    with colours, material, parts): the distractors' categories and nouns differ from it.
    ``kind`` is what the episode spec stores as its cue."""

    kind: str = "category"

    def draw(self, rng: np.random.Generator, roles: tuple[RoleSpec, ...]):
        return {"kind": self.kind}, roles

    def phrase(self, rng, cue: dict, members: Members, goal: int, split: str, sampler: int) -> str:
        return referring_expression(rng, members[goal][0], split)

    def matches(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> bool:
        return names(catalog[spec.objects[k].uuid], spec.instruction)


PICK_CATEGORY = TaskSpec(
    env_id="PickCategory-InstructMove",
    family="pick_category",
    cue=CategoryCue(),
    stages=PICK_STAGES,
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
    retired_templates=RETIRED_PICK_TEMPLATES,
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
      between footprints) and yaw (a lid standing open or a caddy's back turned away from
      the robot, within 45 degrees)
    - the instruction's template and the category noun
    - robot initial joints: rest pose plus Gaussian noise (``robot_init_qpos_noise``)
    - with ``perturbation=``: lighting, table, background, cameras, robot joints, layout and
      paraphrase at levels 0-3 (``instructmove_ms.perturbation``), drawn from the seed

    **Success Conditions:**
    - ``reach``: the TCP came within 0.02 m of the target's box (latched)
    - ``lift``: after reach, the robot grasps the target and it is 0.03 m above its initial
      height (latched); ``success`` equals ``lift``
    """

    task = PICK_CATEGORY
