"""Text-indispensability verifier: the gate every composed episode passes before an env
uses it (sampled, stored, perturbed or counterfactual), and the certificate it leaves.

An episode passes when it has at least two candidate goals, each physically feasible,
exactly one of them matches the instruction under the family's cue (``Cue.matches``: the
catalog annotations, and the object poses for a relation), and no noun of the instruction
could name another object of the scene (a shared head word, "the bin" for a storage bin
and a waste bin, unless the cue tells same-category candidates apart). The certificate
(``EpisodeSpec.certificate``) says which candidate matched and why: each candidate's value
under the cue (attribute; relation bearing with offset, angle and distance) and which
destination the instruction names; ``visibility`` adds what the cameras see of each
(``tasks.visibility``).
"""

from __future__ import annotations

import dataclasses

from .assets.affordances import graspable
from .assets.catalog import Catalog
from .episode import CONDITIONS, EpisodeSpec
from .family import TaskSpec
from .language import head, named_noun, spaced

#: Bumped whenever a rule of the verifier changes; certificates record it.
VERIFIER_VERSION = 3

#: Internal names that must never reach the instruction (whole words).
FORBIDDEN_WORDS = frozenset(
    {
        "distractor",
        "distractors",
        "target",
        "uuid",
        "seed",
        "episode",
        "normal",
        "generic",
        "alternative",
        "absent",
        "condition",
    }
)


class VerificationError(ValueError):
    """An episode is not text-indispensable or not feasible; ``problems`` says why."""

    def __init__(self, spec: EpisodeSpec, problems: list[str]) -> None:
        self.problems = problems
        super().__init__(
            f"{spec.family} episode of seed {spec.seed} ({spec.split}, {spec.condition}) "
            f"fails the verifier: {'; '.join(problems)}"
        )


def _heads(catalog: Catalog, spec: EpisodeSpec, k: int) -> set[str]:
    return {head(n) for n in catalog[spec.objects[k].uuid].nouns}


def ambiguous_nouns(spec: EpisodeSpec, catalog: Catalog) -> list[str]:
    """Nouns of the instruction whose head word also names another object of the scene
    (same-category candidates excepted: the cue separates them)."""
    problems = []
    reference = spec.cue.get("reference")
    named = [spec.target, spec.goal_destination] + ([reference] if reference is not None else [])
    for k in named:
        if k is None or k < 0:
            continue
        inst = catalog[spec.objects[k].uuid]
        said = named_noun(inst, spec.instruction)
        if said is None:
            continue
        for j, obj in enumerate(spec.objects):
            if j == k or (
                j in spec.candidates and k in spec.candidates and obj.category == inst.category
            ):
                continue
            if head(said) in _heads(catalog, spec, j):
                problems.append(f"{said!r} could also name object {j} ({obj.category})")
    return problems


def verify(
    spec: EpisodeSpec, catalog: Catalog, task: TaskSpec, gripper_opening: float
) -> list[str]:
    """Problems of ``spec``, an episode of ``task`` for a robot whose fingers open
    ``gripper_opening`` metres (its agent's ``gripper.max_width``); empty when it is
    text-indispensable and feasible."""
    problems = []
    if spec.condition not in CONDITIONS:
        problems.append(f"unknown condition {spec.condition!r}")
    if spec.num_goals < 2:
        problems.append(f"only {spec.num_goals} candidate goal(s)")
    for k in spec.candidates:
        inst = catalog[spec.objects[k].uuid]
        if not inst.is_graspable or not graspable(inst, gripper_opening):
            problems.append(f"candidate {k} ({inst.category}) cannot be grasped")
    for k in spec.destinations:
        inst = catalog[spec.objects[k].uuid]
        if inst.interior is None:
            problems.append(f"destination {k} ({inst.category}) has no interior")
    words = set(spaced(spec.instruction.lower()).split())
    leaked = sorted(words & FORBIDDEN_WORDS)
    if leaked or any(ch.isdigit() or ch == "_" for ch in spec.instruction):
        problems.append(f"instruction {spec.instruction!r} leaks internal names {leaked}")
    if spec.target < 0:
        if spec.condition in ("normal", "alternative_target"):
            problems.append("no target under a condition that needs one")
        return problems
    matching = [k for k in spec.candidates if task.cue.matches(spec, catalog, k)]
    if matching != [spec.target]:
        problems.append(
            f"instruction {spec.instruction!r} matches candidates {matching}, "
            f"not exactly the target {spec.target}"
        )
    if spec.destinations:
        fits = [d for d in spec.destinations if _named(catalog, spec, d)]
        if fits != [spec.goal_destination]:
            problems.append(
                f"instruction names destinations {fits}, not exactly {spec.goal_destination}"
            )
    return problems + ambiguous_nouns(spec, catalog)


def _named(catalog: Catalog, spec: EpisodeSpec, k: int) -> str | None:
    return named_noun(catalog[spec.objects[k].uuid], spec.instruction)


def certificate(spec: EpisodeSpec, catalog: Catalog, task: TaskSpec) -> dict:
    """Why ``spec``'s instruction picks its goal: every candidate with its category, the
    noun that names it, whether it matches and what the cue reads of it; every destination
    with the noun that names it; the verifier's version. A certificate stored with the spec
    keeps its ``visibility``."""
    cert = {
        "verifier": VERIFIER_VERSION,
        "goal": spec.target,
        "candidates": [
            {
                "index": k,
                "category": spec.objects[k].category,
                "named": _named(catalog, spec, k),
                "matches": spec.target >= 0 and task.cue.matches(spec, catalog, k),
                **(task.cue.explain(spec, catalog, k) if spec.target >= 0 else {}),
            }
            for k in spec.candidates
        ],
    }
    if spec.destinations:
        cert["goal_destination"] = spec.goal_destination
        cert["destinations"] = [
            {"index": d, "category": spec.objects[d].category, "named": _named(catalog, spec, d)}
            for d in spec.destinations
        ]
    if "visibility" in spec.certificate:
        cert["visibility"] = spec.certificate["visibility"]
    return cert


def certify(
    spec: EpisodeSpec, catalog: Catalog, task: TaskSpec, gripper_opening: float
) -> EpisodeSpec:
    """``spec`` with its certificate; ``VerificationError`` if the verifier finds problems."""
    problems = verify(spec, catalog, task, gripper_opening)
    if problems:
        raise VerificationError(spec, problems)
    return dataclasses.replace(spec, certificate=certificate(spec, catalog, task))
