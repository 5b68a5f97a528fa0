"""Instructions: paraphrase templates filled with referring expressions."""

from __future__ import annotations

import re

import numpy as np

from .assets.appearance import shown_color
from .assets.catalog import Instance
from .assets.expressions import (
    MATERIAL_ADJECTIVE,
    SHAPE_NOUNS,
    color_word,
    colored,
    contents,
    count_nouns,
    expressions,
    material_package,
    modified,
    said_nouns,
    shape_nouns,
    shape_word,
)
from .splits import UNSEEN_SPLITS


def referring_expression(rng: np.random.Generator, instance: Instance, split: str) -> str:
    """A phrase for ``instance`` from its seen pool, or its unseen pool on unseen splits."""
    seen, unseen = expressions(instance)
    pool = unseen if split in UNSEEN_SPLITS and unseen else seen
    return pool[int(rng.integers(len(pool)))]


#: Nouns ending in "s" that name one thing.
SINGULAR_S = frozenset({"lens", "thermos"})


def is_plural(noun: str) -> bool:
    """Whether ``noun`` names things in the plural ("nail clippers", "chips"), not one ("a
    pair of scissors", "a wine glass", "a thermos")."""
    words = noun.split()
    last = words[-1]
    return (
        last.endswith("s")
        and not last.endswith("ss")
        and last not in SINGULAR_S
        and ("of" not in words)
    )


def spaced(text: str) -> str:
    """``text`` with its punctuation ("?", ",") turned to spaces and a space at each end, so
    that ``f" {phrase} " in spaced(text)`` finds whole words."""
    return f" {re.sub(r'[?!.,;:]', ' ', text)} "


def says(text: str, word: str) -> bool:
    """Whether ``text`` says ``word`` as a whole word or as the first part of a hyphenated
    one ("pink" in "the pink-wrapped candy")."""
    said = spaced(text)
    return f" {word} " in said or f" {word}-" in said


def pronoun(instance: Instance | None, phrase: str) -> str:
    """ "them" where ``phrase`` names ``instance`` by a plural noun (its longest noun in the
    phrase), else "it"."""
    if " pair of " in spaced(phrase):  # "pair of brown chopsticks": one pair
        return "it"
    named = [n for n in (instance.nouns if instance else ()) if f" {n} " in spaced(phrase)]
    return "them" if named and is_plural(max(named, key=len)) else "it"


#: Longest object phrase (words) a template may put words after ("pick the red mug up",
#: never "pick the tube of toothpaste to the right of the peeler up").
SHORT_PHRASE = 3
#: A template's words after the object phrase that are not a slot ("{target} up").
POSTPOSED = re.compile(r"\{target\} (?!\{|and )\w")


def fits(template: str, target: str) -> bool:
    """Whether ``template`` may hold the object phrase ``target``: words after it (a
    particle, "off the table") only follow a short phrase."""
    return len(target.split()) <= SHORT_PHRASE or not POSTPOSED.search(template)


def render(rng: np.random.Generator, templates: tuple[str, ...], **slots: str) -> str:
    """Fill a randomly chosen template that ``fits`` the target phrase with ``slots`` (a
    template may leave some unused)."""
    usable = tuple(t for t in templates if fits(t, slots.get("target", "")))
    template = usable[int(rng.integers(len(usable)))]
    return template.format(**slots)


def noun(rng: np.random.Generator, instance: Instance, counted: bool = False) -> str:
    """A noun people say for ``instance`` (one that counts it if ``counted``)."""
    nouns = count_nouns(instance) if counted else said_nouns(instance)
    return nouns[int(rng.integers(len(nouns)))]


def attribute_word(instance: Instance, attribute: str, direction: str = "") -> str | None:
    """The word naming ``instance``'s value of ``attribute`` (None if people have none):
    the colour the camera shows of it, its material or shape adjective, or a superlative
    for its extent."""
    if attribute == "color":
        shown = shown_color(instance)
        return color_word(shown) if shown else None
    if attribute == "material":
        return material_package(instance) or MATERIAL_ADJECTIVE.get(instance.material)
    if attribute == "shape":
        return shape_word(instance)
    return {"larger": "biggest", "smaller": "smallest"}[direction]


