"""Instruction grammar: the pronoun agrees with the noun that names the object."""

from __future__ import annotations

import re

import pytest

from instructmove_ms import heldout
from instructmove_ms.assets import load_snapshot
from instructmove_ms.language import is_plural, pronoun, spaced
from instructmove_ms.splits import EVAL_SPLITS
from instructmove_ms.tasks import TASKS

#: Where the templates put the pronoun of the object to move.
PRONOUN = re.compile(r"\b(?:lift|hold|put|place) (it|them)\b")


@pytest.mark.parametrize(
    ("noun", "plural"),
    [
        ("nail clippers", True),
        ("scissors", True),
        ("potato chips", True),
        ("pair of scissors", False),
        ("box of staples", False),
        ("wine glass", False),
        ("thermos", False),
        ("hand lens", False),
        ("mug", False),
    ],
)
def test_plural_nouns(noun, plural):
    assert is_plural(noun) == plural


def test_the_longest_noun_in_the_phrase_decides():
    catalog = load_snapshot()
    scissors = next(i for i in catalog.instances if "pair of scissors" in i.nouns)
    assert pronoun(scissors, "red scissors") == "them"
    assert pronoun(scissors, "red pair of scissors") == "it"
    assert pronoun(None, "object") == "it"


def test_every_stored_instruction_agrees_with_its_target():
    catalog = load_snapshot()
    seen = {"it": 0, "them": 0}
    for env_id, task in TASKS.items():
        for robot in task.supported_robots:
            for split in EVAL_SPLITS:
                for spec in heldout.load_set(env_id, robot, split):
                    match = PRONOUN.search(spec.instruction)
                    if match is None:
                        continue
                    target = catalog[spec.target_object.uuid]
                    named = [n for n in target.nouns if f" {n} " in spaced(spec.instruction)]
                    expected = "them" if is_plural(max(named, key=len)) else "it"
                    assert match.group(1) == expected, spec.instruction
                    seen[expected] += 1
    assert seen["them"] >= 5 and seen["it"] >= 100, seen
