"""The shared episode engine: a TaskSpec, a snapshot, a split and a seed make an episode.

One function serves every family. The family's ``cue`` (see ``family.Cue``) says how the
instruction singles out the goal: which extra constraints the roles get, how the layout is
arranged, how the goal is phrased and which cue names another candidate; roles and their
constraints come from the TaskSpec; the layout honours clearance and the cue's predicate;
conditions re-render the instruction of the same scene.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .assets.catalog import Catalog, Instance
from .episode import CONDITIONS, EpisodeSpec, ObjectSpec
from .family import Members, TaskSpec
from .language import (
    noun,
    place_slots,
    pronoun,
    referring_expression,
    render,
    with_synonyms,
)
from .layout import Workspace, sample_layout
from .sampler import SAMPLER, SAMPLERS, RoleError, RoleSpec, names_clash, resolve_roles, symmetric
from .splits import UNSEEN_SPLITS
from .validation import check_choice
from .verify import VerificationError

SPAWN_LIFT = 0.002  # objects spawn this far above the table and settle
CANDIDATE_ROLES = ("target", "distractor")
DESTINATION_ROLES = ("destination", "distractor_destination")
#: Each goal role and its rivals' role (sampler 2 casts each pair as one group).
GOAL_ROLES = (CANDIDATE_ROLES, DESTINATION_ROLES)
MAX_ATTEMPTS = 64
#: Scene attempts per seed, by sampler: a symmetric group whose members must all differ in
#: the named attribute (a category with three colours, two materials) is refused more often,
#: and a refused attempt costs a role draw.
SCENE_ATTEMPTS = {1: MAX_ATTEMPTS, 2: 4 * MAX_ATTEMPTS}
#: Certifies a composed spec or raises ``verify.VerificationError``.
Gate = Callable[[EpisodeSpec], EpisodeSpec]


class CompositionError(RuntimeError):
    """No episode satisfying the task could be composed for this seed."""


@dataclass(frozen=True)
class Cast:
    """Resolved roles (in scene order) and the cue that singles out the target."""

    members: Members
    cue: dict


def _cast(
    task: TaskSpec,
    roles: tuple[RoleSpec, ...],
    catalog: Catalog,
    split: str,
    key: str,
    rng: np.random.Generator,
    sampler: int,
) -> Cast:
    """The roles of one composition attempt (``key``) and the cue. Sampler 1 casts the
    target, then rivals set against it; sampler 2 casts each goal's group (``symmetric``)
    and takes the goal uniformly among the members the cue singles out, refusing a group
    of which any member could not be the goal (``Cue.admits``)."""
    cue, roles = task.cue.draw(rng, roles)
    if sampler == 1:
        assigned = resolve_roles(roles, catalog, split, key, sampler)
        task.cue.admits(cue, assigned)
        return Cast([(inst, role) for role, group in assigned.items() for inst in group], cue)
    counts = {r.name: r.count for r in roles}
    size = task.cue.group_size(cue, counts["target"] + counts.get("distractor", 0))
    roles = tuple(
        dataclasses.replace(r, count=size - 1) if r.name == "distractor" else r for r in roles
    )
    for goal, rival in GOAL_ROLES:
        roles = symmetric(roles, goal, rival)
    drawn = resolve_roles(roles, catalog, split, key, sampler)
    named = task.cue.singles_out(cue, drawn["target"])
    if not named:
        raise RoleError(f"no member of the group the cue {cue} can name")
    assigned = {
        **drawn,
        **_chosen(drawn, "target", "distractor", named[int(rng.integers(len(named)))]),
    }
    if "destination" in drawn:
        chosen = int(rng.integers(len(drawn["destination"])))
        assigned.update(_chosen(drawn, "destination", "distractor_destination", chosen))
    for k in range(len(drawn["target"])):  # every member must be able to be the goal
        task.cue.admits(cue, {**assigned, **_chosen(drawn, "target", "distractor", k)})
    return Cast([(inst, role) for role, group in assigned.items() for inst in group], cue)


def _chosen(drawn: dict, goal: str, rival: str, k: int) -> dict[str, list[Instance]]:
    """Member ``k`` of ``drawn[goal]`` as the goal, the rest of the group as its rivals."""
    group = drawn[goal]
    return {goal: [group[k]], rival: group[:k] + group[k + 1 :]}


def _instruction(
    task: TaskSpec,
    rng,
    cue: dict,
    members: Members,
    goal: int,
    dest: int,
    split: str,
    sampler: int,
    templates: tuple[str, ...] | None = None,
) -> str:
    """Render the instruction that singles out ``goal`` (and ``dest``) under ``cue`` as
    ``sampler``'s episodes say it, from ``templates`` (default: the task's for it)."""
    phrase = task.cue.phrase(rng, cue, members, goal, split, sampler)
    slots = {"target": phrase, "it": pronoun(members[goal][0], phrase)}
    if dest >= 0:
        receptacle = members[dest][0]
        slots.update(place_slots(receptacle, referring_expression(rng, receptacle, split)))
    return render(rng, templates or task.templates_of(sampler), **slots)


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


def _aimed(
    task: TaskSpec,
    spec: EpisodeSpec,
    members: Members,
    rng: np.random.Generator,
    goal: tuple[int, int],
) -> EpisodeSpec:
    """The scene of ``spec`` with its instruction naming ``goal`` (object, destination or
    -1), under the cue that singles it out (``Cue.alternative``) unless it is the goal
    already."""
    obj, dest = goal
    cue = spec.cue
    if obj != spec.target:
        cue = task.cue.alternative(spec.cue, members, spec.candidates, obj)
    text = _instruction(task, rng, cue, members, obj, dest, spec.split, spec.sampler)
    return dataclasses.replace(spec, instruction=text, target=obj, goal_destination=dest, cue=cue)


def _goals(spec: EpisodeSpec) -> list[tuple[int, int]]:
    """Every (object, destination) goal of ``spec``'s scene (destination -1 for a pick)."""
    return [(o, d) for o in spec.candidates for d in (spec.destinations or (-1,))]


