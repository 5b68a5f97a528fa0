"""Whether a reader's first guess names a category: the accepted names (``names.yaml``)
and the normalisation both sides go through."""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

import yaml

NAMES_FILE = Path(__file__).with_name("names.yaml")
#: Words a guess may start with that say nothing of the kind.
LEADING = ("a ", "an ", "the ", "some ", "one ")
#: What separates a first guess from the alternatives a reader adds.
ALTERNATIVES = re.compile(r"\s*(?:;|/|\(|\?|,| or | maybe | perhaps )\s*")


@cache
def accepted_names() -> dict[str, tuple[str, ...]]:
    """Category -> the names a first guess may use, normalised."""
    data = yaml.safe_load(NAMES_FILE.read_text())
    return {cat: tuple(dict.fromkeys(normalise(n) for n in names)) for cat, names in data.items()}


def singular(word: str) -> str:
    """A plain English singular of ``word`` (enough to compare both sides alike)."""
    if len(word) > 4 and word.endswith("ies"):
        return word[:-3] + "y"
    if word.endswith(("ches", "shes", "sses", "xes")):
        return word[:-2]
    if len(word) > 3 and word.endswith("s") and not word.endswith(("ss", "us", "is")):
        return word[:-1]
    return word


def normalise(text: str) -> str:
    """Lower case, hyphens and underscores as spaces, other punctuation dropped, leading
    articles dropped, every word singular."""
    text = re.sub(r"[-_]", " ", text.lower())
    text = re.sub(r"[^a-z0-9 ]", "", text).strip()
    while text.startswith(LEADING):
        text = text.split(" ", 1)[1] if " " in text else ""
    return " ".join(singular(w) for w in text.split())


def first_guess(answer: str) -> str:
    """The first guess of an answer ("a vase; maybe a cup" -> "a vase")."""
    return ALTERNATIVES.split(answer.strip(), maxsplit=1)[0]


def names_category(answer: str, category: str) -> bool:
    """Whether the first guess of ``answer``, up to a prepositional phrase after its noun,
    is one of ``category``'s accepted names or ends with one as whole words ("red coffee
    mug" names a mug, "egg in an egg cup" an egg)."""
    names = accepted_names()
    if category not in names:
        raise ValueError(f"unknown category {category!r}; names.yaml lists {len(names)}")
    guess = head_phrase(normalise(first_guess(answer)))
    return any(guess == n or guess.endswith(f" {n}") for n in names[category])


def head_phrase(guess: str) -> str:
    """``guess`` without a prepositional phrase after its noun ("egg in egg cup" names an
    egg, "pen holder with pen" a pen holder)."""
    return re.split(r" (?:in|on|with) ", guess, maxsplit=1)[0]
