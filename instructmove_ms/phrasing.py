"""Wording a native speaker would not use, found in an instruction.

The checks behind the stored sets' phrasing (docs/envs.md, "Envs": how instructions are
said): each names one pattern a reader flagged in the first pre-release sets (v2). ``faults``
lists those an instruction of a spec shows; the stored sets show none
(``tests/test_phrasing.py``).
"""

from __future__ import annotations

import re

from .assets.catalog import Catalog
from .assets.expressions import MATERIAL_ADJECTIVE, NOTABLE_MATERIALS, color_word, colored
from .assets.vocab import COLORS
from .episode import EpisodeSpec
from .language import named_noun, spaced

#: Verbs people do not use for picking something up.
ODD_VERBS = ("raise",)
QUESTION = re.compile(r"^(can|could|would|will) you\b")
POSTPOSED = re.compile(r"\b(that|which) (is|are) \w+")
PART = re.compile(r"\bwith (a|an|the)\b")
#: Material words said only where the attribute cue needs them.
PLAIN_MATERIALS = frozenset(
    word for name, word in MATERIAL_ADJECTIVE.items() if name not in NOTABLE_MATERIALS
)
COLOR_WORDS = frozenset(color_word(c) for c in COLORS)


def faults(spec: EpisodeSpec, catalog: Catalog) -> list[str]:
    """The patterns ``spec``'s instruction shows: an odd verb, a question without "?", an
    attribute after its noun, a part modifier, a material word said without the material
    cue (a plain material, or any of a food) and a package's colour said of a food (of the
    objects the instruction describes: the goal and its receptacle)."""
    text = spec.instruction
    words = spaced(text)
    found = [f"verb {v!r}" for v in ODD_VERBS if f" {v} " in words]
    if QUESTION.search(text) and not text.endswith("?"):
        found.append("a question without '?'")
    if POSTPOSED.search(text):
        found.append("an attribute after its noun")
    if PART.search(text):
        found.append("a part modifier")
    material_cue = spec.cue.get("attribute") == "material"
    described = [k for k in (spec.target, spec.goal_destination) if k >= 0]
    for inst in (catalog[spec.objects[k].uuid] for k in described):
        noun = named_noun(inst, text)
        if noun is None:
            continue
        said = {w for w in MATERIAL_ADJECTIVE.values() if f" {w} {noun} " in words}
        if not material_cue and (said & PLAIN_MATERIALS or (said and inst.domain == "food")):
            found.append(f"material {sorted(said)} of the {noun}")
        color = next((c for c in COLOR_WORDS if f" {c} {noun} " in words), None)
        phrase = colored(inst, noun)
        if color and inst.domain == "food" and phrase and not phrase.endswith(f" {noun}"):
            found.append(f"the {noun}'s package colour {color!r} said of the {noun}")
    return found
