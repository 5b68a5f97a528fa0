"""Colours as the camera shows them: the shipped table of rendered colours is what the
renderer gives, instructions name only colours an object shows, and the attribute cue
tells objects apart only by differences that show."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import instructmove_ms  # noqa: F401
from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets.appearance import (
    DISTINCT,
    MATCH,
    _table,
    color_match,
    delta_e,
    lab_of,
    look_differs,
    shown_color,
    swatch,
)
from instructmove_ms.assets.expressions import (
    all_phrases,
    colored,
    own_color_unsaid,
    said_nouns,
)
from instructmove_ms.assets.identity import content_hash
from instructmove_ms.assets.photometry import rendered_color, rendered_swatch
from instructmove_ms.assets.snapshot import SHIPPED
from instructmove_ms.assets.vocab import COLORS
from instructmove_ms.language import color_word, says


@pytest.mark.parametrize("name", sorted(SHIPPED))
def test_the_shipped_table_is_what_the_renderer_shows_for_the_whole_library(name):
    """Every instance (printed or plain, as the snapshot has them) and swatch rendered
    afresh: its colour equals the shipped one (the table was measured on this very
    content), and an instance's stated colours include one the camera shows or the grammar
    names it by none."""
    table = _table(name)["instances"]
    catalog = load_snapshot(name)
    assert set(table) == {inst.uuid for inst in catalog.instances}
    drift, unshown = [], []
    for inst in catalog.instances:
        assert table[inst.uuid]["hash"] == content_hash(inst)
        drift.append(delta_e(rendered_color(inst), table[inst.uuid]["lab"]))
        if shown_color(inst) is None:
            unshown.append(inst)
    for key, lab in _table(name)["swatches"].items():
        drift.append(delta_e(rendered_swatch(*key.split("/")), lab))
    assert max(drift) < 0.5, max(drift)
    assert len(unshown) <= 0.02 * len(catalog.instances), [i.category for i in unshown]
    for inst in unshown:  # named by noun, material and parts only
        words = {color_word(c) for c in COLORS}
        singles = [p for p in all_phrases(inst) if p.split()[0] in words]
        assert not [p for p in singles if " and " not in p], inst.category


def test_phrases_use_the_colour_the_camera_shows():
    catalog = load_snapshot()
    moved = 0
    for inst in catalog.instances:
        shown = shown_color(inst)
        if shown is None:
            continue
        color, distance = color_match(inst)
        assert color == shown and distance <= MATCH
        noun = said_nouns(inst)[0]
        phrase = colored(inst, noun)
        assert color_word(shown) in phrase.replace("-", " ").split()
        # a food's own colour is said by the colour cue alone
        assert (phrase in all_phrases(inst)) != own_color_unsaid(inst)
        moved += shown != inst.colors[0]
    assert moved > 0, "some two-coloured objects show their second colour most"


def test_the_colours_a_reader_confused_do_not_count_as_distinct():
    assert delta_e(swatch("white", "plastic"), swatch("gray", "plastic")) < DISTINCT
    assert delta_e(swatch("white", "plastic"), swatch("silver", "plastic")) < DISTINCT
    assert delta_e(swatch("red", "plastic"), swatch("blue", "plastic")) > DISTINCT
    assert not look_differs("ceramic", "plastic") and not look_differs("silicone", "plastic")
    assert look_differs("metal", "plastic") and look_differs("glass", "ceramic")


@pytest.fixture(scope="module")
def attribute_env():
    env = gym.make("PickAttribute-InstructMove", obs_mode="state", render_backend="none")
    yield env
    env.close()


def test_attribute_episodes_differ_in_what_the_camera_shows(attribute_env):
    u = attribute_env.unwrapped
    seen = set()
    for seed in range(150):
        spec = u.sample_episode(seed)
        insts = [u.catalog[spec.objects[k].uuid] for k in spec.candidates]
        labs = np.array([lab_of(i) for i in insts])
        for a in range(len(insts)):
            for b in range(a + 1, len(insts)):
                assert delta_e(labs[a], labs[b]) >= DISTINCT, (seed, spec.instruction)
        target = u.catalog[spec.target_object.uuid]
        attribute = spec.cue["attribute"]
        seen.add(attribute)
        if attribute == "color":
            assert says(spec.instruction, color_word(shown_color(target)))  # "pink-wrapped" too
        if attribute == "material":
            others = [i for i in insts if i.uuid != target.uuid]
            assert all(look_differs(target.material, o.material) for o in others)
    assert seen == {"color", "size", "shape", "material"}


def test_colours_render_the_same_after_an_env_set_its_camera_shader():
    """ManiSkill's rgb sensors set a global shader pack (8-bit colour, no segmentation);
    a colour measured afterwards (a user snapshot's, on first use inside an env) still
    matches the table."""
    from conftest import make_env

    env = make_env(obs_mode="rgb", render_backend="cpu")
    env.reset(seed=0)
    env.close()
    inst = load_snapshot().of_category("mug")[0]
    assert delta_e(rendered_color(inst), _table()["instances"][inst.uuid]["lab"]) < 0.5
