"""Generator revisions: every category has one build, which carries the library revision
it came in (part of its instances' identity); a later revision adds a build on top, and every
snapshot keeps regenerating the assets it was frozen with."""

from __future__ import annotations

import json

import numpy as np
import pytest

from conftest import with_a_tag
from instructmove_ms.assets import snapshot as snap
from instructmove_ms.assets.catalog import generate_instance, instance_uuid
from instructmove_ms.assets.design import Design, Traits
from instructmove_ms.assets.generators import (
    GENERATORS,
    LIBRARY,
    REVISIONS,
    generator,
    generator_at,
    revised,
)
from instructmove_ms.assets.textures import PRINTED_WORDS, image

#: The builds of revision 2 (that revision 3 did not rebuild), and a part (name, colour)
#: that shows each.
REVISED_2 = {
    "mouse": ("seam_across", None),
    "alarm_clock": ("screen", "black"),
    "glue_gun": ("cord", "black"),
}
#: What revision 2 gave categories that revision 3 rebuilt, and kept: a part that shows it.
KEPT_FROM_2 = {
    "chewing_gum": ("stick_0", "silver"),  # sticks pulled out of the sleeve
    "juice": ("neck", "transparent"),  # a clear neck over the juice
    "mini_sculpture": ("nose", None),  # a bust
}
#: What revision 3 rebuilt (categories fresh readers misnamed), and a part that shows it:
#: bathroom, household and kitchen goods ...
REVISED_3_BATH: dict[str, tuple[str, str | None]] = {
    "toothpaste": ("cap_flip", None),  # a flat tube printed TOOTHPASTE, a wide flip cap
    "facial_cleanser": ("label", None),  # a flat tube on its cap, printed FACE WASH
    "hand_sanitizer": ("bubble_0", "white"),  # clear gel with bubbles, HAND SANITIZER
    "lotion": ("collar_ring", None),  # a pump bottle printed BODY/HAND LOTION
    "dental_floss": ("lid_print", None),  # a rounded case, FLOSS on its lid
    "soap_dish": ("ridge_0", None),  # a shallow tray with drain ridges
    "spice_jar": ("sifter", None),  # a shaker top over a jar labelled with its spice
    "sponge": ("pores_x0", None),  # porous foam under a scourer
    "beverage_bottle": ("neck_ring", None),  # a soft-drink bottle labelled COLA / SODA
    "shampoo_bottle": ("front_label", None),  # a flat bottle printed SHAMPOO, a flip cap
    "mouthwash_cup": ("tooth_print_front", None),  # a panelled tumbler: tooth, toothbrushes
}
#: ... groceries and stationery ...
REVISED_3_DESK: dict[str, tuple[str, str | None]] = {
    "cheese_sticks": ("pack_band", None),  # a band printed STRING CHEESE, one stick peeled
    "garlic": ("loose_clove", None),  # a loose clove beside the head
    "hair_clip": ("claw_lip_0_0", None),  # a claw clip: long curled teeth, spring on top
    "nail_clipper": ("thumb_pad", None),  # the lever arching back to a thumb pad
    "egg": ("cup_foot", None),  # standing in an egg cup
    "pliers": ("rivet_pin", "gray"),  # combination pliers: flat nose, big pivot, pipe grip
    "bread": ("slice_0", None),  # a sliced loaf showing its crumb (or a slashed baguette)
    "potato": ("knob_0", None),
    "peach": ("cheek_0", None),  # the cleft
    "candy": ("pleat_0_0", None),  # the bow-tie twist ends
    "glue_stick": ("glue", None),  # open, the glue twisted up
    "sticky_notes": ("curled_end", None),  # a yellow pad, the top note curling up
    "staples_box": ("strip_0", None),  # a strip of staples beside the carton
    "pen_holder": ("pen_0", None),  # pens standing in it
    "eraser": ("card_sleeve", None),
    "correction_tape": ("roll_core", None),  # a flat dispenser, its tape roll and tip
    # reprints (``generators.reprints``): the same parts, the label printing what it is
    "canned_coke": ("body", None),  # COLA over the ribbon
    "chewing_gum": ("label", None),  # GUM beside the mint leaf
    "chocolate": ("brand", None),  # CHOCOLATE
    "juice": ("label", None),  # JUICE beside the fruit (and on the carton's band)
    "milk_carton": ("print", None),  # MILK beside the drop
    "potato_chips": ("label", None),  # CHIPS beside the chip
    "coaster": ("print_edge_u0", None),  # slate/ceramic/bamboo/felt tiles in a rack or caddy
    "tomato": ("lobe_0", None),  # red lobes round a dimple, a green star calyx
    "biscuit": ("cookie_dome", None),  # a chocolate-chip cookie (or COOKIES pack)
    "lemon": ("nipple", None),  # yellow, longer than wide, tapering to a pointed nipple
    "apple": ("lobe_0_0", None),  # wider than tall, the stalk sunk in a dimple
    "banana": ("blossom_tip", "black"),  # five-sided, curved, a stalk and a dark stub
}
#: ... electronics, bedroom, kitchenware, living-room, receptacles and tools.
REVISED_3_ROOM: dict[str, tuple[str, str | None]] = {
    "remote_holder": ("remote_0", None),  # TV remotes standing in its pockets
    "glasses_case": ("lens_0", "transparent"),  # open, round-rimmed glasses inside
    "presenter_clicker": ("lanyard_0", None),  # short and slim, 3 keys, laser tip, lanyard
    "ac_remote": ("snowflake_0", "blue"),  # the display shows a temperature and a snowflake
    "earbud_case": ("bud_0", None),  # open, the earbuds seated inside
    "mini_sculpture": ("gown", None),  # a bust or a classical draped statue of a woman
    "lunch_box": ("umeboshi", "red"),  # a bento: rice with a red plum, side dishes
    "placemat": ("place_setting", None),  # rounded vinyl or cloth, a place setting printed
    "wire_cutters": ("bevel_0_0", "white"),  # a short black pointed head, bright bevels
    "peeler": ("slot", "black"),  # a Y peeler: a wide slotted blade across the yoke
    "thermos": ("handle_grip", None),  # a flask: shoulder, screw-on cup or flip lid, handle
    "hex_key": ("clip", None),  # a set of L keys in a clip
    "candle_holder": ("stub", None),  # a candlestick or chamberstick, a short unlit stub
    "basket": ("handle_0_0", None),  # woven, a twisted rim and a loop handle at each end
    "waste_bin": ("pedal", None),  # a pedal bin, its lid open, a bag over the rim
    "storage_box": ("rib_x0_0", None),  # an open moulded plastic bin, ribs and a thick lip
    "phone_stand": ("hinge_top", None),  # an empty folding stand: back plate, lip, hinges
    "stamp": ("die", "red"),  # a knob-handled wooden stamp on a red rubber die
    "vase": ("belly", None),  # a belly under a narrower neck and a flared lip
    "jewelry_box": ("ring_roll_0", None),  # ring rolls holding rings, a pearl necklace
}
#: The reprinted categories of revision 3: their part shows it by printing words (a
#: pattern of ``textures.PRINTED_WORDS``) where the same part drew a wordmark before.
REPRINTED_3 = {"canned_coke", "chewing_gum", "chocolate", "juice", "milk_carton", "potato_chips"}
#: The most parts a revised build may have.
MAX_PARTS = 60
#: Revision -> category -> the part that shows the revision.
REVISED = {2: REVISED_2, 3: {**REVISED_3_BATH, **REVISED_3_DESK, **REVISED_3_ROOM}}
#: (category, revision) of every build past revision 1.
BUILDS = sorted((c, r) for r, cats in REVISED.items() for c in cats)
#: What ``generator_at`` says of a revision older than a category's build.
NO_BUILD = (
    "{category} has no build at library revision {asked}: its {which} came in revision "
    "{came}; snapshots before revision 3 left the package at 1.0, git checkout ee264ad for them"
)


