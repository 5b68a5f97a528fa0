"""Measuring how instances look: renders of each instance and of reference swatches (see
``appearance``), and the stored table of them."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from functools import cache
from pathlib import Path

import numpy as np
import sapien

from .appearance import MEASURES, dominant, srgb_to_lab, stored_lab, write_table_file
from .catalog import Instance
from .identity import content_hash
from .parts import Part
from .sapien_builder import actor_builder, add_part
from .sim import add_camera, bare_scene, look_at
from .vocab import COLORS, MATERIALS

WIDTH, HEIGHT = 160, 90  # the robots' default camera resolution
TABLE_RGB = (0.62, 0.52, 0.42)


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
        self.camera = add_camera(self.scene, "camera", WIDTH, HEIGHT, np.deg2rad(45), 0.01, 10)

    def look(self, builder: sapien.ActorBuilder, height: float, reach: float = 0.32) -> np.ndarray:
        """The Lab pixels of the actor ``builder`` makes, standing on the table, seen from
        each of ``VIEWS`` ``reach`` * sqrt(2) away (0.45 m), 45 degrees above."""
        builder.initial_pose = sapien.Pose([0, 0, 0.001])
        actor = builder.build_kinematic(name="subject")
        target = np.array([0.0, 0.0, height / 2])
        pixels = []
        for azimuth in np.deg2rad(VIEWS):
            eye = target + reach * np.array([np.cos(azimuth), np.sin(azimuth), 1.0])
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


def rendered_part(part: Part) -> tuple[float, ...]:
    """The dominant rendered colour of ``part`` alone (moved to stand on the table, the
    camera as near as its size asks), Lab."""
    lo, hi = part.bounds()
    pos = np.asarray(part.pos) - np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]])
    builder = _stage().scene.create_actor_builder()
    add_part(builder, dataclasses.replace(part, pos=tuple(float(v) for v in pos)))
    reach = max(1.5 * float(np.median(hi - lo)), 0.03)  # near enough for a thin strip
    pixels = _stage().look(builder, float(hi[2] - lo[2]), reach)
    return tuple(round(float(v), 2) for v in dominant(pixels))


def rendered_swatch(color: str, material: str) -> tuple[float, ...]:
    """The rendered colour of a 4 cm sphere of vocabulary ``color`` and ``material``."""
    part = Part(
        "swatch", "sphere", (0.04,), (0, 0, 0.04), (1, 0, 0, 0), material, color, COLORS[color]
    )
    builder = _stage().scene.create_actor_builder()
    add_part(builder, part)
    return tuple(round(float(v), 2) for v in dominant(_stage().look(builder, 0.08)))


def write_table(instances: Iterable[Instance], path: Path) -> Path:
    """Measure the rendered colours of ``instances`` (with their content hashes) and of
    every swatch, and write them (atomically), one entry per line. An instance a shipped
    table measured on this very content keeps that colour (it renders the same)."""
    rows = {
        inst.uuid: {
            "hash": content_hash(inst),
            "lab": list(stored_lab(inst) or rendered_color(inst)),
        }
        for inst in instances
    }
    swatches = {
        f"{c}/{m}": list(rendered_swatch(c, m)) for c in sorted(COLORS) for m in sorted(MATERIALS)
    }
    return write_table_file(path, rows, swatches)


MEASURES.update(instance=rendered_color, swatch=rendered_swatch)
