"""Generator revisions: a revised category builds new assets, and every snapshot keeps
regenerating the assets it was frozen with."""

from __future__ import annotations

import json

import numpy as np
import pytest

from instructmove_ms.assets import snapshot as snap
from instructmove_ms.assets.catalog import generate_instance, instance_uuid
from instructmove_ms.assets.generators import LIBRARY, REVISIONS, generator_at, revised
from instructmove_ms.assets.textures import PRINTED_WORDS, image

#: What revision 2 rebuilt, and a part (name, colour) that shows it.
REVISED_2 = {
    "mouse": ("seam_across", None),
    "alarm_clock": ("screen", "black"),
    "glue_gun": ("cord", "black"),
    "chewing_gum": ("stick_0", "silver"),
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
#: (category, revision) of every revised build.
BUILDS = sorted((c, r) for r, cats in REVISED.items() for c in cats)


def _shows(inst, category: str, revision: int) -> bool:
    name, color = REVISED[revision][category]
    if revision == 3 and category in REPRINTED_3:
        return any(
            p.name == name and p.texture is not None and p.texture.pattern in PRINTED_WORDS
            for p in inst.parts
        )
    return any(p.name == name and color in (None, p.color) for p in inst.parts)


def test_the_revised_categories_are_the_ones_registered():
    registered = {(c, r) for c, builds in REVISIONS.items() for r in builds if r > 1}
    assert registered == set(BUILDS)
    assert LIBRARY == 3


@pytest.mark.parametrize(("category", "revision"), BUILDS)
def test_a_revision_is_a_new_asset_of_the_same_category(category, revision):
    old, new = generator_at(category, revision - 1), generator_at(category, revision)
    assert new.revision == revision and old.revision < revision
    assert (old.synonyms, old.size, old.container) == (new.synonyms, new.size, new.container)
    for index in range(10):
        a = generate_instance(category, index, revision - 1)
        b = generate_instance(category, index, revision)
        assert b.uuid == instance_uuid(category, index, revision) != a.uuid
        assert a.parts != b.parts
    # the defining part is there (in the variants that have it), and never before
    assert any(
        _shows(generate_instance(category, i, revision), category, revision) for i in range(10)
    )
    assert not any(
        _shows(generate_instance(category, i, revision - 1), category, revision) for i in range(10)
    )


def test_an_unrevised_category_is_the_same_asset_at_every_revision():
    assert generate_instance("mug", 3, 1) == generate_instance("mug", 3, 2)


def test_each_shipped_snapshot_rebuilds_at_its_own_revision():
    """The snapshots frozen before the revision keep their mice; the newest has the new
    ones, and everything else is shared."""
    mice = {n: snap.load_snapshot(n).of_category("mouse")[0] for n in snap.SHIPPED}
    assert mice["printed"].uuid == mice["default"].uuid == instance_uuid("mouse", 0)
    assert mice["detailed"].uuid == instance_uuid("mouse", 0, 2)
    printed, detailed = (snap.load_snapshot(n) for n in ("printed", "detailed"))
    moved = {i.uuid for i in printed.instances} - {i.uuid for i in detailed.instances}
    assert {printed[u].category for u in moved} == set(REVISED_2)
    assert len(moved) == 10 * len(REVISED_2)
    assert snap.frozen_as("printed") == snap.Frozen(textures=True, library=1)
    assert snap.frozen_as("detailed") == snap.Frozen(textures=True, library=2)


def test_a_snapshot_file_from_before_revisions_reads_as_revision_1(tmp_path, monkeypatch):
    data = json.loads(snap.snapshot_path("printed").read_text())
    assert "library" not in data  # written before revisions: its bytes never changed
    monkeypatch.setattr(snap, "user_snapshot_dir", lambda: tmp_path)
    entry = snap.entry_of(generate_instance("juice", 1, 1))
    snap.write_snapshot(tmp_path / "mine.json", "mine", [entry], snap.Frozen(True, 1))
    snap.load_snapshot.cache_clear()
    try:
        assert snap.load_snapshot("mine").instances[0] == generate_instance("juice", 1, 1)
        bad = {
            **entry,
            "content_hash": snap.entry_of(generate_instance("juice", 1)).get("content_hash"),
        }
        snap.write_snapshot(tmp_path / "bad.json", "bad", [bad], snap.Frozen(True, 2))
        with pytest.raises(ValueError, match="'bad' is stale: juice #1"):
            snap.load_snapshot("bad")
    finally:
        snap.load_snapshot.cache_clear()


def test_bad_revisions_are_refused():
    with pytest.raises(ValueError, match="revision 4 is not in 1..3"):
        generator_at("mouse", 4)
    with pytest.raises(ValueError, match="numbered 2..3, got 1"):
        revised("mouse", 1)
    with pytest.raises(ValueError, match="two builds at revision 2"):
        revised("mouse", 2)(lambda d: None)
    with pytest.raises(ValueError, match="cannot revise 'teapot'"):
        revised("teapot", 2)(lambda d: None)


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
