"""What the rendered perturbation axes change in a built scene (see
``instructmove_ms.perturbation``): the lights, the floor and walls, and the cameras' poses
(the table's look is ``scene.build_table``'s). Each function takes one value dict per
sub-scene (None where that sub-scene is not perturbed on the axis) and returns False when
no sub-scene is, so the env builds its unperturbed scene exactly as before.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import sapien

from instructmove_ms.perturbation import DEFAULT_AMBIENT, DEFAULT_LIGHTS

from .scene import TABLE_CENTER_X

#: Visual-only floor patch and walls: half extents (m) and the walls' distance from the robot.
FLOOR_HALF = 4.0
WALL_DISTANCE, WALL_HALF_WIDTH, WALL_HEIGHT = 2.0, 2.5, 3.0


def light(scene, values: Sequence[dict | None], shadow: bool) -> bool:
    """Per sub-scene the drawn lights (ManiSkill's defaults where None). The ambient light
    is one per scene: sub-scene 0's."""
    if not any(values):
        return False
    first = next(v for v in values if v)
    scene.set_ambient_light(first["ambient"] if values[0] else [DEFAULT_AMBIENT] * 3)
    default = [{"direction": d, "color": [1.0] * 3, "shadow": s} for d, s in DEFAULT_LIGHTS]
    for i, v in enumerate(values):
        for sun in v["lights"] if v else default:
            scene.add_directional_light(
                sun["direction"],
                sun["color"],
                shadow=shadow and sun["shadow"],
                shadow_scale=5,
                shadow_map_size=2048,
                scene_idxs=[i],
            )
        for lamp in v["lamps"] if v else ():
            scene.add_point_light(lamp["position"], lamp["color"], scene_idxs=[i])
    return True


def _panel(scene, name: str, pose: sapien.Pose, half, color, scene_idx: int) -> None:
    builder = scene.create_actor_builder()
    material = sapien.render.RenderMaterial(base_color=[*color, 1.0], roughness=0.9)
    builder.add_box_visual(sapien.Pose(), half_size=half, material=material)
    builder.set_scene_idxs([scene_idx])
    builder.initial_pose = pose
    builder.build_static(name=f"{name}_{scene_idx}")


def backdrop(scene, values: Sequence[dict | None], floor_z: float) -> bool:
    """Per sub-scene a coloured floor over the ground at ``floor_z`` and the drawn walls
    (side 0 ahead of the robot, 1 on its left, 2 on its right); visual only."""
    if not any(values):
        return False
    for i, v in enumerate(values):
        if not v:
            continue
        floor = sapien.Pose(p=[TABLE_CENTER_X, 0.0, floor_z + 0.001])
        _panel(scene, "floor", floor, (FLOOR_HALF, FLOOR_HALF, 0.0005), v["floor"], i)
        for wall in v["walls"]:
            angle = (0.0, math.pi / 2, -math.pi / 2)[wall["side"]]
            centre = [
                TABLE_CENTER_X + WALL_DISTANCE * math.cos(angle),
                WALL_DISTANCE * math.sin(angle),
                floor_z + WALL_HEIGHT / 2,
            ]
            pose = sapien.Pose(p=centre, q=[math.cos(angle / 2), 0.0, 0.0, math.sin(angle / 2)])
            _panel(
                scene,
                f"wall{wall['side']}",
                pose,
                (0.01, WALL_HALF_WIDTH, WALL_HEIGHT / 2),
                wall["color"],
                i,
            )
    return True


def _turned(turn, q) -> list[float]:
    """The quaternion product ``turn * q`` (wxyz)."""
    w1, x1, y1, z1 = turn
    w2, x2, y2, z2 = q
    return [
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ]


def move_cameras(sensors: dict, values: Sequence[dict | None]) -> bool:
    """Each sub-scene's cameras offset and turned in their mount's frame by the drawn
    jitter, from the pose their config gives."""
    if not any(values):
        return False
    for uid, sensor in sensors.items():
        base = sensor.config.pose.raw_pose.cpu().numpy()
        # ManiSkill's camera struct keeps one render camera per sub-scene
        for i, camera in enumerate(sensor.camera._render_cameras):
            jitter = values[i].get(uid) if values[i] else None
            if jitter is None:
                continue
            p, q = base[min(i, len(base) - 1), :3], base[min(i, len(base) - 1), 3:]
            camera.set_local_pose(
                sapien.Pose(p=p + np.asarray(jitter["offset"]), q=_turned(jitter["turn"], q))
            )
        sensor.camera._cached_local_pose = None
    return True
