"""Role sampling: constraints hold, draws are seeded, and stable when the library grows."""

from __future__ import annotations

from collections import Counter

import pytest

from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets.catalog import Catalog, generate_instance
from instructmove_ms.sampler import (
    EACH_OTHER,
    HELD_OUT_PER_CATEGORY,
    SAMPLERS,
    Constraint,
    RoleError,
    RoleSpec,
    resolve_roles,
    split_of,
    split_pools,
    symmetric,
)
from instructmove_ms.tasks import PICK_CATEGORY

ROLES = (
    RoleSpec("target", 1, pool="target"),
    RoleSpec(
        "distractor",
        2,
        constraints=(
            Constraint("category", "match", "target"),
            Constraint("color", "differ", "target"),
        ),
    ),
)


def test_constraints_hold_and_draws_are_seeded():
    catalog = load_snapshot()
    solved = 0
    for seed in range(20):
        try:
            got = resolve_roles(ROLES, catalog, "train", seed)
        except RoleError:  # the drawn target's category may lack two other colours
            continue
        solved += 1
        target, distractors = got["target"][0], got["distractor"]
        assert len({d.uuid for d in distractors} | {target.uuid}) == 3
        for d in distractors:
            assert d.category == target.category
            assert not set(d.colors) & set(target.colors)
        assert got == resolve_roles(ROLES, catalog, "train", seed)
    assert solved >= 10
    draws = {resolve_roles(ROLES[:1], catalog, "train", s)["target"][0].uuid for s in range(20)}
    assert len(draws) > 10


def test_adding_assets_does_not_change_existing_assignments():
    catalog = load_snapshot()
    roles = PICK_CATEGORY.roles  # the shipped family's declared roles
    before = {s: resolve_roles(roles, catalog, "unseen_category", s) for s in range(30)}
    # the same snapshot listed in another order, with more instances of its categories
    extra = [generate_instance(c, 10 + k) for c in catalog.categories[:4] for k in range(2)]
    grown = Catalog(catalog.name, list(reversed(catalog.instances)) + extra)
    changed = 0
    for seed, want in before.items():
        got = resolve_roles(roles, grown, "unseen_category", seed)
        changed += got != want
    # rendezvous hashing: order never matters; a draw changes only when a new instance wins
    assert changed <= 30 * 0.5
    reordered = Catalog(catalog.name, list(reversed(catalog.instances)))
    assert all(resolve_roles(roles, reordered, "unseen_category", s) == before[s] for s in before)


@pytest.mark.parametrize("sampler", SAMPLERS)
def test_splits_partition_the_snapshot(sampler):
    catalog = load_snapshot()
    parts = {"seen": set(), "unseen_instance": set(), "unseen_category": set()}
    for inst in catalog.instances:
        parts[split_of(inst, catalog, sampler)].add(inst.uuid)
    assert sum(map(len, parts.values())) == len(catalog)
    seen_categories = {catalog[u].category for u in parts["seen"]}
    assert not seen_categories & {catalog[u].category for u in parts["unseen_category"]}
    targets, seen = split_pools(catalog, "unseen_instance", sampler)
    assert {i.uuid for i in targets} == parts["unseen_instance"]
    assert {i.uuid for i in seen} == parts["seen"]
    held = Counter(catalog[u].category for u in parts["unseen_instance"])
    if sampler == 1:  # about one instance in five, by a hash of its own
        held_out = {i.uuid for i in catalog.instances if i.held_out}
        assert {i.uuid for i in targets} == held_out - parts["unseen_category"]
    else:  # the same number of every seen category
        assert set(held.values()) == {HELD_OUT_PER_CATEGORY}
        assert set(held) == seen_categories


def test_symmetric_folds_rivals_into_the_goal_group():
    roles = PICK_CATEGORY.roles
    (group,) = symmetric(roles, "target", "distractor")
    assert (group.name, group.count, group.pool) == ("target", 6, "target")
    assert set(group.constraints) == {
        Constraint("category", "differ", EACH_OTHER),
        Constraint("name", "differ", EACH_OTHER),
        Constraint("look", "differ", EACH_OTHER),  # members of other categories
    }
    sized = (
        roles[0],
        RoleSpec("distractor", 1, constraints=(Constraint("extent", "smaller", "target"),)),
    )
    assert symmetric(sized, "target", "distractor")[0].constraints == (
        Constraint("extent", "differ", EACH_OTHER),
    )
    assert symmetric(roles, "destination", "distractor_destination") == roles
    uneven = (roles[0], RoleSpec("distractor", 1, require=()))
    with pytest.raises(ValueError, match="ask different things"):
        symmetric(uneven, "target", "distractor")


def test_unsatisfiable_role_names_the_constraint_and_pool():
    roles = (
        RoleSpec("target", 1, pool="target"),
        RoleSpec("distractor", 40, constraints=(Constraint("category", "match", "target"),)),
    )
    with pytest.raises(RoleError, match=r"'category must match target'.*pool of \d+"):
        resolve_roles(roles, load_snapshot(), "train", 0)
