"""Text-indispensability verifier (the test suite runs it on every stored held-out episode).

An episode passes when it has at least two candidate goals, each physically feasible, and
exactly one of them matches the instruction under the family's cue (``Cue.matches``: the
catalog annotations, and the object poses for a relation).
"""

from __future__ import annotations

from .assets.affordances import grasp_affordances
from .assets.catalog import Catalog
from .episode import CONDITIONS, EpisodeSpec
from .family import TaskSpec
from .language import names

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
        if not inst.is_graspable or not grasp_affordances(inst, gripper_opening):
            problems.append(f"candidate {k} ({inst.category}) cannot be grasped")
    for k in spec.destinations:
        inst = catalog[spec.objects[k].uuid]
        if inst.interior is None:
            problems.append(f"destination {k} ({inst.category}) has no interior")
    words = set(spec.instruction.lower().split())
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
        fits = [
            d for d in spec.destinations if names(catalog[spec.objects[d].uuid], spec.instruction)
        ]
        if fits != [spec.goal_destination]:
            problems.append(
                f"instruction names destinations {fits}, not exactly {spec.goal_destination}"
            )
    return problems
