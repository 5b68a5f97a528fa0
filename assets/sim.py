"""A bare SAPIEN scene for checking and photographing single instances."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from functools import cache

import numpy as np
import sapien
from mani_skill.envs.utils.system.backend import parse_sim_and_render_backend

from .catalog import Instance
from .sapien_builder import actor_builder, physical_material

TIMESTEP = 1.0 / 120.0


def look_at(eye, target, up=(0.0, 0.0, 1.0)) -> sapien.Pose:
    """SAPIEN camera pose (x forward, y left, z up) at ``eye`` looking at ``target``."""
    forward = np.asarray(target, float) - np.asarray(eye, float)
    forward /= np.linalg.norm(forward)
    left = np.cross(up, forward)
    left /= np.linalg.norm(left)
    mat = np.eye(4)
    mat[:3, :3] = np.stack([forward, left, np.cross(forward, left)], axis=1)
    mat[:3, 3] = eye
    return sapien.Pose(mat)


@cache
def _render_device() -> sapien.Device:
    """The device ManiSkill renders on by default here (SAPIEN renders on one device per
    process, so our own scenes must use the same one)."""
    return parse_sim_and_render_backend("cpu", "gpu").render_device


@contextmanager
def sapien_physics() -> Iterator[None]:
    """SAPIEN's default physics settings for the scenes, bodies and shapes made inside
    (a ManiSkill env sets its own as process-wide defaults), restored afterwards."""
    physx = sapien.physx
    kinds = ("scene", "body", "shape")
    saved = [getattr(physx, f"get_{k}_config")() for k in kinds]
    defaults = (physx.PhysxSceneConfig(), physx.PhysxBodyConfig(), physx.PhysxShapeConfig())
    for kind, config in zip(kinds, defaults, strict=True):
        getattr(physx, f"set_{kind}_config")(config)
    try:
        yield
    finally:
        for kind, config in zip(kinds, saved, strict=True):
            getattr(physx, f"set_{kind}_config")(config)


def bare_scene() -> sapien.Scene:
    """An empty CPU-physics scene (SAPIEN's physics settings) with its render system on
    ManiSkill's device."""
    with sapien_physics():
        system = sapien.physx.PhysxCpuSystem()
    return sapien.Scene([system, sapien.render.RenderSystem(_render_device())])


def add_camera(
    scene: sapien.Scene, name: str, width: int, height: int, fovy: float, near: float, far: float
) -> sapien.render.RenderCameraComponent:
    """A camera of SAPIEN's default shader pack (float colour and segmentation), whatever
    pack an env made before set as the global one (ManiSkill's rgb sensors set "minimal":
    8-bit colour, no segmentation). ManiSkill's sensors set their own pack when made."""
    from mani_skill.render import PREBUILT_SHADER_CONFIGS, set_shader_pack

    set_shader_pack(PREBUILT_SHADER_CONFIGS["default"])
    return scene.add_camera(name, width, height, fovy, near, far)


def table_scene(render: bool = False) -> sapien.Scene:
    """Ground plane as the table top at z = 0 (wood friction), lit when ``render``."""
    scene = bare_scene()
    scene.set_timestep(TIMESTEP)
    scene.add_ground(0.0, render=render, material=physical_material("wood"))
    if render:
        scene.set_ambient_light([0.45, 0.45, 0.45])
        scene.add_directional_light([0.3, 0.5, -1.0], [0.9, 0.9, 0.9], shadow=False)
        scene.add_directional_light([-0.4, -0.3, -0.6], [0.3, 0.3, 0.3], shadow=False)
    return scene


def spawn(
    scene: sapien.Scene, instance: Instance, xy=(0.0, 0.0), yaw: float = 0.0, z: float = 0.002
) -> sapien.Entity:
    builder = actor_builder(scene, instance)
    builder.initial_pose = sapien.Pose(
        [xy[0], xy[1], z], [np.cos(yaw / 2), 0.0, 0.0, np.sin(yaw / 2)]
    )
    with sapien_physics():
        return builder.build(name=instance.uuid)
