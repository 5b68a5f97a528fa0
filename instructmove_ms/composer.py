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
from .sampler import RoleError, RoleSpec, names_clash, resolve_roles
from .splits import UNSEEN_SPLITS
from .validation import check_choice
from .verify import VerificationError

SPAWN_LIFT = 0.002  # objects spawn this far above the table and settle
CANDIDATE_ROLES = ("target", "distractor")
DESTINATION_ROLES = ("destination", "distractor_destination")
MAX_ATTEMPTS = 64
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
    seed: int,
    attempt: int,
    rng: np.random.Generator,
) -> Cast:
    cue, roles = task.cue.draw(rng, roles)
    assigned = resolve_roles(roles, catalog, split, f"{seed}:{attempt}")
    task.cue.admits(cue, assigned)
    return Cast([(inst, role) for role, group in assigned.items() for inst in group], cue)


def _instruction(
    task: TaskSpec,
    rng,
    cue: dict,
    members: Members,
    goal: int,
    dest: int,
    split: str,
    templates: tuple[str, ...] | None = None,
) -> str:
    """Render the instruction that singles out ``goal`` (and ``dest``) under ``cue``, from
    ``templates`` (default: the task's)."""
    phrase = task.cue.phrase(rng, cue, members, goal, split)
    slots = {"target": phrase, "it": pronoun(members[goal][0], phrase)}
    if dest >= 0:
        receptacle = members[dest][0]
        slots.update(place_slots(receptacle, referring_expression(rng, receptacle, split)))
    return render(rng, templates or task.templates, **slots)


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
        goals = [
            (o, d)
            for o in spec.candidates
            for d in (spec.destinations or (-1,))
            if (o, d) != (spec.target, spec.goal_destination)
        ]
        goal, dest = goals[int(rng.integers(len(goals)))]
        cue = task.cue.alternative(spec.cue, members, spec.candidates, goal)
        text = _instruction(task, rng, cue, members, goal, dest, split)
        return dataclasses.replace(
            spec, instruction=text, target=goal, goal_destination=dest, cue=cue, condition=condition
        )
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
        text = render(rng, task.templates, **slots)
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
    templates = with_synonyms(task.templates) if synonyms else task.templates
    return _instruction(
        task, rng, spec.cue, members, spec.target, spec.goal_destination, split, templates
    )


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
    problems: list[str] = []
    for _ in range(MAX_ATTEMPTS):
        try:
            return gate(_condition(task, spec, members, rng, catalog, spec.split, condition))
        except VerificationError as exc:
            problems = exc.problems
    raise CompositionError(
        f"{task.family}: no {condition} instruction for the scene of seed {spec.seed} passes "
        f"the verifier after {MAX_ATTEMPTS} draws; last problems: {problems}"
    )


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
) -> EpisodeSpec:
    """The episode of ``seed`` for ``task``: assets, layout, robot joints, instruction.

    ``gate`` certifies a spec or raises ``VerificationError`` (see ``verify.certify``):
    a scene whose normal spec it refuses is drawn again (the next attempt); the
    condition's instruction of a passed scene is drawn again until it passes, so every
    condition of a seed shares one scene."""
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
            instruction=_instruction(task, rng, cue, members, target, dest, split),
            objects=objects,
            target=target,
            candidates=candidates,
            robot_qpos=tuple(float(q) for q in qpos),
            destinations=destinations,
            goal_destination=dest,
            cue=cue,
        )
        try:
            spec = gate(spec)
        except VerificationError as exc:
            failures.append(str(exc))
            continue
        return variant(task, spec, catalog, condition, gate)
    raise CompositionError(
        f"{task.family}: no episode for seed {seed} in split {split!r} after {MAX_ATTEMPTS} "
        f"attempts; last reasons: {failures[-3:]}"
    )
