"""Text-indispensability verifier, run on every generated episode.

An episode passes when it has at least two candidate goals, each physically feasible, and
exactly one of them matches the instruction under the catalog annotations (and, for spatial
cues, under the object poses).
"""

from __future__ import annotations

from .assets.affordances import grasp_affordances
from .assets.catalog import Catalog, Instance
from .episode import CONDITIONS, EpisodeSpec
from .language import attribute_word
from .relations import unique_holder
from .sampler import EXTENT_RATIO

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


def _named(inst: Instance, text: str) -> bool:
    return any(f" {n} " in f" {text} " for n in inst.nouns)


def _matches(spec: EpisodeSpec, catalog: Catalog, k: int) -> bool:
    """Whether candidate ``k`` fits the instruction under the spec's cue."""
    inst = catalog[spec.objects[k].uuid]
    cue, text = spec.cue, spec.instruction
    if "relation" in cue:
        ref = spec.objects[cue["reference"]].pose[:2]
        xy = [spec.objects[c].pose[:2] for c in spec.candidates]
        holder = unique_holder(cue["relation"], xy, ref)
        return _named(inst, text) and holder is not None and spec.candidates[holder] == k
    if "attribute" in cue:
        others = [catalog[spec.objects[c].uuid] for c in spec.candidates if c != k]
        if not _named(inst, text):
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
        if not word or f" {word} " not in f" {text} ":
            return False
        if cue["attribute"] == "color":
            return all(inst.colors[0] not in o.colors for o in others)
        return all(getattr(o, cue["attribute"]) != getattr(inst, cue["attribute"]) for o in others)
    return _named(inst, text)


def verify(spec: EpisodeSpec, catalog: Catalog, gripper_opening: float = 0.08) -> list[str]:
    """Problems of ``spec`` (empty when it is text-indispensable and feasible)."""
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
    matching = [k for k in spec.candidates if _matches(spec, catalog, k)]
    if matching != [spec.target]:
        problems.append(
            f"instruction {spec.instruction!r} matches candidates {matching}, "
            f"not exactly the target {spec.target}"
        )
    if spec.destinations:
        fits = [
            d for d in spec.destinations if _named(catalog[spec.objects[d].uuid], spec.instruction)
        ]
        if fits != [spec.goal_destination]:
            problems.append(
                f"instruction names destinations {fits}, not exactly {spec.goal_destination}"
            )
    return problems
