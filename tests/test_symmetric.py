"""The symmetric sampler (2): every candidate comes from the split's partition, the named
attribute leaves no odd one out, and no language-blind rule finds the target; sampler 1
(InstructMove 1.0) still draws what it drew, shortcuts and all."""

from __future__ import annotations

from collections import Counter
from itertools import combinations

import gymnasium as gym
import pytest

from instructmove_ms import audit
from instructmove_ms.assets import load_snapshot
from instructmove_ms.sampler import EXTENT_RATIO, lookalike, split_of
from instructmove_ms.tasks import TASKS


def _specs(env_id: str, split: str, sampler: int, seeds: range) -> list:
    env = gym.make(env_id, split=split, sampler=sampler, obs_mode="state", render_backend="none")
    try:
        return [env.unwrapped.sample_episode(seed) for seed in seeds]
    finally:
        env.close()


@pytest.mark.parametrize("env_id", sorted(TASKS))
@pytest.mark.parametrize("split", ["unseen_instance", "unseen_category"])
def test_every_candidate_comes_from_the_split_partition(env_id, split):
    catalog = load_snapshot()
    for spec in _specs(env_id, split, 2, range(6)):
        assert spec.sampler == 2
        parts = {split_of(catalog[spec.objects[k].uuid], catalog, 2) for k in spec.candidates}
        assert parts == {split}, "the target is never the only unfamiliar candidate"
        receptacles = {
            split_of(catalog[spec.objects[d].uuid], catalog, 2) for d in spec.destinations
        }
        assert receptacles <= {"seen"}, "receptacles are a choice of their own, all seen"


def test_lookalikes_are_a_stick_for_a_stick_or_one_shape_and_colour():
    catalog = load_snapshot()
    marker = next(i for i in catalog.of_category("marker") if "red" in i.colors)
    knives = catalog.of_category("fruit_knife")
    red_knife = next(i for i in knives if "red" in i.colors)
    assert lookalike(marker, red_knife) and lookalike(red_knife, marker)
    blue_knife = next(i for i in knives if not set(i.colors) & set(marker.colors))
    assert not lookalike(marker, blue_knife), "sticks of no shared colour are told apart"
    tomato = catalog.of_category("tomato")[0]
    apples = catalog.of_category("apple")
    assert any(lookalike(tomato, a) for a in apples if a.colors[0] == tomato.colors[0])
    assert not any(lookalike(tomato, a) for a in apples if a.colors[0] != tomato.colors[0])
    assert not lookalike(marker, tomato)


def test_shapes_that_look_alike_name_no_member():
    """A cube-shaped charging head and a rectangular one: the cue names neither (the
    composer refuses the group); a cylinder and a cuboid it names both."""
    catalog = load_snapshot()
    cue = TASKS["PickAttribute-InstructMove"].cue
    heads = catalog.of_category("charging_head")
    pair = [next(i for i in heads if i.shape == s) for s in ("cube", "cuboid")]
    assert cue.singles_out({"attribute": "shape"}, pair) == []
    assert cue.singles_out({"attribute": "color"}, pair) == [0, 1]
    clocks = catalog.of_category("alarm_clock")
    apart = [next(i for i in clocks if i.shape == s) for s in ("cylinder", "cuboid")]
    assert cue.singles_out({"attribute": "shape"}, apart) == [0, 1]


@pytest.mark.parametrize("env_id", ["PickCategory-InstructMove", "PlaceA2B-InstructMove"])
@pytest.mark.parametrize("split", ["seen", "unseen_category"])
def test_no_two_candidates_of_sampler_two_look_alike(env_id, split):
    """Candidates of different categories never pass for one another (a red marker beside a
    red-handled knife); sampler 1 kept such pairs."""
    catalog = load_snapshot()
    for spec in _specs(env_id, split, 2, range(12)):
        for roles in (spec.candidates, spec.destinations):
            group = [catalog[spec.objects[k].uuid] for k in roles]
            assert not [
                (a.category, b.category) for a, b in combinations(group, 2) if lookalike(a, b)
            ]


def test_sampler_one_still_draws_rivals_from_the_seen_partition():
    catalog = load_snapshot()
    for spec in _specs("PickCategory-InstructMove", "unseen_category", 1, range(4)):
        parts = [split_of(catalog[spec.objects[k].uuid], catalog, 1) for k in spec.candidates]
        assert Counter(parts) == {"seen": 5, "unseen_category": 1}
        assert parts[spec.candidates.index(spec.target)] == "unseen_category"
        assert "sampler" not in spec.to_dict(), "a sampler-1 spec reads as 1.0's did"


def _odd_one_out(values: list) -> bool:
    """Whether one value is unique while another is shared."""
    counts = Counter(values)
    return 1 in counts.values() and max(counts.values()) > 1


def test_the_named_attribute_leaves_no_odd_one_out():
    catalog = load_snapshot()
    odd = {1: 0, 2: 0}
    directions = Counter()
    for sampler in (1, 2):
        for spec in _specs("PickAttribute-InstructMove", "train", sampler, range(40)):
            group = [catalog[spec.objects[k].uuid] for k in spec.candidates]
            attribute = spec.cue["attribute"]
            if attribute in ("material", "shape"):
                odd[sampler] += _odd_one_out([getattr(i, attribute) for i in group])
            if sampler == 2 and attribute == "size":
                extents = sorted(max(i.dims) for i in group)
                assert len(group) == 2 and extents[1] >= EXTENT_RATIO * extents[0]
                directions[spec.cue["direction"]] += 1
            if sampler == 2 and attribute != "color":
                assert len(group) == 2, f"{attribute} is told apart between two candidates"
    assert odd[1] > 0, "1.0's sampler left the target the odd one out"
    assert odd[2] == 0


def test_language_blind_rules_find_nothing_in_sampler_two_scenes():
    """The novelty rule sits exactly at chance (every candidate shares the target's
    partition), and no rule finds the target on 40 scenes per family and split far above
    chance (fixed seeds: the same figures on every machine)."""
    fresh = []
    for env_id in TASKS:
        fresh += audit.scenes.fresh_choices(env_id, 40, sampler=2, progress=False)
    cells = audit.judge(fresh, trees=False)[0]
    novelty = [c for c in cells if c.adversary == "novelty" and c.robot == "pooled"]
    assert novelty and all(c.accuracy == pytest.approx(c.chance) for c in novelty)
    pooled = [c for c in cells if c.split == "pooled" and c.robot == "pooled"]
    worst = max(pooled, key=lambda c: c.accuracy - c.chance)
    assert worst.accuracy - worst.chance < 0.15, worst


def _says_retired(text: str) -> bool:
    return "side of" in text or text.startswith(("lift the", "move the"))


def test_sampler_two_drops_the_wording_readers_found_odd():
    """ "on the right side of the chopping board" (lying on it?), "lift the comb", "move the
    pear into the waste bin": sampler 1 still says them, sampler 2 never."""
    said = {1: 0, 2: 0}
    for env_id in TASKS:
        for sampler in (1, 2):
            texts = [s.instruction for s in _specs(env_id, "train", sampler, range(30))]
            said[sampler] += sum(map(_says_retired, texts))
    assert said[1] > 0 and said[2] == 0
