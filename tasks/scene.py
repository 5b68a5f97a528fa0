"""The shared table scene: a floor and a table whose top is the z = 0 plane."""

from __future__ import annotations

import numpy as np
import sapien
from mani_skill.utils.building.ground import build_ground

from instructmove_ms.perturbation import TABLE_COLOR

TABLE_HALF = (0.6, 0.7, 0.02)  # metres: x (front-back), y, thickness
TABLE_CENTER_X = 0.3  # the robot base (origin) stands on the table, 0.3 m from its back edge
TABLE_HEIGHT = 0.75
#: The table's look; the ``table`` perturbation axis draws others of the same keys.
DEFAULT_LOOK = {"color": list(TABLE_COLOR), "roughness": 0.7, "metallic": 0.0, "height": 0.0}


def _stripes(color, stripes: dict) -> sapien.render.RenderTexture2D:
    """A striped texture (like wood grain) of the table colour and the stripes' colour."""
    size, half_period = 64, max(1, stripes["period"] // 2)
    rows = (np.arange(size) // half_period) % 2
    image = np.where(rows[:, None, None], [*stripes["color"], 1.0], [*color, 1.0])
    image = np.broadcast_to(image, (size, size, 4))
    return sapien.render.RenderTexture2D(
        np.ascontiguousarray((image * 255).astype(np.uint8)), "R8G8B8A8Unorm"
    )


def _add_visuals(builder, look: dict, can_render: bool) -> None:
    """The table top and legs of ``look`` (legs down to the floor ``look``'s ``height``
    below ``TABLE_HEIGHT``)."""
    pose = sapien.Pose(p=[TABLE_CENTER_X, 0.0, -TABLE_HALF[2]])
    material = sapien.render.RenderMaterial(
        base_color=[*look["color"], 1.0], roughness=look["roughness"], metallic=look["metallic"]
    )
    if "stripes" in look and can_render:
        material.base_color_texture = _stripes(look["color"], look["stripes"])
    builder.add_box_visual(pose, half_size=TABLE_HALF, material=material)
    height = TABLE_HEIGHT + look["height"]
    for sx in (-1, 1):
        for sy in (-1, 1):
            leg = sapien.Pose(
                p=[
                    TABLE_CENTER_X + sx * (TABLE_HALF[0] - 0.05),
                    sy * (TABLE_HALF[1] - 0.05),
                    -height / 2,
                ]
            )
            builder.add_box_visual(
                leg, half_size=(0.03, 0.03, height / 2 - 0.02), material=material
            )


def build_table(scene, look: dict | None = DEFAULT_LOOK) -> None:
    """The static ``table`` actor with its top face at z = 0, drawn with ``look`` (none:
    collision only)."""
    builder = scene.create_actor_builder()
    pose = sapien.Pose(p=[TABLE_CENTER_X, 0.0, -TABLE_HALF[2]])
    builder.add_box_collision(pose, half_size=TABLE_HALF)
    if look is not None:
        _add_visuals(builder, look, scene.can_render())
    builder.initial_pose = sapien.Pose()
    builder.build_static(name="table")


def build_room(scene, looks: list[dict | None]) -> float:
    """The table and the floor below it; returns the floor's height. Where a sub-scene has
    a ``table`` look drawn, the shared table keeps its collision and each sub-scene gets
    its own visual-only table of its look (the floor follows sub-scene 0's height)."""
    if any(looks):
        build_table(scene, None)
        for i, look in enumerate(looks):
            builder = scene.create_actor_builder()
            _add_visuals(builder, look or DEFAULT_LOOK, scene.can_render())
            builder.set_scene_idxs([i])
            builder.initial_pose = sapien.Pose()
            builder.build_static(name=f"table_look_{i}")
    else:
        build_table(scene)
    floor = -(TABLE_HEIGHT + (looks[0] or DEFAULT_LOOK)["height"])
    build_ground(scene, altitude=floor)
    return floor