def _shows(inst, part: tuple[str, str | None], printed: bool = False) -> bool:
    name, color = part
    if printed:
        return any(
            p.name == name and p.texture is not None and p.texture.pattern in PRINTED_WORDS
            for p in inst.parts
        )
    return any(p.name == name and color in (None, p.color) for p in inst.parts)


def _no_build(category: str, asked: int, came: int, which: str = "build") -> str:
    return NO_BUILD.format(category=category, asked=asked, came=came, which=which)


def test_every_category_has_one_build_and_the_revised_ones_are_listed():
    assert all(list(builds.values()) == [GENERATORS[c]] for c, builds in REVISIONS.items())
    assert set(REVISIONS) == set(GENERATORS)
    registered = {(c, g.revision) for c, g in GENERATORS.items() if g.revision > 1}
    assert registered == set(BUILDS)
    assert LIBRARY == 3


def test_the_shipped_snapshot_names_each_instance_by_its_builds_revision():
    """``recognisable`` (revision 3) was frozen before the older builds left: each uuid it
    names is the one the surviving build's revision gives (read from the file, nothing
    rebuilt)."""
    assert snap.frozen_as("recognisable") == snap.Frozen(textures=True, library=3)
    entries = json.loads(snap.snapshot_path("recognisable").read_text())["instances"]
    assert {e["category"] for e in entries} == set(GENERATORS)
    for e in entries:
        revision = GENERATORS[e["category"]].revision
        assert e["uuid"] == instance_uuid(e["category"], e["index"], revision), e