def _condition(
    task: TaskSpec,
    spec: EpisodeSpec,
    members: Members,
    rng: np.random.Generator,
    catalog: Catalog,
    split: str,
    condition: str,
) -> EpisodeSpec:
    """The same scene under ``condition`` (not normal): only the instruction and the goal
    change."""
    if condition == "alternative_target":
        goals = [g for g in _goals(spec) if g != (spec.target, spec.goal_destination)]
        aimed = _aimed(task, spec, members, rng, goals[int(rng.integers(len(goals)))])
        return dataclasses.replace(aimed, condition=condition)
    cue: dict = {}
    if condition == "empty":
        text = ""
    else:
        word, named = "object", None
        if condition == "absent_object":
            named = _absent_instance(rng, catalog, members)
            word, cue = noun(rng, named), {"absent": named.category}
        slots = {"target": word, "it": pronoun(named, word)}
        if spec.goal_destination >= 0:
            receptacle = members[spec.goal_destination][0]
            slots.update(place_slots(receptacle, noun(rng, receptacle)))
        text = render(rng, task.templates_of(spec.sampler), **slots)
    return dataclasses.replace(
        spec, instruction=text, target=-1, goal_destination=-1, cue=cue, condition=condition
    )


def rephrase(
    task: TaskSpec,
    catalog: Catalog,
    spec: EpisodeSpec,
    rng: np.random.Generator,
    unseen: bool,
    synonyms: bool,
) -> str:
    """``spec``'s goal said again: another template and expression, from the unseen
    expression pool if ``unseen``, with the grammar's verb synonyms if ``synonyms``."""
    members = [(catalog[o.uuid], o.role) for o in spec.objects]
    split = UNSEEN_SPLITS[0] if unseen else spec.split
    templates = task.templates_of(spec.sampler)
    if synonyms:
        templates = with_synonyms(templates)
    goal, dest = spec.target, spec.goal_destination
    return _instruction(task, rng, spec.cue, members, goal, dest, split, spec.sampler, templates)


def _first_passing(draw: Callable[[], EpisodeSpec], gate: Gate) -> tuple[EpisodeSpec | None, list]:
    """The first of up to ``MAX_ATTEMPTS`` specs ``draw`` gives that ``gate`` passes (None if
    none does), and the last problems found."""
    problems: list[str] = []
    for _ in range(MAX_ATTEMPTS):
        try:
            return gate(draw()), problems
        except VerificationError as exc:
            problems = exc.problems
    return None, problems


