"""Referring expressions from our own grammar, every phrase true of its instance.

Phrases put the modifiers before a category noun, as people say them: the colour the camera
shows of it (one of its stated colours, ``appearance.shown_color``, said as people say it:
"clear", "gold") and its material where people name it ("the red mug", "the ceramic mug",
"the metal bottle opener"). A packaged food's colour is its package's and is said as such
("the juice in the green bottle"). Parts ("with a handle") and shape words are left out:
in our families the noun already tells the candidates apart (the verifier's noun rule), and
shape, like a plain material, is said only by the attribute cue, where it does. About 15
go to the seen pool and 5 to the unseen pool, split deterministically by a hash of (uuid,
phrase).
"""

from __future__ import annotations

import hashlib

from .appearance import shown_color
from .catalog import Instance

#: Material adjectives (what the attribute cue says); "organic" (fruit, food) has none.
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
#: Materials people name when they describe an object ("the wooden spoon", "the metal
#: bottle opener"); plastic, paper, rubber and the like go unsaid unless they tell two
#: candidates apart (the attribute cue), and so does any material of a food.
NOTABLE_MATERIALS = frozenset({"metal", "wood", "ceramic", "glass", "stone", "leather", "wicker"})
#: What a packaged food comes in, by (category, material): a colour of it that no part of
#: the food itself has is said of this ("the string cheese in the purple wrapper").
PACKAGES = {
    ("biscuit", "organic"): "packet",
    ("biscuit", "paper"): "packet",
    ("candy", "organic"): "wrapper",
    ("cheese_sticks", "organic"): "wrapper",
    ("chewing_gum", "paper"): "pack",
    ("chocolate", "organic"): "wrapper",
    ("chocolate", "plastic"): "wrapper",
    ("juice", "paper"): "carton",
    ("juice", "plastic"): "bottle",
    ("potato_chips", "paper"): "tube",
    ("potato_chips", "plastic"): "bag",
}
#: Nouns with one of these words name the package itself ("soda can", "pack of gum"): its
#: colour goes before them.
PACKAGE_NOUNS = frozenset({"bottle", "box", "can", "carton", "pack", "packet", "tube", "bag"})
SEEN, UNSEEN = 15, 5

#: Colour words as people say them, where the annotation's word is not ("transparent").
COLOR_WORDS = {"transparent": "clear", "golden": "gold"}


def color_word(color: str) -> str:
    """How a person says the annotated colour ``color``."""
    return COLOR_WORDS.get(color, color)


def said_material(inst: Instance) -> str | None:
    """The material adjective people would say of ``inst`` unprompted, if any."""
    if inst.domain == "food" or inst.material not in NOTABLE_MATERIALS:
        return None
    return MATERIAL_ADJECTIVE[inst.material]


def colored(inst: Instance, noun: str) -> str | None:
    """``noun`` with the colour the camera shows of ``inst`` ("red mug"), said of a packaged
    food's package ("juice in the green bottle", "green pack of gum"); None where ``inst``
    shows no stated colour or its package has no word."""
    shown = shown_color(inst)
    if shown is None:
        return None
    word = color_word(shown)
    own = inst.domain != "food" or any(
        p.material == "organic" and p.color == shown for p in inst.parts
    )
    if own or PACKAGE_NOUNS & set(noun.split()):
        return f"{word} {noun}"
    package = PACKAGES.get((inst.category, inst.material))
    return f"{noun} in the {word} {package}" if package else None


def all_phrases(inst: Instance) -> list[str]:
    """Every phrase the grammar makes for ``inst`` (deduplicated, in a fixed order)."""
    material = said_material(inst)
    both = " and ".join(color_word(c) for c in inst.colors)
    two_colored = len(inst.colors) == 2 and inst.domain != "food" and shown_color(inst)
    out: list[str] = []
    for noun in inst.nouns:
        out.append(noun)
        phrase = colored(inst, noun)
        if phrase:
            out.append(phrase)
        if two_colored:
            out.append(f"{both} {noun}")
        if material and material not in noun.split():  # not "glass wine glass"
            out.append(f"{material} {noun}")
            if phrase and phrase.endswith(f" {noun}"):
                out.append(f"{phrase[: -len(noun)]}{material} {noun}")
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
