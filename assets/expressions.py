"""Referring expressions from our own grammar, every phrase true of its instance.

Phrases name the object by a noun people say for its category (``nouns.yaml``, the most
natural first: a choice among the category's nouns) and put the modifiers before it, in
English order (colour, then material): the colour the camera shows of it (one of its stated
colours, ``appearance.shown_color``, said as people say it: "clear", "gold") and its
material where people name it ("the red mug", "the ceramic mug", "the metal bottle
opener"). A food's own colour goes unsaid (it restates the kind: "yellow lemon"), unless
the attribute cue needs it; a packaged food's colour is its package's and is said as such
("the green bottle of juice", "the purple-wrapped candy"). The colour of a pair is said of
what comes in it ("pair of brown chopsticks"); no modifier repeats a word of its noun
("white white-out tape", "wooden rubber stamp"). Parts ("with a handle") and shape words
are left out: in our families the noun already tells the candidates apart (the verifier's
noun rule), and shape, like a plain material, is said only by the attribute cue, where it
does. About 15 go to the seen pool and 5 to the unseen pool, split deterministically by a
hash of (uuid, phrase).
"""

from __future__ import annotations

import hashlib
from functools import cache
from pathlib import Path

import yaml

from .appearance import shown_color
from .catalog import Instance

NOUNS_FILE = Path(__file__).with_name("nouns.yaml")

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
#: Material names and adjectives.
MATERIAL_WORDS = frozenset(MATERIAL_ADJECTIVE) | frozenset(MATERIAL_ADJECTIVE.values())
#: Shape words as a person says them before a noun ("the round pen holder", never "the
#: cylindrical pen holder").
SHAPE_ADJECTIVE = {
    "sphere": "round",
    "hemisphere": "dome-shaped",
    "ellipsoid": "oval",
    "cylinder": "round",
    "cone": "conical",
    "cube": "cube-shaped",
    "cuboid": "rectangular",
    "disk": "round",
    "ring": "ring-shaped",
    "L-shape": "L-shaped",
    "T-shape": "T-shaped",
    "flat": "flat",
    "elongated": "long",
}
#: What tells a category's shapes apart to a person, where the plain shape word does not
#: ("the sticky tape dispenser" beside a roll, never "the long tape roll"; "the thin
#: chocolate bar" beside a thick one); None where people have no word for the shape (a
#: roll of tape is just that, never "the ring-shaped tape roll" nor "the loose one").
CATEGORY_SHAPES: dict[str, dict[str, str | None]] = {
    "scotch_tape": {"ring": None, "elongated": "dispenser"},
    "chocolate": {"cuboid": "thick", "flat": "thin"},
    "cutting_board": {"flat": "rectangular"},
    "candy": {"disk": "flat"},
    "charging_head": {"cube": "square"},
}
#: Shape words that are nouns, said after a noun of stuff as one compound: what is picked
#: up is the dispenser, not the roll in it ("the sticky tape dispenser").
SHAPE_NOUNS = frozenset({"dispenser"})
#: Materials people name when they describe an object ("the wooden spoon", "the metal
#: bottle opener"); plastic, paper, rubber and the like go unsaid unless they tell two
#: candidates apart (the attribute cue), and so does any material of a food.
NOTABLE_MATERIALS = frozenset({"metal", "wood", "ceramic", "glass", "stone", "leather", "wicker"})
#: What a packaged food comes in, by (category, material): a colour of it that no part of
#: the food itself has is said of this ("the green carton of juice", "the purple-wrapped
#: string cheese").
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

#: Nouns of stuff rather than things, with the measure that counts them ("the smallest
#: loaf of bread", never "the smallest bread"); a packaged food is counted by its package.
MEASURES = {
    "bread": "loaf",
    "candy": "piece",
    "chocolate": "bar",
    "chewing gum": "pack",
    "gum": "pack",
    "dental floss": "box",
    "floss": "box",
    "garlic": "head",
    "juice": "bottle",
    "milk": "carton",
    "scotch tape": "roll",
    "sticky tape": "roll",
    "toothpaste": "tube",
    "shampoo": "bottle",
    "lotion": "bottle",
    "face wash": "tube",
    "hand sanitizer": "bottle",
    "chips": "bag",
    "potato chips": "bag",
    "string cheese": "stick",
}


@cache
def _said() -> dict[str, tuple[str, ...]]:
    return {c: tuple(n) for c, n in yaml.safe_load(NOUNS_FILE.read_text()).items()}


def said_nouns(inst: Instance) -> tuple[str, ...]:
    """The nouns instructions say for ``inst``, the most natural first: its category's
    choice (``nouns.yaml``) among its own nouns, or all of them for a category the file
    does not list (an imported asset)."""
    chosen = tuple(n for n in _said().get(inst.category, ()) if n in inst.nouns)
    return chosen or inst.nouns


def count_nouns(inst: Instance) -> tuple[str, ...]:
    """``said_nouns`` that count the object, a noun of stuff with its measure ("loaf of
    bread", "carton of juice" for juice in a carton)."""
    package = PACKAGES.get((inst.category, inst.material))
    out = []
    for noun in said_nouns(inst):
        measure = MEASURES.get(noun)
        if measure is None:
            out.append(noun)
        elif package != "wrapper":
            out.append(f"{package or measure} of {noun}")
    return tuple(dict.fromkeys(out)) or said_nouns(inst)


