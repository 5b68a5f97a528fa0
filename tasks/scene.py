"""The shared table scene: a floor and a table whose top is the z = 0 plane."""

from __future__ import annotations

import sapien
from mani_skill.utils.building.ground import build_ground

TABLE_HALF = (0.6, 0.7, 0.02)  # metres: x (front-back), y, thickness
TABLE_CENTER_X = 0.3  # the robot base (origin) stands on the table, 0.3 m from its back edge
TABLE_HEIGHT = 0.75


def build_table(scene, color=(0.55, 0.40, 0.25, 1.0)) -> None:
    """Build a static table with its top face at z = 0, and the floor below it."""
    builder = scene.create_actor_builder()
    pose = sapien.Pose(p=[TABLE_CENTER_X, 0.0, -TABLE_HALF[2]])
    builder.add_box_collision(pose, half_size=TABLE_HALF)
    material = sapien.render.RenderMaterial(base_color=list(color), roughness=0.7)
    builder.add_box_visual(pose, half_size=TABLE_HALF, material=material)
    for sx in (-1, 1):
        for sy in (-1, 1):
            leg = sapien.Pose(
                p=[
                    TABLE_CENTER_X + sx * (TABLE_HALF[0] - 0.05),
                    sy * (TABLE_HALF[1] - 0.05),
                    -TABLE_HEIGHT / 2,
                ]
            )
            builder.add_box_visual(
                leg, half_size=(0.03, 0.03, TABLE_HEIGHT / 2 - 0.02), material=material
            )
    builder.initial_pose = sapien.Pose()
    builder.build_static(name="table")
    build_ground(scene, altitude=-TABLE_HEIGHT)
