"""PickSpatial: pick the object that stands in the named relation to a reference object."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from mani_skill.utils.registration import register_env

from instructmove_ms.assets.catalog import Catalog
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.family import Cue, Members, TaskSpec
from instructmove_ms.language import names, noun
from instructmove_ms.layout import Placement
from instructmove_ms.relations import (
    OPPOSITE,
    PHRASES,
    RELATIONS,
    RETIRED_PHRASES,
    bearing,
    holds,
    unique_holder,
)
from instructmove_ms.sampler import Constraint, RoleSpec

from .base import InstructMoveEnv
from .pick_category import PICK_STAGES, RELATION_TEMPLATES, RETIRED_PICK_TEMPLATES


@dataclass(frozen=True)
class RelationCue(Cue):
    """The instruction names the goal by a relation to the reference object ("the apple to
    the left of the bowl"), drawn per episode from ``relations``: the layout puts the target
    where the relation holds and the same-category distractor where its opposite does. The
    cue stores the relation and the reference's index."""

    relations: tuple[str, ...] = RELATIONS

    def draw(self, rng: np.random.Generator, roles: tuple[RoleSpec, ...]):
        return {"relation": self.relations[int(rng.integers(len(self.relations)))]}, roles

    def arrange(self, cue: dict, index: dict[str, list[int]], count: int):
        """Reference, target and distractor placed first, each checked against the
        reference already placed."""
        ref, target, distractor = (index[r][0] for r in ("reference", "target", "distractor"))
        order = [ref, target, distractor]
        order += [k for k in range(count) if k not in order]
        relation = cue["relation"]

        def accept(i: int, p: Placement, placed: dict[int, Placement]) -> bool:
            if i not in (target, distractor):
                return True
            wanted = relation if i == target else OPPOSITE[relation]
            return holds(wanted, (p.x, p.y), (placed[ref].x, placed[ref].y))

        return order, accept, {**cue, "reference": ref}

    def phrase(self, rng, cue: dict, members: Members, goal: int, split: str, sampler: int) -> str:
        inst, ref = members[goal][0], members[cue["reference"]][0]
        options = PHRASES[cue["relation"]]
        if sampler != 1:
            options = tuple(p for p in options if p not in RETIRED_PHRASES)
        relation = options[int(rng.integers(len(options)))]
        return f"{noun(rng, inst)} {relation} the {noun(rng, ref)}"

    def alternative(self, cue: dict, members: Members, candidates: Sequence[int], goal: int):
        """The opposite relation: the distractor holds it by the same margin."""
        return {**cue, "relation": OPPOSITE[cue["relation"]]}

    def matches(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> bool:
        cue = spec.cue
        ref = spec.objects[cue["reference"]].pose[:2]
        xy = [spec.objects[c].pose[:2] for c in spec.candidates]
        holder = unique_holder(cue["relation"], xy, ref)
        named = names(catalog[spec.objects[k].uuid], spec.instruction)
        return named and holder is not None and spec.candidates[holder] == k

    def explain(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> dict:
        """The candidate's bearing from the reference for the cue's relation and whether
        that relation, or its opposite, holds."""
        relation = spec.cue["relation"]
        xy, ref = spec.objects[k].pose[:2], spec.objects[spec.cue["reference"]].pose[:2]
        return {
            "relation": relation,
            **bearing(relation, xy, ref).as_dict(),
            "holds": holds(relation, xy, ref),
            "opposite_holds": holds(OPPOSITE[relation], xy, ref),
        }


PICK_SPATIAL = TaskSpec(
    env_id="PickSpatial-InstructMove",
    family="pick_spatial",
    cue=RelationCue(),
    stages=PICK_STAGES,
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
    templates=RELATION_TEMPLATES,
    retired_templates=RETIRED_PICK_TEMPLATES,
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
    - positions: the target holds the relation and the distractor its opposite: a direction
      relation within 45 deg of its direction, at least 0.06 m along it and within 0.35 m
      of the reference; near < 0.16 m, far > 0.26 m; yaw (an open lid turned away
      from the robot, as in PickCategory), template, robot joints
    - with ``perturbation=``: lighting, table, background, cameras, robot joints, layout and
      paraphrase at levels 0-3 (``instructmove_ms.perturbation``), drawn from the seed

    **Success Conditions:**
    - ``reach``: the TCP came within 0.02 m of the target's box (latched)
    - ``lift``: after reach, the robot grasps the target and raises it 0.03 m (latched);
      ``success`` equals ``lift``
    """

    task = PICK_SPATIAL
