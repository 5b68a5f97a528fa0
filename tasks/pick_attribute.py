"""PickAttribute: pick the object of a category that has the named attribute."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import combinations

import numpy as np
from mani_skill.utils.registration import register_env

from instructmove_ms.assets.appearance import (
    DISTINCT,
    delta_e,
    lab_of,
    look_differs,
    shown_color,
)
from instructmove_ms.assets.catalog import Catalog, Instance
from instructmove_ms.assets.expressions import colored
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.family import Cue, Members, TaskSpec
from instructmove_ms.language import attribute_phrases, attribute_word, names, says
from instructmove_ms.sampler import (
    EACH_OTHER,
    EXTENT_RATIO,
    Constraint,
    RoleError,
    RoleSpec,
    with_constraints,
)

from .base import InstructMoveEnv
from .pick_category import PICK_STAGES, PICK_TEMPLATES, RETIRED_PICK_TEMPLATES


def _sets_apart(attribute: str, inst: Instance, others: Sequence[Instance]) -> bool:
    """Whether ``inst``'s material (as it renders) or shape differs from every one of
    ``others``'."""
    if attribute == "material":
        return all(look_differs(inst.material, o.material) for o in others)
    return all(getattr(o, attribute) != getattr(inst, attribute) for o in others)


#: Shapes the symmetric sampler does not tell apart: a cube-shaped body and a rectangular one
#: differ in proportions that the whole object does not show (a charging head's prongs and
#: plug face: readers took the "square" one for its rectangular twin).
SHAPES_ALIKE = (frozenset({"cube", "cuboid"}),)

#: The most of another candidate's surface that may show the colour a candidate is named
#: by ("the clear bottle" beside bottles whose shoulders are clear too is no name).
SHARED_COLOR = 0.2


def _colors_tell_apart(candidates: Sequence[Instance]) -> bool:
    """Whether every candidate shows a colour, the rendered colours of every two are
    ``DISTINCT`` apart and no candidate's colour covers more than ``SHARED_COLOR`` of
    another's surface."""
    return (
        all(shown_color(c) for c in candidates)
        and all(delta_e(lab_of(a), lab_of(b)) >= DISTINCT for a, b in combinations(candidates, 2))
        and all(
            b.color_share(shown_color(a)) <= SHARED_COLOR
            for a in candidates
            for b in candidates
            if b is not a
        )
    )


