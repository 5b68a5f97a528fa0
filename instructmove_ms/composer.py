"""The shared episode engine: a TaskSpec, a snapshot, a split and a seed make an episode.

One function serves every family. The task's ``cue`` says how the instruction singles out
the goal (category, attribute, spatial relation, or object plus destination); roles and
their constraints come from the TaskSpec; the layout honours clearance and relations; the
verifier checks text-indispensability on every episode; conditions re-render the
instruction of the same scene.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .assets.catalog import Catalog, Instance
from .episode import CONDITIONS, EpisodeSpec, ObjectSpec
from .language import attribute_word, noun, preposition, referring_expression, render
from .layout import Placement, Workspace, sample_layout
from .relations import OPPOSITE, PHRASES, holds
from .sampler import EACH_OTHER, Constraint, RoleError, RoleSpec, names_clash, resolve_roles
from .validation import check_choice

SPAWN_LIFT = 0.002  # objects spawn this far above the table and settle
CANDIDATE_ROLES = ("target", "distractor")
DESTINATION_ROLES = ("destination", "distractor_destination")
MAX_ATTEMPTS = 64


class CompositionError(RuntimeError):
    """No episode satisfying the task could be composed for this seed."""


@dataclass(frozen=True)
class Cast:
    """Resolved roles (in scene order) and the cue that singles out the target."""

    members: list[tuple[Instance, str]]
    cue: dict


def _with_constraint(roles: tuple[RoleSpec, ...], role: str, *extra: Constraint):
    return tuple(
        dataclasses.replace(r, constraints=r.constraints + extra) if r.name == role else r
        for r in roles
    )


def _cast(
    task, roles, catalog: Catalog, split: str, seed: int, attempt: int, rng: np.random.Generator
) -> Cast:
    key = f"{seed}:{attempt}"
    if task.cue == "attribute":
        attribute = task.attributes[int(rng.integers(len(task.attributes)))]
        if attribute == "size":
            direction = ("smaller", "larger")[int(rng.integers(2))]
            extra = (Constraint("extent", direction, "target"),)
            cue = {
                "attribute": "size",
                "direction": "larger" if direction == "smaller" else "smaller",
            }
        else:
            extra = (Constraint(attribute, "differ", "target"),)
            cue = {"attribute": attribute}
        # colours pairwise distinct: any candidate can be named for alternative_target
        extra += (
            Constraint("color", "differ", "target"),
            Constraint("color", "differ", EACH_OTHER),
        )
        roles = _with_constraint(roles, "distractor", *extra)
    elif task.cue == "spatial":
        cue = {"relation": task.relations[int(rng.integers(len(task.relations)))]}
    else:
        cue = {"kind": task.cue}
    assigned = resolve_roles(roles, catalog, split, key)
    members = [(inst, role) for role, group in assigned.items() for inst in group]
    if task.cue == "attribute" and cue["attribute"] != "size":
        target = assigned["target"][0]
        if attribute_word(target, cue["attribute"]) is None:
            raise RoleError(f"{target.category} has no word for its {cue['attribute']}")
    return Cast(members, cue)


def _spatial_accept(order: list[int], relation: str) -> Callable:
    """Layout predicate: target where ``relation`` holds, distractor where its opposite does."""
    ref, target, distractor = order[:3]

    def accept(i: int, p: Placement, placed: dict[int, Placement]) -> bool:
        if i == target:
            return holds(relation, (p.x, p.y), (placed[ref].x, placed[ref].y))
        if i == distractor:
            return holds(OPPOSITE[relation], (p.x, p.y), (placed[ref].x, placed[ref].y))
        return True

    return accept


def _instruction(task, rng, cast: Cast, members, goal: int, dest: int, split: str) -> str:
    """Render the instruction that singles out ``goal`` (and ``dest``) under the cast's cue."""
    inst = members[goal][0]
    cue = cast.cue
    if "attribute" in cue:
        word = attribute_word(inst, cue["attribute"], cue.get("direction", ""))
        phrase = f"{word} {noun(rng, inst)}"
    elif "relation" in cue:
        ref = members[cue["reference"]][0]
        options = PHRASES[cue["relation"]]
        relation = options[int(rng.integers(len(options)))]
        phrase = f"{noun(rng, inst)} {relation} the {noun(rng, ref)}"
    else:
        phrase = referring_expression(rng, inst, split)
    slots = {"target": phrase}
    if dest >= 0:
        receptacle = members[dest][0]
        slots.update(
            destination=referring_expression(rng, receptacle, split), prep=preposition(receptacle)
        )
    return render(rng, task.templates, **slots)


def _absent_instance(rng, catalog: Catalog, members) -> Instance:
    """A graspable category that is not in the scene and whose nouns name nothing there."""
    present = {inst.category for inst, _ in members}
    nouns = frozenset(n for inst, _ in members for n in inst.nouns)
    options = [
        catalog.of_category(c)[0]
        for c in catalog.categories
        if c not in present
        and catalog.of_category(c)[0].is_graspable
        and not names_clash(frozenset(catalog.of_category(c)[0].nouns), nouns)
    ]
    return options[int(rng.integers(len(options)))]