def attribute_phrase(instance: Instance, attribute: str, noun: str, direction: str = "") -> str:
    """``noun`` with the word of ``instance``'s value of ``attribute`` before it ("red mug",
    "wooden spoon", "biggest apple"); a packaged food's colour is its package's ("juice in
    the green bottle", see ``expressions.colored``)."""
    if attribute == "color":
        phrase = colored(instance, noun)
        if phrase is None:
            raise ValueError(f"{instance.category} shows no colour it has a phrase for")
        return phrase
    package = material_package(instance) if attribute == "material" else None
    if package:  # "the carton of juice", never "the paper juice"
        return f"{package} of {contents(noun)}"
    word = attribute_word(instance, attribute, direction)
    if word in SHAPE_NOUNS:  # "sticky tape dispenser"
        return f"{noun} {word}"
    phrase = modified(word, noun) if word else None
    if phrase is None:
        raise ValueError(f"{instance.category}: no {attribute} word {word!r} for {noun!r}")
    return phrase


def attribute_phrases(instance: Instance, attribute: str, direction: str = "") -> list[str]:
    """Every ``attribute_phrase`` of ``instance`` over the nouns people say for it, leaving
    out those that repeat a word. Size and shape are said of a thing that counts ("the
    smallest tape roll", never "the smallest sticky tape"; ``shape_nouns``)."""
    nouns = {"size": count_nouns, "shape": shape_nouns}.get(attribute, said_nouns)(instance)
    out = []
    for each in nouns:
        try:
            out.append(attribute_phrase(instance, attribute, each, direction))
        except ValueError:
            continue
    if not out:
        raise ValueError(f"{instance.category}: no {attribute} phrase over its nouns {nouns}")
    return out


def names(instance: Instance, text: str) -> bool:
    """Whether ``text`` names ``instance`` by one of its nouns (as whole words)."""
    return named_noun(instance, text) is not None


def named_noun(instance: Instance, text: str) -> str | None:
    """The longest of ``instance``'s nouns that ``text`` says (as whole words), if any."""
    said = [n for n in instance.nouns if f" {n} " in spaced(text)]
    return max(said, key=len) if said else None


def head(noun: str) -> str:
    """The head word of a noun ("bin" of "storage bin"), singular."""
    word = noun.split()[-1]
    return word[:-1] if is_plural(word) else word


#: Flat receptacles (interior shallower than this, m: plates, trays, boards) take "onto".
FLAT_INTERIOR = 0.03


def preposition(receptacle: Instance, short: bool = False) -> str:
    """'onto' for flat receptacles (plates, trays, boards, mats), 'into' for the others
    (bins, boxes, bowls, cups); 'on' and 'in' if ``short`` (after "put")."""
    interior = receptacle.interior
    flat = interior is not None and interior.height < FLAT_INTERIOR
    return ("on" if flat else "in") if short else ("onto" if flat else "into")


def place_slots(receptacle: Instance, phrase: str) -> dict[str, str]:
    """A place template's slots for ``receptacle`` said as ``phrase``."""
    return {
        "destination": phrase,
        "prep": preposition(receptacle),
        "at": preposition(receptacle, short=True),
    }


#: The grammar's synonyms of the templates' verbs (a template's first word, or the verb
#: after "and"), for paraphrases beyond the stored templates.
VERB_SYNONYMS = {
    "pick up": "fetch",
    "pick": "lift",
    "grab": "seize",
    "lift": "hoist",
    "grasp": "clutch",
    "take": "get",
    "get": "bring",
    "put": "drop",
    "place": "position",
    "move": "transfer",
}


def with_synonyms(templates: tuple[str, ...]) -> tuple[str, ...]:
    """``templates`` with each verb replaced by its synonym (object slots untouched)."""

    def swap(template: str) -> str:
        words = template.split(" ")
        out = []
        k = 0
        while k < len(words):
            pair = " ".join(words[k : k + 2])
            starts = k == 0 or words[k - 1] in ("and", "you", "please")
            if starts and pair in VERB_SYNONYMS:
                out.append(VERB_SYNONYMS[pair])
                k += 2
            elif starts and words[k] in VERB_SYNONYMS:
                out.append(VERB_SYNONYMS[words[k]])
                k += 1
            else:
                out.append(words[k])
                k += 1
        return " ".join(out)

    return tuple(swap(t) for t in templates)
