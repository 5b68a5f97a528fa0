"""Printed words read the right way round: every part of the library (revision 3) that
carries a word pattern shows its words upright and left to right, seen from outside, on
the face a person reads it on; the images draw the words upright; and the texture
convention the geometric check relies on (the image's first row is at v = 1) is what
SAPIEN renders."""

from __future__ import annotations

import dataclasses
import math
import uuid
from functools import cache

import cv2
import numpy as np

from instructmove_ms.assets.catalog import generate_instance
from instructmove_ms.assets.generators import GENERATORS
from instructmove_ms.assets.parts import (
    IDENTITY,
    X_TO_Z,
    Part,
    axis_angle_quat,
    quat_mul,
    quat_to_matrix,
)
from instructmove_ms.assets.textures import (
    FRONT,
    LAYOUT_WORDS,
    PRINTED_WORDS,
    SIZE,
    WORD_FONT,
    WORDS,
    Texture,
    first_words,
    image,
)
from instructmove_ms.assets.uv_meshes import aspect, mesh_path
from instructmove_ms.assets.vocab import COLORS

LIBRARY_REVISION = 3
INDICES = range(10)
#: The categories whose build reprints another (``generators.reprints``).
REPRINTED = {"canned_coke", "chewing_gum", "chocolate", "juice", "milk_carton", "potato_chips"}


@cache
def _word_parts() -> list[tuple[str, Part]]:
    """(instance uuid, part) of every part that prints words (``print_``/``wrap_`` and the
    labels printing words, ``<layout>_words_<key>``), indices 0..9 of every category at
    library revision 3."""
    found = []
    for category in sorted(GENERATORS):
        for index in INDICES:
            inst = generate_instance(category, index, LIBRARY_REVISION)
            for part in inst.parts:
                if part.texture is not None and part.texture.pattern in PRINTED_WORDS:
                    found.append((inst.uuid, part))
    return found


# --- the image: the words drawn upright, left to right ----------------------------------


def _key(pattern: str) -> str:
    return PRINTED_WORDS[pattern]


def _ink_mask(img: np.ndarray, ink: str) -> np.ndarray:
    target = np.array([round(255 * v) for v in COLORS[ink]])
    return (np.abs(img[..., :3].astype(int) - target).sum(axis=-1) < 90).astype(np.float32)


def _crop(mask: np.ndarray) -> np.ndarray:
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    return mask[rows.min() : rows.max() + 1, cols.min() : cols.max() + 1]