def _alternative_cue(cast: Cast, members, candidates, goal: int) -> Cast:
    """A cue that singles out ``goal``: the opposite relation, or the same attribute when the
    goal's value is unique among the candidates, else its colour (pairwise distinct)."""
    cue = cast.cue
    if "relation" in cue:
        return Cast(cast.members, {**cue, "relation": OPPOSITE[cue["relation"]]})
    if "attribute" not in cue:
        return cast
    inst = members[goal][0]
    others = [members[k][0] for k in candidates if k != goal]
    attribute = cue["attribute"]
    if attribute in ("material", "shape"):
        unique = all(getattr(o, attribute) != getattr(inst, attribute) for o in others)
        if unique and attribute_word(inst, attribute):
            return cast
    return Cast(cast.members, {"attribute": "color"})


def _condition(
    task, spec: EpisodeSpec, cast: Cast, members, rng, catalog, split, condition: str
) -> EpisodeSpec:
    """The same scene under ``condition``: only the instruction and the goal change."""
    if condition == "normal":
        return spec
    if condition == "alternative_target":
        goals = [
            (o, d)
            for o in spec.candidates
            for d in (spec.destinations or (-1,))
            if (o, d) != (spec.target, spec.goal_destination)
        ]
        goal, dest = goals[int(rng.integers(len(goals)))]
        cue = _alternative_cue(cast, members, spec.candidates, goal)
        text = _instruction(task, rng, cue, members, goal, dest, split)
        return dataclasses.replace(
            spec,
            instruction=text,
            target=goal,
            goal_destination=dest,
            cue=cue.cue,
            condition=condition,
        )
    cue: dict = {}
    if condition == "empty":
        text = ""
    else:
        word = "object"
        if condition == "absent_object":
            absent = _absent_instance(rng, catalog, members)
            word, cue = noun(rng, absent), {"absent": absent.category}
        slots = {"target": word}
        if spec.goal_destination >= 0:
            receptacle = members[spec.goal_destination][0]
            slots.update(destination=noun(rng, receptacle), prep=preposition(receptacle))
        text = render(rng, task.templates, **slots)
    return dataclasses.replace(
        spec, instruction=text, target=-1, goal_destination=-1, cue=cue, condition=condition
    )


def compose(
    task,
    roles: tuple[RoleSpec, ...],
    catalog: Catalog,
    split: str,
    seed: int,
    robot: str,
    sample_qpos: Callable[[np.random.Generator], np.ndarray],
    condition: str = "normal",
    workspace: Workspace | None = None,
) -> EpisodeSpec:
    """The episode of ``seed`` for ``task``: assets, layout, robot joints, instruction."""
    check_choice("condition", condition, CONDITIONS)
    rng = np.random.default_rng(seed)
    failures = []
    for attempt in range(MAX_ATTEMPTS):
        try:
            cast = _cast(task, roles, catalog, split, seed, attempt, rng)
        except RoleError as exc:
            failures.append(str(exc))
            continue
        members = [cast.members[k] for k in rng.permutation(len(cast.members))]
        index = {
            role: [k for k, (_, r) in enumerate(members) if r == role]
            for role in {r for _, r in members}
        }
        halves = []
        for inst, _ in members:
            lo, hi = inst.bounds
            halves.append((float(hi[0] - lo[0]) / 2, float(hi[1] - lo[1]) / 2))
        order, accept = None, None
        if task.cue == "spatial":
            first = [index["reference"][0], index["target"][0], index["distractor"][0]]
            order = first + [k for k in range(len(members)) if k not in first]
            accept = _spatial_accept(order, cast.cue["relation"])
            cast = Cast(cast.members, {**cast.cue, "reference": first[0]})
        try:
            places = sample_layout(
                rng,
                halves,
                workspace or task.workspace,
                task.clearance,
                restarts=8,
                order=order,
                accept=accept,
            )
        except RuntimeError as exc:
            failures.append(str(exc))
            continue
        objects = tuple(
            ObjectSpec(
                inst.uuid,
                inst.category,
                role,
                (p.x, p.y, SPAWN_LIFT, math.cos(p.yaw / 2), 0.0, 0.0, math.sin(p.yaw / 2)),
            )
            for (inst, role), p in zip(members, places, strict=True)
        )
        candidates = tuple(k for k, (_, r) in enumerate(members) if r in CANDIDATE_ROLES)
        destinations = tuple(k for k, (_, r) in enumerate(members) if r in DESTINATION_ROLES)
        target = index["target"][0]
        dest = index["destination"][0] if "destination" in index else -1
        qpos = sample_qpos(rng)
        spec = EpisodeSpec(
            family=task.family,
            robot=robot,
            snapshot=catalog.name,
            split=split,
            seed=int(seed),
            instruction=_instruction(task, rng, cast, members, target, dest, split),
            objects=objects,
            target=target,
            candidates=candidates,
            robot_qpos=tuple(float(q) for q in qpos),
            destinations=destinations,
            goal_destination=dest,
            cue=cast.cue,
        )
        return _condition(task, spec, cast, members, rng, catalog, split, condition)
    raise CompositionError(
        f"{task.family}: no episode for seed {seed} in split {split!r} after {MAX_ATTEMPTS} "
        f"attempts; last reasons: {failures[-3:]}"
    )
