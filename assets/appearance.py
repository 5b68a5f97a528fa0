"""How instances look once rendered: each one's dominant colour, measured on a render.

An instance is rendered alone on the table's colour under ManiSkill's default lights, from
a camera 0.45 m away looking down at 45 degrees, at the default camera resolution; its
pixels (from the segmentation) are read in CIE Lab and the most populated colour (a coarse
Lab histogram's fullest bin, averaged, over four views around it) is its rendered colour.
``delta_e`` compares two such colours (CIE94 with lightness weighted half; about 1 is a
just noticeable difference; ``DISTINCT`` is what the attribute cue needs between two
objects it tells apart by colour). Reference swatches
render each vocabulary colour on a sphere of each material the same way, so an instance's
stated colour can be checked against what the camera shows (``shown_color``). The
measurements of the shipped snapshot are stored beside it, so that composition reads the
same colours on every machine.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from functools import cache
from pathlib import Path

import numpy as np
import sapien

from ..files import write_text
from .catalog import Instance
from .parts import Part
from .sapien_builder import actor_builder, add_part
from .sim import bare_scene, look_at
from .snapshot import DEFAULT_SNAPSHOT, content_hash, package_snapshot_dir
from .vocab import COLORS, MATERIALS

#: Rendered colours at least this far apart read as different colours (``delta_e``).
DISTINCT = 12.0
#: An instance shows a stated colour when its rendered colour is within this of the
#: colour's swatch.
MATCH = 15.0
#: Roughness difference that reads as another material (ceramic 0.25 vs plastic 0.45 does
#: not; wood 0.75 vs plastic does).
ROUGHNESS_STEP = 0.3
WIDTH, HEIGHT = 160, 90  # the robots' default camera resolution
TABLE_RGB = (0.62, 0.52, 0.42)
_BIN = 8.0  # Lab histogram bin for the dominant colour


def srgb_to_lab(rgb: np.ndarray) -> np.ndarray:
    """CIE Lab (D65) of sRGB values in [0, 1], shape (..., 3)."""
    rgb = np.asarray(rgb, dtype=float)
    linear = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    m = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    xyz = linear @ m.T / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack(
        [116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])],
        axis=-1,
    )


def delta_e(a, b) -> float:
    """CIE94 colour difference of two Lab colours, with lightness weighted half
    (``K_L = 2``: shading moves lightness across an object's faces, not its hue) and the
    two chromas' geometric mean as reference, so that it is symmetric."""
    (l1, a1, b1), (l2, a2, b2) = (np.asarray(v, float) for v in (a, b))
    c1, c2 = np.hypot(a1, b1), np.hypot(a2, b2)
    c, dc = np.sqrt(c1 * c2), c1 - c2
    dh2 = max((a1 - a2) ** 2 + (b1 - b2) ** 2 - dc**2, 0.0)
    return float(
        np.sqrt(((l1 - l2) / 2) ** 2 + (dc / (1 + 0.045 * c)) ** 2 + dh2 / (1 + 0.015 * c) ** 2)
    )


def dominant(lab: np.ndarray) -> np.ndarray:
    """The mean of the fullest coarse Lab bin of ``lab`` pixels (n, 3)."""
    bins = np.floor(lab / _BIN).astype(int)
    keys, inverse, counts = np.unique(bins, axis=0, return_inverse=True, return_counts=True)
    return lab[inverse.ravel() == int(np.argmax(counts))].mean(axis=0)


#: Camera azimuths (degrees) around the object: the rendered colour pools four views.
VIEWS = (0.0, 90.0, 180.0, 270.0)


class _Stage:
    """A scene with the table's colour, ManiSkill's default lights and one camera."""

    def __init__(self) -> None:
        self.scene = bare_scene()
        self.scene.set_ambient_light([0.3, 0.3, 0.3])
        self.scene.add_directional_light([1, 1, -1], [1, 1, 1])
        self.scene.add_directional_light([0, 0, -1], [1, 1, 1])
        ground = self.scene.create_actor_builder()
        material = sapien.render.RenderMaterial(base_color=[*TABLE_RGB, 1.0], roughness=0.7)
        ground.add_box_visual(sapien.Pose([0, 0, -0.01]), [1, 1, 0.01], material=material)
        ground.build_static(name="table")
        self.camera = self.scene.add_camera("camera", WIDTH, HEIGHT, np.deg2rad(45), 0.01, 10)

    def look(self, builder: sapien.ActorBuilder, height: float) -> np.ndarray:
        """The Lab pixels of the actor ``builder`` makes, standing on the table, seen from
        each of ``VIEWS`` 0.45 m away, 45 degrees above."""
        builder.initial_pose = sapien.Pose([0, 0, 0.001])
        actor = builder.build_kinematic(name="subject")
        target = np.array([0.0, 0.0, height / 2])
        pixels = []
        for azimuth in np.deg2rad(VIEWS):
            eye = target + 0.32 * np.array([np.cos(azimuth), np.sin(azimuth), 1.0])
            self.camera.entity.set_pose(look_at(eye, target))
            self.scene.update_render()
            self.camera.take_picture()
            rgb = self.camera.get_picture("Color")[..., :3]
            mask = self.camera.get_picture("Segmentation")[..., 1] == actor.per_scene_id
            pixels.append(rgb[mask])
        self.scene.remove_entity(actor)
        return srgb_to_lab(np.clip(np.concatenate(pixels), 0.0, 1.0))


@cache
def _stage() -> _Stage:
    return _Stage()


def rendered_color(instance: Instance) -> tuple[float, float, float]:
    """The instance's dominant rendered colour, Lab."""
    lo, hi = instance.bounds
    pixels = _stage().look(actor_builder(_stage().scene, instance), float(hi[2] - lo[2]))
    if not len(pixels):
        raise ValueError(f"{instance.uuid} ({instance.category}) covers no pixel of the camera")
    return tuple(round(float(v), 2) for v in dominant(pixels))


@cache
def swatch(color: str, material: str) -> tuple[float, float, float]:
    """The rendered colour of a 4 cm sphere of vocabulary ``color`` and ``material``."""
    part = Part(
        "swatch", "sphere", (0.04,), (0, 0, 0.04), (1, 0, 0, 0), material, color, COLORS[color]
    )
    builder = _stage().scene.create_actor_builder()
    add_part(builder, part)
    return tuple(round(float(v), 2) for v in dominant(_stage().look(builder, 0.08)))


def rendered_colors(instances: Iterable[Instance]) -> dict[str, dict]:
    """uuid -> {"hash": content hash, "lab": rendered colour} of each instance."""
    return {
        inst.uuid: {"hash": content_hash(inst), "lab": list(rendered_color(inst))}
        for inst in instances
    }


def table_path(snapshot: str = DEFAULT_SNAPSHOT) -> Path:
    """The file of a snapshot's rendered colours, beside the snapshot."""
    return package_snapshot_dir() / "appearance" / f"{snapshot}.json"


def write_table(instances: Iterable[Instance], path: Path) -> Path:
    """Measure and write the rendered colours of ``instances`` (atomically)."""
    rows = sorted(rendered_colors(instances).items())
    body = ",\n".join(f"{json.dumps(k)}: {json.dumps(v, sort_keys=True)}" for k, v in rows)
    return write_text(path, "{\n" + body + "\n}\n")


@cache
def _table() -> dict[str, dict]:
    path = table_path()
    return json.loads(path.read_text()) if path.is_file() else {}


@cache
def lab_of(instance: Instance) -> tuple[float, float, float]:
    """The instance's rendered colour: from the shipped table where it was measured on
    this very content (the same on every machine), else rendered now."""
    entry = _table().get(instance.uuid)
    if entry is not None and entry["hash"] == content_hash(instance):
        return tuple(entry["lab"])
    return rendered_color(instance)


def _material(instance: Instance, color: str) -> str:
    return next(p.material for p in instance.parts if p.color == color)


def color_match(instance: Instance) -> tuple[str, float]:
    """The stated colour whose swatch (in that colour's material) is nearest the
    instance's rendered colour, and how near."""
    lab = lab_of(instance)
    return min(
        ((c, delta_e(lab, swatch(c, _material(instance, c)))) for c in instance.colors),
        key=lambda pair: pair[1],
    )


def shown_color(instance: Instance) -> str | None:
    """The stated colour the camera shows (within ``MATCH`` of the rendered colour), None
    where it shows none of them: instructions name an object only by a colour it shows."""
    color, distance = color_match(instance)
    return color if distance <= MATCH else None


def look_differs(a: str, b: str) -> bool:
    """Whether materials ``a`` and ``b`` render differently: metallic or transmissive
    against not, or roughness ``ROUGHNESS_STEP`` apart."""
    ma, mb = MATERIALS[a], MATERIALS[b]
    return (
        abs(ma.metallic - mb.metallic) >= 0.5
        or abs(ma.transmission - mb.transmission) >= 0.5
        or abs(ma.roughness - mb.roughness) >= ROUGHNESS_STEP
    )