@cache
def _reference(key: str) -> np.ndarray:
    """The words of ``key`` as OpenCV writes them upright (lines centred), cropped to ink."""
    lines = WORDS[key]
    sizes = [cv2.getTextSize(t, WORD_FONT, 2.0, 5)[0] for t in lines]
    width = max(w for w, _ in sizes) + 40
    line_h = max(h for _, h in sizes)
    canvas = np.zeros((len(lines) * int(line_h * 1.45) + 40, width), np.uint8)
    for k, (text, (w, _)) in enumerate(zip(lines, sizes, strict=True)):
        base = 20 + (k + 1) * line_h + int(k * 0.45 * line_h)
        cv2.putText(canvas, text, ((width - w) // 2, base), WORD_FONT, 2.0, 255, 5, cv2.LINE_AA)
    return _crop((canvas > 127).astype(np.float32))


def _agreement(mask: np.ndarray, key: str) -> dict[str, float]:
    """How well the cropped ink ``mask`` matches the reference words as they are, mirrored
    left-right, flipped upside down and turned half round (correlation of the masks)."""
    crop = _crop(mask)
    ref = cv2.resize(_reference(key), (crop.shape[1], crop.shape[0]), interpolation=cv2.INTER_AREA)
    sigma = max(1.0, 0.06 * crop.shape[0] / len(WORDS[key]))  # a stroke's misplacement forgiven
    crop, ref = (cv2.GaussianBlur(m, (0, 0), sigma) for m in (crop, ref))
    views = {
        "upright": ref,
        "mirrored": ref[:, ::-1],
        "flipped": ref[::-1],
        "turned": ref[::-1, ::-1],
    }
    a = crop - crop.mean()
    return {
        name: float((a * (v - v.mean())).sum() / (np.linalg.norm(a) * np.linalg.norm(v - v.mean())))
        for name, v in views.items()
    }


def _reads_upright(mask: np.ndarray, key: str, floor: float = 0.5) -> bool:
    """The ink matches the words upright (at least ``floor``), better than any flip."""
    score = _agreement(mask, key)
    others = max(v for k, v in score.items() if k != "upright")
    return score["upright"] > floor and score["upright"] > others + 0.1


def _copy_mask(part: Part) -> np.ndarray:
    """The ink of the first copy of the part's words in its image (no pictogram)."""
    if part.texture.pattern in LAYOUT_WORDS:  # a label's layout: the box of its first words
        shape = aspect(part.shape, part.size)
        ink, (x0, y0, x1, y1) = first_words(part.texture, shape)
        img = image(part.texture, part.rgb, shape)[..., :3].astype(int)
        target = np.array([round(255 * v) for v in (part.rgb if ink is None else ink)])
        mask = np.zeros(img.shape[:2], np.float32)
        box = img[y0:y1, x0:x1]
        mask[y0:y1, x0:x1] = np.abs(box - target).sum(axis=-1) < 90
        return mask
    texture = dataclasses.replace(part.texture, motif="")
    img = image(texture, part.rgb, aspect(part.shape, part.size))
    mask = _ink_mask(img, texture.inks[0])
    if texture.pattern.startswith("wrap_"):  # two copies: the one at a quarter of the width
        mask = mask[:, : mask.shape[1] // 2]
    return mask


# --- the mesh and pose: the image's right and up, seen from outside ---------------------


@cache
def _mesh(shape: str) -> list[tuple[np.ndarray, np.ndarray]]:
    """(3 corners, 3 uv) of each triangle of the shipped textured unit mesh."""
    vs, uvs, tris = [], [], []
    for line in mesh_path(shape).read_text().splitlines():
        kind, *rest = line.split()
        if kind == "v":
            vs.append([float(x) for x in rest])
        elif kind == "vt":
            uvs.append([float(x) for x in rest])
        elif kind == "f":
            idx = [[int(i) - 1 for i in corner.split("/")] for corner in rest]
            tris.append((np.array([vs[i[0]] for i in idx]), np.array([uvs[i[1]] for i in idx])))
    return tris


def _frames(part: Part) -> list[tuple[float, np.ndarray, np.ndarray, np.ndarray]]:
    """(area, outward normal, image right, image up) of each triangle of ``part``'s mesh,
    in the object's frame. The image's first row lies at v = 1 (SAPIEN's convention,
    checked by rendering below), so "up" in the image is +v."""
    s = part.size
    scale = np.array(s if part.shape == "box" else (s[1], s[0], s[0]))
    rot = quat_to_matrix(part.quat)
    out = []
    for corners, uv in _mesh(part.shape):
        p = corners * scale @ rot.T
        e1, e2 = p[1] - p[0], p[2] - p[0]
        du1, du2 = uv[1] - uv[0], uv[2] - uv[0]
        det = du1[0] * du2[1] - du2[0] * du1[1]
        normal = np.cross(e1, e2)
        area = float(np.linalg.norm(normal)) / 2
        if abs(det) < 1e-12 or area < 1e-12:  # a cylinder's end (uv of a disc) or a sliver
            continue
        right = (e1 * du2[1] - e2 * du1[1]) / det  # dP/du
        up = (e2 * du1[0] - e1 * du2[0]) / det  # dP/dv
        if np.dot(normal, p.mean(axis=0)) < 0:  # outward (the mesh is centred), whatever winding
            normal = -normal
        out.append((area, normal / (2 * area), right, up))
    return out


def _face_failures(part: Part) -> list[str]:
    """Where the part's words would read mirrored or not upright, seen from outside."""
    failures = []
    frames = _frames(part)
    pattern = part.texture.pattern
    if pattern.startswith("wrap_") or (part.shape == "cylinder" and pattern in LAYOUT_WORDS):
        # a cylinder's side, the whole way round
        read = [f for f in frames if abs(np.dot(f[1], quat_to_matrix(part.quat)[:, 0])) < 0.5]
    else:  # a box: the faces the image was drawn for (its largest, both sides)
        largest = max(f[0] for f in frames)
        read = [f for f in frames if f[0] > 0.999 * largest]
    if not read:
        return ["no face to read the words on"]
    for _, normal, right, up in read:
        if np.dot(np.cross(right, up), normal) <= 0:
            failures.append("mirrored")
        if abs(normal[2]) < 0.5 and np.dot(up, (0, 0, 1)) < 0.9 * np.linalg.norm(up):
            failures.append(f"not upright on a side (image up {np.round(up, 4).tolist()})")
        # on a lid or a top, read from the front (+x, where the printed sides face): the
        # words' top away from the reader
        if normal[2] > 0.5 and np.dot(up, (-1, 0, 0)) < 0.9 * np.linalg.norm(up):
            failures.append(f"not read from the front on a top (image up {np.round(up, 4)})")
    return sorted(set(failures))


# --- the tests --------------------------------------------------------------------------


def test_the_library_prints_words():
    patterns = {part.texture.pattern for _, part in _word_parts()}
    assert {"print_toothpaste", "print_face_wash", "print_sanitizer", "print_floss"} <= patterns
    assert any(p.startswith("wrap_") for p in patterns)


def test_no_label_draws_a_wordmark():
    """A label prints the words of what it is, or no word: no row of letter-like strokes
    (the first labels' wordmark, read as "Lnol" or "oluo") is left at revision 3."""
    wordmarks = {"label", "sticker", "wave"}  # the patterns that draw one
    bad = [
        (category, index, part.name, part.texture.pattern)
        for category in sorted(GENERATORS)
        for index in INDICES
        for part in generate_instance(category, index, LIBRARY_REVISION).parts
        if part.texture is not None and part.texture.pattern in wordmarks
    ]
    assert not bad, bad[:5]
    layouts = {
        LAYOUT_WORDS[p.texture.pattern][0]
        for _, p in _word_parts()
        if p.texture.pattern in LAYOUT_WORDS
    }
    assert layouts == {"label", "sticker", "wave"}  # the labels' layouts print words


def test_a_reprint_builds_what_the_build_it_reprints_builds_but_for_the_words():
    """A reprinted category (revision 3) is the build it reprints, from the same random
    draws, each wordmark label printing words instead: the same parts in the same place
    (a label turned only about its own axis or a quarter, the same box), the same
    pictogram; nothing else changed."""
    from instructmove_ms.assets.design import Design

    reprints = {
        category: gen.build.__wrapped__
        for category, gen in GENERATORS.items()
        if hasattr(gen.build, "__wrapped__")
    }
    assert set(reprints) == REPRINTED
    for category, before in sorted(reprints.items()):
        assert GENERATORS[category].revision == LIBRARY_REVISION
        reprinted = 0
        for index in INDICES:
            inst = generate_instance(category, index, LIBRARY_REVISION)
            d = Design(np.random.default_rng(uuid.UUID(inst.uuid).int % 2**63))
            before(d)
            parts, _ = d.finish()
            assert [p.name for p in parts] == [p.name for p in inst.parts]
            for old, new in zip(parts, inst.parts, strict=True):
                if old.texture == new.texture:
                    assert old == new
                    continue
                reprinted += 1
                layout = LAYOUT_WORDS[new.texture.pattern][0]
                assert layout == old.texture.pattern and new.texture.motif == old.texture.motif
                assert np.allclose(old.bounds(), new.bounds(), atol=1e-9)
                same = ("shape", "pos", "material", "color", "rgb", "visual_only")
                assert all(getattr(old, f) == getattr(new, f) for f in same), (category, old)
        assert reprinted, category


def test_a_standing_sleeve_shows_its_first_words_to_the_front():
    """Round a standing cylinder a label's first words are centred on the side that faces
    the front (``textures.FRONT``), where a reader (and a sheet's camera) stands."""
    seen = 0
    for _, part in _word_parts():
        pattern = part.texture.pattern
        if part.shape != "cylinder" or pattern not in LAYOUT_WORDS:
            continue
        rot = quat_to_matrix(part.quat)
        assert abs(rot[2, 0]) > 0.999, (part.name, pattern)  # standing
        _, (x0, _, x1, _) = first_words(part.texture, aspect(part.shape, part.size))
        a = math.pi * (x0 + x1) / SIZE  # the unit cylinder's side at that column
        out = rot @ np.array([0.0, math.cos(a), math.sin(a)])
        off = (math.atan2(out[1], out[0]) - FRONT + math.pi) % (2 * math.pi) - math.pi
        assert abs(off) < 0.1, (part.name, pattern, off)
        seen += 1
    assert seen


def test_every_printed_word_reads_upright_and_left_to_right_seen_from_outside():
    bad = [
        (uuid, part.name, part.texture.pattern, failure)
        for uuid, part in _word_parts()
        for failure in _face_failures(part)
    ]
    assert not bad, bad[:5]


def test_every_word_image_draws_its_words_upright():
    seen = {}
    for _, part in _word_parts():
        seen.setdefault((part.texture.pattern, part.texture.inks, part.color), part)
    bad = [
        (pattern, _agreement(_copy_mask(part), _key(pattern)))
        for (pattern, _, _), part in seen.items()
        if not _reads_upright(_copy_mask(part), _key(pattern))
    ]
    assert not bad, bad[:3]


def test_the_checks_catch_a_mirrored_or_upside_down_print():
    """The checks can fail: a flipped image, a label turned upside down or a box label
    turned to lie on its side are caught."""
    box = Part("label", "box", (0.0004, 0.03, 0.02), (0, 0, 0.02), IDENTITY, "paper", "white",
               COLORS["white"], texture=Texture("print_toothpaste", ("blue",)))  # fmt: skip
    sleeve = Part("label", "cylinder", (0.03, 0.03), (0, 0, 0.03), X_TO_Z, "paper", "white",
                  COLORS["white"], texture=Texture("wrap_lotion", ("blue",)))  # fmt: skip
    assert _face_failures(box) == [] and _face_failures(sleeve) == []
    upside_down = axis_angle_quat((1, 0, 0), math.pi)
    assert _face_failures(dataclasses.replace(box, quat=upside_down))
    assert _face_failures(dataclasses.replace(sleeve, quat=quat_mul(upside_down, X_TO_Z)))
    on_its_side = axis_angle_quat((1, 0, 0), math.pi / 2)
    assert _face_failures(dataclasses.replace(box, quat=on_its_side))
    lid = dataclasses.replace(box, size=(0.02, 0.03, 0.0004))  # lying flat: read from +x
    quarter = axis_angle_quat((0, 0, 1), math.pi / 2)
    assert _face_failures(dataclasses.replace(lid, quat=quarter)) == []
    assert _face_failures(lid)  # its words run along +x: read from the side
    mask = _copy_mask(box)
    assert _reads_upright(mask, "toothpaste")
    for flipped in (mask[:, ::-1], mask[::-1], mask[::-1, ::-1]):
        assert not _reads_upright(flipped, "toothpaste")


def test_sapien_shows_the_first_image_row_at_the_top():
    """Rendered from in front (+x), a standing box label's and a sleeve's words read
    upright, left to right: the convention ``_frames`` assumes."""
    import sapien

    from instructmove_ms.assets.sapien_builder import add_part
    from instructmove_ms.assets.sim import add_camera, look_at, table_scene

    box = Part("label", "box", (0.002, 0.05, 0.03), (0, 0, 0.03), IDENTITY, "plastic", "white",
               COLORS["white"], texture=Texture("print_toothpaste", ("blue",)))  # fmt: skip
    sleeve = Part("label", "cylinder", (0.03, 0.03), (0, 0, 0.03), X_TO_Z, "plastic", "white",
                  COLORS["white"], texture=Texture("wrap_floss", ("blue",)))  # fmt: skip
    scene = table_scene(render=True)
    camera = add_camera(scene, "front", 256, 256, math.radians(40), 0.005, 10.0)
    camera.set_local_pose(look_at((0.2, 0.0, 0.03), (0.0, 0.0, 0.03)))
    for part, key in ((box, "toothpaste"), (sleeve, "floss")):
        builder = scene.create_actor_builder()
        add_part(builder, part)
        builder.initial_pose = sapien.Pose([0, 0, 0.0])
        actor = builder.build_kinematic(name="label")
        scene.update_render()
        camera.take_picture()
        rgb = (np.clip(camera.get_picture("Color")[..., :3], 0, 1) * 255).astype(int)
        mask = ((rgb[..., 2] - rgb[..., 0] > 40) & (rgb[..., 2] > 90)).astype(np.float32)
        scene.remove_entity(actor)
        assert mask.sum() > 100, key
        # a sleeve's word bends away at its ends: a looser match, still far above a flip
        assert _reads_upright(mask, key, floor=0.3), (key, _agreement(mask, key))