def shape_nouns(inst: Instance) -> tuple[str, ...]:
    """The nouns a shape phrase of ``inst`` is said with: ``count_nouns`` ("thin chocolate
    bar"), or the nouns of stuff its shape noun compounds with ("sticky tape dispenser")."""
    if shape_word(inst) in SHAPE_NOUNS:
        return tuple(n for n in said_nouns(inst) if n in MEASURES)
    return count_nouns(inst)


def _words(text: str) -> set[str]:
    return set(text.replace("-", " ").split())


#: Colours that already say "metal" ("silver metal bucket" says it twice).
METAL_COLORS = frozenset({"silver", "golden"})
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


def shape_word(inst: Instance) -> str | None:
    """How a person says ``inst``'s shape to tell it from others of its category (None if
    people have no word for it)."""
    said = CATEGORY_SHAPES.get(inst.category, {})
    return said[inst.shape] if inst.shape in said else SHAPE_ADJECTIVE.get(inst.shape)


def modified(words: str, noun: str) -> str | None:
    """``noun`` with ``words`` (adjectives) before it, put on what a pair holds ("pair of
    brown chopsticks"); None where ``words`` repeat a word of ``noun`` or put a material
    before a noun that names one ("wooden rubber stamp")."""
    said, named = _words(words), _words(noun)
    if said & named or (said & MATERIAL_WORDS and named & MATERIAL_WORDS):
        return None
    if noun.startswith("pair of "):
        return f"pair of {words} {noun[len('pair of ') :]}"
    return f"{words} {noun}"


def colored(inst: Instance, noun: str) -> str | None:
    """``noun`` with the colour the camera shows of ``inst`` ("red mug"), said of a packaged
    food's package ("green bottle of juice", "green pack of gum", "purple-wrapped candy");
    None where ``inst`` shows no stated colour or its package has no word."""
    shown = shown_color(inst)
    if shown is None:
        return None
    word = color_word(shown)
    own = inst.domain != "food" or any(
        p.material == "organic" and p.color == shown for p in inst.parts
    )
    if own or PACKAGE_NOUNS & set(noun.split()):
        return modified(word, noun)
    package = PACKAGES.get((inst.category, inst.material))
    if package is None:
        return None
    if package == "wrapper":
        return f"{word}-wrapped {noun}"
    return f"{word} {package} of {contents(noun)}"


def contents(noun: str) -> str:
    """``noun`` as what a package holds: stuff as it is, things in the plural ("pack of
    cookies")."""
    return noun if noun in MEASURES or noun.endswith("s") else f"{noun}s"


def material_package(inst: Instance) -> str | None:
    """The package that says ``inst``'s material ("carton" of juice for paper, "bottle" for
    plastic; "packet" of cookies beside a bare cookie), where each packaging material of its
    category comes in a package of its own."""
    if inst.material == "organic":  # the food itself: no package says it
        return None
    own = {m: p for (c, m), p in PACKAGES.items() if c == inst.category and m != "organic"}
    package = own.get(inst.material)
    if package is None or package == "wrapper" or list(own.values()).count(package) > 1:
        return None
    return package


def own_color_unsaid(inst: Instance) -> bool:
    """Whether the colour ``inst`` shows is the food's own, which goes unsaid unprompted."""
    shown = shown_color(inst)
    return inst.domain == "food" and any(
        p.material == "organic" and p.color == shown for p in inst.parts
    )


def all_phrases(inst: Instance) -> list[str]:
    """Every phrase the grammar makes for ``inst`` (deduplicated, in a fixed order)."""
    material = said_material(inst)
    both = " and ".join(color_word(c) for c in inst.colors)
    two_colored = (
        len(inst.colors) == 2
        and inst.domain != "food"
        and shown_color(inst)
        and "transparent" not in inst.colors  # "red and clear" is not how people say it
    )
    out: list[str] = []
    for noun in said_nouns(inst):
        out.append(noun)
        phrase = None if own_color_unsaid(inst) else colored(inst, noun)
        options = [
            phrase,
            modified(both, noun) if two_colored else None,
            modified(material, noun) if material else None,
        ]
        metallic = material == "metal" and shown_color(inst) in METAL_COLORS
        if (
            material
            and phrase
            and phrase.endswith(f" {noun}")
            and " of " not in noun
            and not metallic
        ):
            options.append(modified(f"{phrase[: -len(noun) - 1]} {material}", noun))
        out += [p for p in options if p]
    return list(dict.fromkeys(out))


def _score(uuid: str, phrase: str) -> int:
    return int.from_bytes(
        hashlib.blake2b(f"{uuid}/{phrase}".encode(), digest_size=8).digest(), "little"
    )


def expressions(inst: Instance) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(seen, unseen) phrase pools: up to 15 and 5, the unseen ones never in the seen pool
    (where there are two phrases or more)."""
    ranked = sorted(all_phrases(inst), key=lambda p: _score(inst.uuid, p))[: SEEN + UNSEEN]
    if len(ranked) == 1:  # one way to say it: both pools say it
        return tuple(ranked), tuple(ranked)
    n_unseen = max(1, round(len(ranked) * UNSEEN / (SEEN + UNSEEN)))
    return tuple(ranked[n_unseen:]), tuple(ranked[:n_unseen])