@dataclass(frozen=True)
class AttributeCue(Cue):
    """The instruction names the goal's value of one attribute ("the red mug", "the biggest
    apple"), drawn per episode from ``attributes``; every distractor differs from the target
    in it (sizes by ``EXTENT_RATIO`` in the largest dimension, materials in how they
    render) and the candidates' rendered colours are pairwise ``DISTINCT``, none covering
    more than ``SHARED_COLOR`` of another's surface, so that any candidate can be named by
    the colour the camera shows of it."""

    attributes: tuple[str, ...] = ("color", "size", "shape", "material")
    #: Attributes the symmetric sampler tells apart between two candidates: the library
    #: seldom holds three instances of a category whose materials, shapes or sizes all
    #: differ, and a third candidate sharing a value would leave the target the odd one out.
    paired: tuple[str, ...] = ("size", "shape", "material")

    def group_size(self, cue: dict, count: int) -> int:
        return min(count, 2) if cue["attribute"] in self.paired else count

    def singles_out(self, cue: dict, group: Sequence[Instance]) -> list[int]:
        """Every member for colour, material and shape (their values all differ), none for
        shapes that look alike (``SHAPES_ALIKE``); for size the member the drawn direction
        names (the larger or the smaller of two)."""
        if cue["attribute"] == "shape" and frozenset(i.shape for i in group) in SHAPES_ALIKE:
            return []
        if cue["attribute"] != "size":
            return list(range(len(group)))
        pick = max if cue["direction"] == "larger" else min
        return [pick(range(len(group)), key=lambda k: max(group[k].dims))]

    def draw(self, rng: np.random.Generator, roles: tuple[RoleSpec, ...]):
        attribute = self.attributes[int(rng.integers(len(self.attributes)))]
        cue = {"attribute": attribute}
        if attribute == "size":  # the direction the target lies in
            cue["direction"] = ("larger", "smaller")[int(rng.integers(2))]
        return cue, with_constraints(roles, "distractor", *self.rivals(cue))

    def rivals(self, cue: dict) -> tuple[Constraint, ...]:
        """Distractors differ from the target in the named attribute (smaller than a larger
        target, and vice versa) and in colour from it and from each other."""
        if cue["attribute"] == "size":
            relation = "smaller" if cue["direction"] == "larger" else "larger"
            named = Constraint("extent", relation, "target")
        else:
            named = Constraint(cue["attribute"], "differ", "target")
        return (
            named,
            Constraint("color", "differ", "target"),
            Constraint("color", "differ", EACH_OTHER),
        )

    def admits(self, cue: dict, assigned: dict[str, list[Instance]]) -> None:
        """Refuse a cast where the named difference would not show in the image: a target
        without a word for its attribute, candidates whose rendered colours are not
        ``DISTINCT`` (any of them may be named by colour) or a material that renders like
        a distractor's."""
        target = assigned["target"][0]
        attribute = cue["attribute"]
        if attribute != "size" and attribute_word(target, attribute) is None:
            raise RoleError(f"{target.category} has no word for its {attribute}")
        if attribute == "color" and any(colored(target, n) is None for n in target.nouns):
            raise RoleError(f"{target.category}: a colour of a package without a word")
        candidates = assigned["target"] + assigned["distractor"]
        if not _colors_tell_apart(candidates):
            raise RoleError(f"{target.category}: candidates whose colours do not show apart")
        if attribute == "material" and not _sets_apart("material", target, assigned["distractor"]):
            raise RoleError(f"{target.category}: materials that render alike")

    def phrase(self, rng, cue: dict, members: Members, goal: int, split: str, sampler: int) -> str:
        options = attribute_phrases(members[goal][0], cue["attribute"], cue.get("direction", ""))
        return options[int(rng.integers(len(options)))]

    def alternative(self, cue: dict, members: Members, candidates: Sequence[int], goal: int):
        """The same attribute where it sets the goal apart from every other candidate (a
        material as it renders, as ``matches`` reads it) and has a word, else its colour
        (pairwise distinct)."""
        inst = members[goal][0]
        others = [members[k][0] for k in candidates if k != goal]
        attribute = cue["attribute"]
        if (
            attribute in ("material", "shape")
            and _sets_apart(attribute, inst, others)
            and attribute_word(inst, attribute)
        ):
            return cue
        return {"attribute": "color"}

    def matches(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> bool:
        inst = catalog[spec.objects[k].uuid]
        others = [catalog[spec.objects[c].uuid] for c in spec.candidates if c != k]
        cue, text = spec.cue, spec.instruction
        if not names(inst, text):
            return False
        if cue["attribute"] == "size":
            bigger = cue["direction"] == "larger"
            return all(
                (max(inst.dims) >= EXTENT_RATIO * max(o.dims))
                if bigger
                else (EXTENT_RATIO * max(inst.dims) <= max(o.dims))
                for o in others
            )
        word = attribute_word(inst, cue["attribute"])
        if not word or not says(text, word):
            return False
        if cue["attribute"] == "color":
            return _colors_tell_apart([inst, *others]) and all(
                shown_color(inst) not in o.colors for o in others
            )
        return _sets_apart(cue["attribute"], inst, others)

    def explain(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> dict:
        """The candidate's value of the cue's attribute: its colours, material, shape or
        largest extent (m)."""
        inst = catalog[spec.objects[k].uuid]
        attribute = spec.cue["attribute"]
        values = {
            "color": list(inst.colors),
            "material": inst.material,
            "shape": inst.shape,
            "size": round(max(inst.dims), 4),
        }
        return {"attribute": attribute, "value": values[attribute]}


PICK_ATTRIBUTE = TaskSpec(
    env_id="PickAttribute-InstructMove",
    family="pick_attribute",
    cue=AttributeCue(),
    stages=PICK_STAGES,
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
    retired_templates=RETIRED_PICK_TEMPLATES,
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
      apart); sizes differ by at least 1.3x in the largest dimension; rendered colours are
      pairwise at least ``appearance.DISTINCT`` apart, none covering more than a fifth of
      another candidate's surface, so that every candidate can be named by the colour the
      camera shows; a material is named only against materials that render differently
    - positions (reference workspace, 0.05 m between footprints), yaw (an open lid turned away
      from the robot, as in PickCategory), template, robot joints
    - with ``perturbation=``: lighting, table, background, cameras, robot joints, layout and
      paraphrase at levels 0-3 (``instructmove_ms.perturbation``), drawn from the seed

    **Success Conditions:**
    - ``reach``: the TCP came within 0.02 m of the target's box (latched)
    - ``lift``: after reach, the robot grasps the target and raises it 0.03 m (latched);
      ``success`` equals ``lift``
    """

    task = PICK_ATTRIBUTE