@pytest.mark.parametrize(("category", "revision"), BUILDS)
def test_a_revised_build_is_its_own_asset_and_shows_its_revision(category, revision):
    gen = generator_at(category, LIBRARY)
    assert gen is GENERATORS[category] and gen.revision == revision
    for later in range(revision, LIBRARY + 1):
        assert generator_at(category, later) is gen
    for earlier in range(1, revision):
        with pytest.raises(ValueError) as err:
            generator_at(category, earlier)
        assert str(err.value) == _no_build(category, earlier, revision)
    instances = [generate_instance(category, i, revision) for i in range(10)]
    for i, inst in enumerate(instances):
        assert inst.uuid == instance_uuid(category, i, revision) != instance_uuid(category, i)
        assert inst == generate_instance(category, i)  # the newest library builds the same
    # the defining part is there (in the variants that have it)
    printed = revision == 3 and category in REPRINTED_3
    assert any(_shows(inst, REVISED[revision][category], printed) for inst in instances)
    if category in KEPT_FROM_2:
        assert any(_shows(inst, KEPT_FROM_2[category]) for inst in instances)


def test_an_unrevised_category_is_the_same_asset_at_every_revision():
    assert GENERATORS["mug"].revision == 1
    mugs = [generate_instance("mug", 3, library) for library in range(1, LIBRARY + 1)]
    assert mugs[0] == mugs[1] == mugs[2] and mugs[0].uuid == instance_uuid("mug", 3)


# --- the mechanism, on a copy of the registry -------------------------------------------


def test_a_revised_build_replaces_the_newest_from_its_revision_on(revision_4):
    real = GENERATORS["mouse"]
    new = revision_4.GENERATORS["mouse"]
    assert new is revision_4.REVISIONS["mouse"][4] and new.revision == 4
    assert new.build is not real.build
    assert (new.synonyms, new.size, new.graspable, new.container) == (
        real.synonyms,
        real.size,
        real.graspable,
        real.container,
    )
    assert generator_at("mouse", 4) is new
    assert generator_at("mouse", 3) is generator_at("mouse", 2) is real
    with pytest.raises(ValueError) as err:
        generator_at("mouse", 1)
    assert str(err.value) == _no_build("mouse", 1, 2, which="first build")
    assert generator_at("mug", 4) is GENERATORS["mug"]  # the other categories unchanged
    for i in range(3):
        old, rebuilt = generate_instance("mouse", i, 3), generate_instance("mouse", i, 4)
        assert old.uuid == instance_uuid("mouse", i, 2)
        assert rebuilt.uuid == instance_uuid("mouse", i, 4) != old.uuid
        # its own draws (seeded by its uuid), and the part the revision added
        assert any(p.name == "tag" for p in rebuilt.parts)
        assert not any(p.name == "tag" for p in old.parts)
        assert generate_instance("mug", i, 4) == generate_instance("mug", i, 3)


