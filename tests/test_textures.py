"""Printed labels and patterns: they show on the camera, keep each part's annotated colour,
change nothing physical, and a snapshot frozen before them still rebuilds its plain look."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets import snapshot as snap
from instructmove_ms.assets.appearance import DISTINCT, delta_e, dominant, srgb_to_lab
from instructmove_ms.assets.catalog import generate_instance
from instructmove_ms.assets.identity import content_hash
from instructmove_ms.assets.parts import X_TO_Z, Part
from instructmove_ms.assets.photometry import _stage, rendered_part
from instructmove_ms.assets.sapien_builder import add_part
from instructmove_ms.assets.textures import Texture, image
from instructmove_ms.assets.uv_meshes import SHAPES, WRITERS, aspect, mesh_path
from instructmove_ms.assets.vocab import COLORS

#: The packaged and printed objects two readers could not name from their plain close-ups.
READER_MISSES = (
    "canned_coke",
    "juice",
    "potato_chips",
    "chewing_gum",
    "biscuit",
    "chocolate",
    "cheese_sticks",
    "staples_box",
    "dental_floss",
    "hand_sanitizer",
    "alarm_clock",
)


def _textured_parts(*catalogs):
    """Each distinct textured part of ``catalogs`` (by recipe, colour, material and size)."""
    seen = {}
    for inst in (i for catalog in catalogs for i in catalog.instances):
        for part in inst.parts:
            if part.texture is not None:
                key = (part.texture, part.color, part.material, part.shape, part.size)
                seen.setdefault(key, (inst, part))
    return list(seen.values())


@pytest.mark.parametrize("shape", SHAPES)
def test_the_shipped_uv_meshes_are_what_the_module_writes(shape):
    assert mesh_path(shape).read_text() == WRITERS[shape]()


def test_a_plain_build_holds_the_same_bodies():
    """An instance built plain (``--plain``) is the printed one without its textures: same
    parts, colours and masses (so the same physics and layouts); only textured instances
    hash apart, and every category a reader missed wears a print in its packaged kinds (a
    loose cookie has none)."""
    printed = load_snapshot()
    textured = set()
    for inst in printed.instances:
        bare = snap.plain(inst)
        assert bare.uuid == inst.uuid and bare.mass == inst.mass
        assert [p.rgb for p in bare.parts] == [p.rgb for p in inst.parts]
        assert all(p.texture is None for p in bare.parts)
        wears = any(p.texture is not None for p in inst.parts)
        assert (content_hash(inst) != content_hash(bare)) == wears
        if wears:
            textured.add(inst.uuid)
    assert len(textured) > 200
    for category in READER_MISSES:
        wearing = [i for i in printed.of_category(category) if i.uuid in textured]
        assert len(wearing) >= 2, category  # 2 of the 10 biscuits are packets


def test_each_texture_keeps_its_part_colour_and_shows():
    """Rendered alone, every textured part of the library keeps the colour of its plain
    self (its annotation: never a colour apart), and its image's dominant colour is the
    part's own."""
    far = []
    textured = [load_snapshot(n) for n, frozen in snap.SHIPPED.items() if frozen.textures]
    for inst, part in _textured_parts(*textured):
        drawn_on = image(part.texture, part.rgb, aspect(part.shape, part.size))
        pixels = srgb_to_lab(drawn_on[..., :3].reshape(-1, 3) / 255.0)
        drawn = delta_e(dominant(pixels), srgb_to_lab(np.array(part.rgb)))
        assert drawn < 3, (inst.category, part.name, drawn)
        shown = delta_e(rendered_part(part), rendered_part(dataclasses.replace(part, texture=None)))
        far.append((shown, inst.category, part.name))
    assert max(far)[0] < DISTINCT, max(far)