def variant(
    task: TaskSpec, spec: EpisodeSpec, catalog: Catalog, condition: str, gate: Gate
) -> EpisodeSpec:
    """The certified normal ``spec`` under ``condition``: the scene stays, its instruction
    is drawn again until the gate passes it. The draws come from the seed and the
    condition alone, so a stored episode and the composer's of its seed get one variant."""
    check_choice("condition", condition, CONDITIONS)
    if condition == "normal":
        return spec
    rng = np.random.default_rng([spec.seed, CONDITIONS.index(condition)])
    members = [(catalog[o.uuid], o.role) for o in spec.objects]
    passed, problems = _first_passing(
        lambda: _condition(task, spec, members, rng, catalog, spec.split, condition), gate
    )
    if passed is None:
        raise CompositionError(
            f"{task.family}: no {condition} instruction for the scene of seed {spec.seed} "
            f"passes the verifier after {MAX_ATTEMPTS} draws; last problems: {problems}"
        )
    return passed


def _named(
    task: TaskSpec,
    spec: EpisodeSpec,
    members: Members,
    rng: np.random.Generator,
    goal: tuple[int, int],
    gate: Gate,
) -> tuple[EpisodeSpec | None, list]:
    """``spec``'s scene with an instruction naming ``goal`` that the gate passes, drawn up
    to ``MAX_ATTEMPTS`` times (None if none passes), and the last problems found."""
    return _first_passing(lambda: _aimed(task, spec, members, rng, goal), gate)


def _unnamed_goals(task: TaskSpec, spec: EpisodeSpec, members: Members, gate: Gate) -> list:
    """The goals of ``spec``'s scene other than its own that no instruction names past the
    gate (sampler 2 refuses such a scene, so that no gate picks the target by its role)."""
    rng = np.random.default_rng([spec.seed, len(CONDITIONS)])
    own = (spec.target, spec.goal_destination)
    return [
        goal
        for goal in _goals(spec)
        if goal != own and _named(task, spec, members, rng, goal, gate)[0] is None
    ]


def compose(
    task: TaskSpec,
    roles: tuple[RoleSpec, ...],
    catalog: Catalog,
    split: str,
    seed: int,
    robot: str,
    sample_qpos: Callable[[np.random.Generator], np.ndarray],
    gate: Gate,
    condition: str = "normal",
    workspace: Workspace | None = None,
    sampler: int = SAMPLER,
) -> EpisodeSpec:
    """The episode of ``seed`` for ``task``: assets, layout, robot joints, instruction,
    drawn by ``sampler`` (see ``sampler.SAMPLERS``).

    ``gate`` certifies a spec or raises ``VerificationError`` (see ``verify.certify``):
    a scene whose normal spec it refuses is drawn again (the next attempt). Sampler 2
    draws the goal's instruction until the gate passes it, and refuses the scene unless
    every other goal of it has an instruction the gate passes too. The condition's
    instruction of a passed scene is drawn again until it passes, so every condition of a
    seed shares one scene."""
    check_choice("condition", condition, CONDITIONS)
    check_choice("sampler", sampler, SAMPLERS)
    rng = np.random.default_rng(seed)
    failures = []
    attempts = SCENE_ATTEMPTS[sampler]
    for attempt in range(attempts):
        try:
            cast = _cast(task, roles, catalog, split, f"{seed}:{attempt}", rng, sampler)
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
        order, accept, cue = task.cue.arrange(cast.cue, index, len(members))
        try:
            places = sample_layout(
                rng,
                halves,
                workspace or task.workspace,
                task.clearance,
                restarts=8,
                order=order,
                accept=accept,
                backs=[inst.back for inst, _ in members],
            )
        except RuntimeError as exc:
            failures.append(str(exc))
            continue
        objects = tuple(
            ObjectSpec(inst.uuid, inst.category, role, p.pose(SPAWN_LIFT))
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
            instruction=_instruction(task, rng, cue, members, target, dest, split, sampler),
            objects=objects,
            target=target,
            candidates=candidates,
            robot_qpos=tuple(float(q) for q in qpos),
            destinations=destinations,
            goal_destination=dest,
            cue=cue,
            sampler=sampler,
        )
        if sampler == 1:
            try:
                spec = gate(spec)
            except VerificationError as exc:
                failures.append(str(exc))
                continue
        else:
            passed, problems = _named(task, spec, members, rng, (target, dest), gate)
            if passed is None:
                failures.append(f"no instruction for the goal passes: {problems}")
                continue
            unnamed = _unnamed_goals(task, passed, members, gate)
            if unnamed:
                failures.append(f"goals {unnamed} have no instruction the verifier passes")
                continue
            spec = passed
        return variant(task, spec, catalog, condition, gate)
    raise CompositionError(
        f"{task.family}: no episode for seed {seed} in split {split!r} after {attempts} "
        f"attempts; last reasons: {failures[-3:]}"
    )