def test_an_older_snapshot_keeps_its_build_after_a_revision(revision_4, tmp_path):
    """A snapshot frozen at revision 3 still rebuilds its mice (and is not stale); one
    frozen at revision 4 holds the new ones; the mugs are shared. A revision-3 file naming
    a mouse as revision 4 built it is stale."""
    for name, library in (("old", 3), ("new", 4)):
        entries = snap.build_entries(["mouse", "mug"], 2, snap.Frozen(True, library))
        snap.write_snapshot(tmp_path / f"{name}.json", name, entries, snap.Frozen(True, library))
    old, new = snap.load_snapshot("old"), snap.load_snapshot("new")
    for catalog, revision in ((old, 2), (new, 4)):
        uuids = [i.uuid for i in catalog.of_category("mouse")]
        assert uuids == [instance_uuid("mouse", i, revision) for i in (0, 1)]
    assert old.of_category("mouse") == [generate_instance("mouse", i, 3) for i in (0, 1)]
    assert old.of_category("mug") == new.of_category("mug")
    moved = {i.uuid for i in old.instances} - {i.uuid for i in new.instances}
    assert {old[u].category for u in moved} == {"mouse"} and len(moved) == 2
    stale = [snap.entry_of(generate_instance("mouse", 0, 4))]
    stale[0]["uuid"] = instance_uuid("mouse", 0, 2)
    snap.write_snapshot(tmp_path / "bad.json", "bad", stale, snap.Frozen(True, 3))
    with pytest.raises(ValueError, match="'bad' is stale: mouse #0"):
        snap.load_snapshot("bad")


def test_a_snapshot_file_from_before_revisions_reads_as_revision_1(tmp_path, monkeypatch):
    """A file without a library revision is at revision 1: a category built then rebuilds
    alike; one whose build came later says so; a changed instance is stale."""
    monkeypatch.setattr(snap, "user_snapshot_dir", lambda: tmp_path)
    snap.load_snapshot.cache_clear()
    try:
        entry = snap.entry_of(generate_instance("mug", 1, 1))
        snap.write_snapshot(tmp_path / "mine.json", "mine", [entry], snap.Frozen(True, 1))
        assert "library" not in json.loads((tmp_path / "mine.json").read_text())
        assert snap.frozen_as("mine") == snap.Frozen(True, 1)
        assert snap.load_snapshot("mine").instances[0] == generate_instance("mug", 1, 1)
        juice = {**entry, "category": "juice", "uuid": instance_uuid("juice", 1)}
        snap.write_snapshot(tmp_path / "gone.json", "gone", [juice], snap.Frozen(True, 1))
        with pytest.raises(ValueError) as err:
            snap.load_snapshot("gone")
        assert str(err.value) == _no_build("juice", 1, 3)
        bad = {
            **snap.entry_of(generate_instance("juice", 1)),
            "content_hash": snap.entry_of(generate_instance("juice", 2)).get("content_hash"),
        }
        snap.write_snapshot(tmp_path / "bad.json", "bad", [bad], snap.Frozen(True, 3))
        with pytest.raises(ValueError, match="'bad' is stale: juice #1"):
            snap.load_snapshot("bad")
    finally:
        snap.load_snapshot.cache_clear()


