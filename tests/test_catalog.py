"""The object library: deterministic generation, exact annotations, disjoint splits."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import instructmove_ms  # noqa: F401
from instructmove_ms.assets import generate_instance, load_snapshot, taxonomy
from instructmove_ms.assets.catalog import instance_uuid, is_held_out_category
from instructmove_ms.assets.generators import GENERATORS
from instructmove_ms.assets.parts import Part
from instructmove_ms.assets.snapshot import DEFAULT_SNAPSHOT, frozen_as
from instructmove_ms.assets.vocab import COLORS, SHAPES
from instructmove_ms.sampler import split_pools


def test_every_taxonomy_category_and_the_receptacles_have_ten_instances():
    catalog = load_snapshot()
    assert set(catalog.categories) == set(taxonomy())
    domains = {taxonomy()[c].domain for c in catalog.categories}
    assert len(domains) == 8  # the paper's 7 domains and our receptacles
    paper = [c for c in catalog.categories if taxonomy()[c].domain != "receptacles"]
    assert len(paper) == 103
    receptacles = [c for c in catalog.categories if GENERATORS[c].container]
    assert len(receptacles) >= 20
    for cat in catalog.categories:
        assert len(catalog.of_category(cat)) >= 10


def test_the_shipped_snapshot_is_up_to_date_with_the_generators():
    """The shipped snapshot is what the generators build at the library revision it was
    frozen at: a generator change shows here (a changed build is a new revision, whose
    instances are new assets frozen by a new snapshot)."""
    catalog = load_snapshot()
    library = frozen_as(DEFAULT_SNAPSHOT).library
    assert {i.category for i in catalog.instances} == set(GENERATORS)
    for inst in catalog.instances:
        assert generate_instance(inst.category, inst.index, library) == inst


def test_generation_is_deterministic_and_uuids_stable():
    a = generate_instance("mug", 3)
    b = generate_instance("mug", 3)
    assert a == b
    assert a.uuid == instance_uuid("mug", 3) == "bd2dd3f7-86bf-5ef4-bd76-2927a67b2c4f"
    assert generate_instance("mug", 4).parts != a.parts


def assert_exact_annotations(inst) -> None:
    """What every instance's annotations promise (snapshots, and revisions before one freezes
    them: tests/test_revisions.py)."""
    lo, hi = inst.bounds
    assert abs(lo[2]) < 1e-9, "objects rest on z = 0"
    assert abs(lo[0] + hi[0]) < 1e-9 and abs(lo[1] + hi[1]) < 1e-9, "centred in xy"
    assert math.isclose(
        inst.mass, sum(p.volume * p.density for p in inst.parts if not p.visual_only)
    )
    assert 0.005 < inst.mass < 2.0
    assert 1 <= len(inst.colors) <= 2 and set(inst.colors) <= set(COLORS)
    assert inst.shape in SHAPES
    assert inst.size == (
        "small" if inst.height < 0.05 else "medium" if inst.height < 0.12 else "large"
    )
    # the named colours are really there: every one is the colour of some part
    assert set(inst.colors) <= {p.color for p in inst.parts}
    if inst.is_graspable and not inst.is_container:  # containers are held by the wall
        assert min(inst.dims[:2]) < 0.08, "fits a parallel gripper from above"


@pytest.mark.parametrize("category", sorted(GENERATORS))
def test_annotations_are_exact(category):
    for inst in load_snapshot().of_category(category):
        assert_exact_annotations(inst)


def test_splits_are_disjoint():
    catalog = load_snapshot()
    seen, _ = split_pools(catalog, "train")
    unseen_inst, _ = split_pools(catalog, "unseen_instance")
    unseen_cat, distractors = split_pools(catalog, "unseen_category")
    ids = [{i.uuid for i in pool} for pool in (seen, unseen_inst, unseen_cat)]
    assert ids[0] and ids[1] and ids[2]
    assert not (ids[0] & ids[1]) and not (ids[0] & ids[2]) and not (ids[1] & ids[2])
    assert all(is_held_out_category(i.category) for i in unseen_cat)
    assert not any(is_held_out_category(i.category) for i in seen + unseen_inst + distractors)


def test_unknown_names_are_reported():
    with pytest.raises(KeyError, match="'teapot'"):
        generate_instance("teapot", 0)
    with pytest.raises(ValueError, match="'validation'"):
        split_pools(load_snapshot(), "validation")


def test_category_nouns_never_name_another_category():
    owner: dict[str, str] = {}
    for cat, gen in GENERATORS.items():
        for noun in gen.synonyms:
            assert noun not in owner, f"{noun!r} names both {owner.get(noun)} and {cat}"
            owner[noun] = cat


def test_every_instance_passes_the_quality_checks():
    from instructmove_ms.assets.quality import check_instances

    failures = [
        (r.category, r.failures)
        for r in check_instances(list(load_snapshot().instances))
        if not r.ok
    ]
    assert not failures


#: How far a flat receptacle's placement layer may rise above its top (metres).
FLAT_LAYER = 0.005


def test_containers_declare_an_interior_inside_their_bounds():
    for inst in load_snapshot().instances:
        if not inst.is_container:
            assert inst.interior is None
            continue
        lo, hi = inst.bounds
        c, half = np.asarray(inst.interior.center), np.asarray(inst.interior.half)
        assert np.all(c[:2] - half >= lo[:2]) and np.all(c[:2] + half <= hi[:2])
        # the floor lies in the object; only a flat receptacle's (a mat's) placement layer
        # rises above it, by at most FLAT_LAYER
        assert lo[2] <= c[2] <= hi[2] + 1e-9 and inst.interior.height > 0
        assert c[2] + inst.interior.height <= hi[2] + FLAT_LAYER


def test_a_cup_that_fits_the_hand_is_also_held_around_its_whole_rim():
    from instructmove_ms.assets.affordances import enveloping_grasps, grasp_affordances

    for inst in load_snapshot().of_category("coffee_cup"):
        around = enveloping_grasps(inst, max_opening=0.1)
        assert around and set(around) <= set(grasp_affordances(inst, max_opening=0.1))
        walls = [p for p in inst.parts if not p.visual_only and p.bounds()[1][2] >= inst.height]
        lo, hi = (
            np.min([p.bounds()[0] for p in walls], 0),
            np.max([p.bounds()[1] for p in walls], 0),
        )
        for g in around:
            axis = int(np.argmax(np.abs(g.closing)))
            assert g.width >= hi[axis] - lo[axis] - 1e-9  # the fingers close outside the rim
            assert np.allclose(g.center[:2], 0.5 * (lo + hi)[:2], atol=0.02)
    assert not enveloping_grasps(load_snapshot().of_category("apple")[0], max_opening=0.1)


def test_a_container_too_wide_for_the_hand_is_held_across_its_rim():
    """A metal pencil holder 8 cm across: each rim grasp closes towards the middle on one
    wall piece (a finger inside, one outside), not along the rim."""
    from instructmove_ms.assets.affordances import enveloping_grasps, rim_grasps

    catalog = load_snapshot()
    holder = catalog["0076e554-bbc0-525b-a396-d030d4a76400"]
    assert holder.category == "pen_holder" and not enveloping_grasps(holder, max_opening=0.08)
    lo, hi = holder.bounds
    middle = 0.5 * (lo + hi)[:2]
    top = max(p.bounds()[1][2] for p in holder.parts if not p.visual_only)  # pens stick out
    rims = rim_grasps(holder, max_opening=0.08)
    assert len(rims) >= 8
    for g in rims:
        inward = middle - np.asarray(g.center[:2])
        assert np.linalg.norm(inward) > 0.03  # at the wall, not the middle
        assert abs(np.dot(g.closing[:2], inward / np.linalg.norm(inward))) > 0.99
        assert g.width < 0.005  # across the wall's thickness
        assert top - 0.021 < g.center[2] < top  # just below the rim
    assert not rim_grasps(catalog.of_category("apple")[0], max_opening=0.08)


def test_sticks_lying_side_by_side_are_held_around_the_pack():
    """String cheese: three sticks 7 mm and 1 mm apart, too close for a finger between; the
    section grasp closes across all three."""
    from instructmove_ms.assets.affordances import enveloping_grasps, section_grasps

    pack = load_snapshot()["57068ba2-eb20-5c88-9dd5-927c82d0e61b"]
    assert pack.category == "cheese_sticks" and not pack.is_container
    assert not enveloping_grasps(pack, max_opening=0.1)
    sticks = [p.bounds() for p in pack.parts if not p.visual_only]
    across = [g for g in section_grasps(pack, max_opening=0.1) if abs(g.closing[0]) > 0.99]
    assert len(across) == 1
    lo = min(b[0][0] for b in sticks)
    hi = max(b[1][0] for b in sticks)
    assert across[0].width == pytest.approx(hi - lo)
    assert lo < across[0].center[0] < hi


def test_a_lid_standing_open_gives_a_bin_its_back_and_scenes_turn_it_from_the_robot():
    catalog = load_snapshot()
    assert [b.back for b in catalog.of_category("waste_bin")] == [math.pi] * 10  # hinge at -x
    assert all(b.back is None for b in catalog.of_category("basket"))  # a handle over the middle
    env = gym.make("PlaceA2B-InstructMove", obs_mode="state", render_backend="none")
    checked = 0
    for seed in range(60):
        spec = env.unwrapped.sample_episode(seed)
        for obj in spec.objects:
            inst = catalog[obj.uuid]
            if inst.category != "waste_bin":
                continue
            x, y, _, qw, _, _, qz = obj.pose
            yaw = 2 * math.atan2(qz, qw)
            (lid,) = [p for p in inst.parts if p.name == "lid"]
            lx, ly = lid.pos[0], lid.pos[1]
            c, s = math.cos(yaw), math.sin(yaw)
            lid_at = np.hypot(x + lx * c - ly * s, y + lx * s + ly * c)
            assert lid_at > np.hypot(x, y) + 0.05, (seed, "the open lid stands behind the bin")
            checked += 1
    env.close()
    assert checked >= 5


def test_part_areas_and_colour_shares():
    box = Part("b", "box", (0.01, 0.02, 0.03), (0, 0, 0), (1, 0, 0, 0), "plastic", "red", (1, 0, 0))
    assert box.area == pytest.approx(2 * (0.02 * 0.04 + 0.04 * 0.06 + 0.02 * 0.06))
    ball = Part("s", "sphere", (0.02,), (0, 0, 0), (1, 0, 0, 0), "plastic", "blue", (0, 0, 1))
    egg = Part("e", "ellipsoid", (0.02,) * 3, (0, 0, 0), (1, 0, 0, 0), "plastic", "blue", (0, 0, 1))
    assert ball.area == pytest.approx(4 * math.pi * 0.02**2)
    assert egg.area == pytest.approx(ball.area, rel=0.01)
    can = Part("c", "cylinder", (0.02, 0.05), (0, 0, 0), (1, 0, 0, 0), "metal", "gray", (0.5,) * 3)
    assert can.area == pytest.approx(2 * math.pi * 0.02 * 0.1 + 2 * math.pi * 0.02**2)
    mug = next(i for i in load_snapshot().of_category("mug"))
    shares = {c: mug.color_share(c) for c in {p.color for p in mug.parts}}
    assert sum(shares.values()) == pytest.approx(1.0) and mug.color_share("none of them") == 0
