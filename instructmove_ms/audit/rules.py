"""Rule adversaries: fixed language-blind rules that pick among a choice's options.

Each rule maps the options to the set it picks (ties share the pick: an option of a set of
``n`` scores ``1/n`` when it is the answer). A rule that cannot tell the options apart picks
them all, which is chance. Rules see ``Choice.options`` only.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from .choices import CATEGORICAL, Option

#: A rule: the options -> the indices it picks (never empty).
Rule = Callable[[Sequence[Option]], list[int]]

#: Figures whose largest and smallest option each make a rule.
EXTREMES = ("height", "extent", "footprint", "volume", "mass", "density")
#: Layout figures: (figure, the end that makes the rule's name).
LAYOUT = (
    ("robot_distance", "nearest", "farthest"),
    ("centrality", "most_peripheral", "most_central"),
    ("nearest_gap", "most_crowded", "most_isolated"),
    ("side", "most_middle", "most_sideways"),
)
#: Visibility figures, most visible first (stored episodes carry them).
VISIBILITY = tuple(f"pixels_{c}" for c in range(2))


def _all(options: Sequence[Option]) -> list[int]:
    return list(range(len(options)))


def odd_one_out(attribute: str) -> Rule:
    """The options whose ``attribute`` no other option shares (sets: no value in common)."""

    def rule(options: Sequence[Option]) -> list[int]:
        values = [o.values[attribute] for o in options]
        odd = [
            k
            for k, v in enumerate(values)
            if all(not (v & w) for j, w in enumerate(values) if j != k)
        ]
        return odd if 0 < len(odd) < len(options) else _all(options)

    return rule


def extreme(figure: str, largest: bool) -> Rule:
    """The options with the largest (smallest) ``figure``; all where an option lacks it."""

    def rule(options: Sequence[Option]) -> list[int]:
        if any(figure not in o.numbers for o in options):
            return _all(options)
        values = [o.numbers[figure] for o in options]
        best = max(values) if largest else min(values)
        return [k for k, v in enumerate(values) if v == best]

    return rule


def novelty(options: Sequence[Option]) -> list[int]:
    """The options outside the training partition (a policy has never seen them)."""
    novel = [k for k, o in enumerate(options) if o.novel]
    return novel if 0 < len(novel) < len(options) else _all(options)


def familiarity(options: Sequence[Option]) -> list[int]:
    """The options inside the training partition (the elimination's mirror)."""
    known = [k for k, o in enumerate(options) if not o.novel]
    return known if 0 < len(known) < len(options) else _all(options)


def rules() -> dict[str, Rule]:
    """Every rule adversary, by name."""
    out: dict[str, Rule] = {f"odd {a}": odd_one_out(a) for a in CATEGORICAL}
    for figure in EXTREMES:
        out[f"largest {figure}"] = extreme(figure, True)
        out[f"smallest {figure}"] = extreme(figure, False)
    for figure, low, high in LAYOUT:
        out[low.replace("_", " ")] = extreme(figure, False)
        out[high.replace("_", " ")] = extreme(figure, True)
    for c, figure in enumerate(VISIBILITY):
        out[f"most visible camera {c + 1}"] = extreme(figure, True)
    out["novelty"] = novelty
    out["familiarity"] = familiarity
    return out


def score(picked: list[int], answer: int) -> float:
    """The expected accuracy of picking uniformly among ``picked``."""
    return 1.0 / len(picked) if answer in picked else 0.0