def test_bad_revisions_are_refused(own_registry):
    with pytest.raises(ValueError, match="revision 4 is not in 1..3"):
        generator_at("mouse", 4)
    with pytest.raises(ValueError, match="revision 0 is not in 1..3"):
        generator_at("mouse", 0)
    with pytest.raises(ValueError, match="numbered 2..3, got 1"):
        revised("mouse", 1)
    with pytest.raises(ValueError, match="two builds at revision 2"):
        revised("mouse", 2)(lambda d: None)
    with pytest.raises(ValueError, match="cannot revise 'teapot'"):
        revised("teapot", 2)(lambda d: None)
    with pytest.raises(ValueError, match="cannot revise 'toothpaste' at revision 2: its newest"):
        revised("toothpaste", 2)(lambda d: None)
    with pytest.raises(ValueError, match="two generators"):
        generator("mug", size=(0.08, 0.13))(lambda d: None)
    with pytest.raises(ValueError, match="a build's revision is in 1..3, got 4"):
        generator("teapot", size=(0.1, 0.2), revision=4)
    with pytest.raises(KeyError):
        generator_at("teapot", 3)
    assert own_registry.REVISIONS == REVISIONS  # nothing registered


def test_a_category_can_come_in_a_later_revision_and_be_revised(own_registry):
    """``generator(..., revision=2)`` registers a first build of revision 2: the revisions
    before it have none; a revision 3 goes on top of it."""

    def first(d: Design) -> Traits:
        d.box("pot", (0.05, 0.05, 0.05), (0.0, 0.0, 0.05), "ceramic", "white")
        return Traits(("white",), "ceramic", "cube")

    generator("teapot", size=(0.1, 0.2), synonyms=("teapot",), revision=2)(first)
    built = own_registry.GENERATORS["teapot"]
    assert built.revision == 2 and own_registry.REVISIONS["teapot"] == {2: built}
    assert generator_at("teapot", 2) is generator_at("teapot", 3) is built
    with pytest.raises(ValueError) as err:
        generator_at("teapot", 1)
    assert str(err.value) == _no_build("teapot", 1, 2)
    revised("teapot", 3)(with_a_tag(first))
    assert generator_at("teapot", 2) is built
    assert generator_at("teapot", 3).revision == 3 and generator_at("teapot", 3).build is not first
    with pytest.raises(ValueError) as err:
        generator_at("teapot", 1)
    assert str(err.value) == _no_build("teapot", 1, 2, which="first build")
    assert "teapot" not in GENERATORS  # the real registry untouched


def test_the_digital_clock_shows_its_time_lit_on_a_dark_screen():
    """The screen's image is mostly the screen's own black, with the segments lit in the
    ink: the lit share sits between a tenth and a half of the image."""
    clock = next(
        inst
        for inst in (generate_instance("alarm_clock", i) for i in range(20))
        if any(p.name == "screen" for p in inst.parts)
    )
    screen = next(p for p in clock.parts if p.name == "screen")
    assert screen.color == "black" and screen.texture.pattern == "digits"
    img = image(screen.texture, screen.rgb, 3.0)[..., :3].astype(int)
    lit = np.abs(img - img[0, 0]).sum(axis=-1) > 60
    assert 0.05 < lit.mean() < 0.5
    rows = np.flatnonzero(lit.any(axis=1))
    assert rows.min() > 0.05 * img.shape[0] and rows.max() < 0.95 * img.shape[0]


@pytest.mark.parametrize(("category", "revision"), BUILDS)
def test_a_revised_build_keeps_the_catalogs_promises(category, revision):
    """Before a snapshot freezes a revision, its builds already hold what the catalog's tests
    hold of a snapshot: exact annotations, the quality checks, an interior inside the bounds,
    and (a CPU renderer pays per part) at most ``MAX_PARTS`` parts."""
    from test_catalog import assert_exact_annotations

    from instructmove_ms.assets.quality import check_instances

    instances = [generate_instance(category, i, revision) for i in range(10)]
    for inst in instances:
        assert_exact_annotations(inst)
        assert len(inst.parts) <= MAX_PARTS, (inst.uuid, len(inst.parts))
        if inst.is_container:
            lo, hi = inst.bounds
            c, half = np.asarray(inst.interior.center), np.asarray(inst.interior.half)
            assert np.all(c[:2] - half >= lo[:2]) and np.all(c[:2] + half <= hi[:2])
    assert not [(r.category, r.failures) for r in check_instances(instances) if not r.ok]
