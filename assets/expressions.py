"""Referring expressions from our own grammar, every phrase true of its instance.

Phrases combine a category noun with the colour the camera shows of it (one of its stated
colours, ``appearance.shown_color``, said as people say it: "clear", "gold"), its material
and distinctive parts ("the red mug", "ceramic mug with a handle"). Shape words are left to
the attribute cue, where they tell objects apart. About 15 go to the seen pool and 5 to the
unseen pool, split deterministically by a hash of (uuid, phrase).
"""

from __future__ import annotations

import hashlib
import re

from .appearance import shown_color
from .catalog import Instance

#: Material adjectives; "organic" (fruit, food) has none that a person would say.
MATERIAL_ADJECTIVE = {
    "plastic": "plastic",
    "metal": "metal",
    "wood": "wooden",
    "ceramic": "ceramic",
    "glass": "glass",
    "fabric": "fabric",
    "rubber": "rubber",
    "paper": "paper",
    "silicone": "silicone",
    "leather": "leather",
    "stone": "stone",
    "wicker": "wicker",
}
#: Part names that make a distinctive feature, and how a person says them.
FEATURES = {
    "handle": "handle",
    "cap": "cap",
    "lid": "lid",
    "stem": "stem",
    "leaf": "leaf",
    "label": "label",
    "clip": "clip",
    "tab": "pull tab",
    "sleeve": "sleeve",
    "straw": "straw",
    "pump": "pump",
    "spout": "spout",
    "blade": "blade",
    "bristles": "bristles",
    "power": "power button",
    "connector": "metal connector",
    "cork": "cork",
    "nozzle": "nozzle",
    "trigger": "trigger",
    "wheel": "wheel",
    "screen": "screen",
    "lens": "lens",
}
#: Shape words as a person says them before a noun.
SHAPE_ADJECTIVE = {
    "sphere": "round",
    "hemisphere": "dome-shaped",
    "ellipsoid": "oval",
    "cylinder": "cylindrical",
    "cone": "conical",
    "cube": "cube-shaped",
    "cuboid": "rectangular",
    "disk": "round flat",
    "ring": "ring-shaped",
    "L-shape": "L-shaped",
    "T-shape": "T-shaped",
    "flat": "flat",
    "elongated": "long",
}
SEEN, UNSEEN = 15, 5

#: Colour words as people say them, where the annotation's word is not ("transparent").
COLOR_WORDS = {"transparent": "clear", "golden": "gold"}


def color_word(color: str) -> str:
    """How a person says the annotated colour ``color``."""
    return COLOR_WORDS.get(color, color)


def _base_name(part_name: str) -> str:
    return re.sub(r"(_[a-z]?[+-]?\d+)+$", "", part_name)


def features(inst: Instance) -> list[tuple[str, str]]:
    """(feature word, its colour) for each distinctive part kind of the instance."""
    found: dict[str, str] = {}
    for part in inst.parts:
        word = FEATURES.get(_base_name(part.name))
        if word and word not in found:
            found[word] = part.color
    return sorted(found.items())


def _be(noun: str) -> str:
    """'are' for plural nouns (sticky notes, chopsticks), 'is' otherwise (glass, floss)."""
    return "are" if noun.endswith("s") and not noun.endswith("ss") else "is"


def _with(word: str, color: str | None) -> str:
    article = "" if word.endswith("s") else "an " if word[0] in "aeiou" else "a "
    if color:
        article = "" if word.endswith("s") else "an " if color[0] in "aeiou" else "a "
        return f"with {article}{color} {word}"
    return f"with {article}{word}"


def all_phrases(inst: Instance) -> list[str]:
    """Every phrase the grammar makes for ``inst`` (deduplicated, in a fixed order)."""
    shown = shown_color(inst)
    color = color_word(shown) if shown else None
    colors = " and ".join(color_word(c) for c in inst.colors)
    material = MATERIAL_ADJECTIVE.get(inst.material)
    out: list[str] = []
    for noun in inst.nouns:
        out.append(noun)
        if color:
            out += [f"{color} {noun}", f"{noun} that {_be(noun)} {color}"]
        if len(inst.colors) == 2 and shown:
            out.append(f"{colors} {noun}")
        if material:
            out.append(f"{material} {noun}")
            if color:
                out.append(f"{color} {material} {noun}")
        for word, part_color in features(inst):
            out.append(f"{noun} {_with(word, None)}")
            if color:
                out.append(f"{color} {noun} {_with(word, None)}")
            if part_color != shown:
                out.append(f"{noun} {_with(word, color_word(part_color))}")
    return list(dict.fromkeys(out))


def _score(uuid: str, phrase: str) -> int:
    return int.from_bytes(
        hashlib.blake2b(f"{uuid}/{phrase}".encode(), digest_size=8).digest(), "little"
    )


def expressions(inst: Instance) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(seen, unseen) phrase pools: up to 15 and 5, the unseen ones never in the seen pool."""
    ranked = sorted(all_phrases(inst), key=lambda p: _score(inst.uuid, p))[: SEEN + UNSEEN]
    n_unseen = max(1, round(len(ranked) * UNSEEN / (SEEN + UNSEEN)))
    return tuple(ranked[n_unseen:]), tuple(ranked[:n_unseen])