def test_prints_are_drawn_at_the_shape_of_their_surface():
    """A can's side is about twice as wide as high: its image is drawn that wide and
    squeezed (the mesh stretches it back), so a pictogram stays round; a disc's badge and
    a box's largest face likewise."""
    assert aspect("cylinder", (0.033, 0.05)) == 2.07  # pi r / half length
    assert aspect("cylinder", (0.04, 0.001)) == 1.0  # a disc shows its ends
    assert aspect("box", (0.05, 0.02, 0.01)) == 2.5  # the top, x over y
    fruit = Texture("sticker", ("white", "yellow"), "fruit")
    wide, square = image(fruit, COLORS["red"], 2.0), image(fruit, COLORS["red"], 1.0)
    yellow = np.array([int(255 * v) for v in COLORS["yellow"]])

    def fruit_width_over_height(img):
        rows, cols = np.nonzero((np.abs(img[..., :3].astype(int) - yellow) < 40).all(axis=-1))
        return (np.ptp(cols) + 1) / (np.ptp(rows) + 1)

    assert fruit_width_over_height(wide) == pytest.approx(fruit_width_over_height(square) / 2, 0.15)
    badge = Texture("badge", ("white", "yellow"), "fruit")
    assert (image(badge, COLORS["red"], 3.0) == image(badge, COLORS["red"], 1.0)).all()


def test_a_print_shows_on_the_camera():
    """The cola can's ribbon: white pixels on the printed body, none on the plain one."""
    ribbon = Texture("wave", ("white",))
    body = Part("body", "cylinder", (0.033, 0.05), (0, 0, 0.05), X_TO_Z, "aluminium", "red",
                COLORS["red"], texture=ribbon)  # fmt: skip
    whites = []
    for part in (body, dataclasses.replace(body, texture=None)):
        builder = _stage().scene.create_actor_builder()
        add_part(builder, part)
        lab = _stage().look(builder, 0.1, 0.12)
        whites.append(float(((lab[:, 0] > 55) & (np.hypot(lab[:, 1], lab[:, 2]) < 10)).mean()))
    assert whites[0] > 0.05 and whites[1] < 0.005, whites


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: Texture("tartan"), "unknown texture pattern 'tartan'"),
        (lambda: Texture("label", ("mauve",)), "unknown ink colour 'mauve'"),
        (lambda: Texture("label", (), "unicorn"), "unknown motif 'unicorn'"),
        (lambda: Texture("dial"), "pattern 'dial' prints 1 inks"),
        (
            lambda: Part(
                "ball",
                "sphere",
                (0.02,),
                (0, 0, 0.02),
                (1, 0, 0, 0),
                "plastic",
                "red",
                COLORS["red"],
                texture=Texture("grain"),
            ),  # fmt: skip
            "a sphere carries no texture",
        ),
    ],
)
def test_bad_textures_are_refused_by_name(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_a_snapshot_frozen_without_textures_rebuilds_them_plain(tmp_path, monkeypatch):
    """A snapshot file with no ``textures`` key (every one frozen before them) loads its
    instances plain and hash-checks them; the same entries marked textured are stale."""
    monkeypatch.setattr(snap, "user_snapshot_dir", lambda: tmp_path)
    notebook = generate_instance("notebook", 0, 1)  # as the snapshot (revision 1) builds it
    assert any(p.texture is not None for p in notebook.parts)
    entry = snap.entry_of(snap.plain(notebook))
    path = snap.write_snapshot(tmp_path / "old.json", "old", [entry], snap.Frozen(False, 1))
    data = {k: v for k, v in json.loads(path.read_text()).items() if k != "textures"}
    (loaded,) = snap._checked("old", data)
    assert loaded == snap.plain(notebook)
    with pytest.raises(ValueError, match="is stale: notebook #0"):
        snap._checked("old", {**data, "textures": True})


def test_a_state_env_then_a_rendering_env_in_one_process(tmp_path):
    """An env without a renderer builds its printed objects plain (a texture made there
    would start SAPIEN's renderer on another device); a rendering env made after it in the
    same process starts and shows the prints. In a fresh process: the suite's own
    processes have started a renderer already."""
    import subprocess
    import sys

    script = tmp_path / "two_envs.py"
    script.write_text(
        "import gymnasium as gym\n"
        "import instructmove_ms\n"
        "from sapien.render import RenderBodyComponent\n"
        "kw = dict(robot_uids='franka', obs_mode='state')\n"
        "gym.make('PickCategory-InstructMove', render_backend='none', **kw).reset(seed=0)\n"
        "env = gym.make('PickCategory-InstructMove', **{**kw, 'obs_mode': 'rgb'})\n"
        "env.reset(seed=0)\n"
        "shapes = [s for a in env.unwrapped.objects for e in a._objs\n"
        "          for s in e.find_component_by_type(RenderBodyComponent).render_shapes]\n"
        "print(sum(s.material.base_color_texture is not None for s in shapes))\n"
    )
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    assert int(done.stdout.split()[-1]) > 0, "seed 0's scene holds a printed object"
