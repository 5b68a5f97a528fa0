"""Turn catalog instances into SAPIEN actors (visual and collision from the same parts)."""

from __future__ import annotations

from functools import cache
from importlib import resources

import numpy as np
import sapien
import sapien.physx as physx
import sapien.render as render

from .catalog import Instance, plain
from .parts import Part
from .textures import Texture, image
from .uv_meshes import aspect, mesh_path
from .vocab import MATERIALS


@cache
def _unit_sphere_mesh() -> str:
    return str(resources.files("instructmove_ms.assets").joinpath("meshes/icosphere.obj"))


@cache
def physical_material(name: str) -> physx.PhysxMaterial:
    mu = MATERIALS[name].friction
    return physx.PhysxMaterial(static_friction=mu, dynamic_friction=0.9 * mu, restitution=0.0)


@cache
def _texture(
    texture: Texture, rgb: tuple[float, float, float], aspect: float
) -> render.RenderTexture2D:
    """The texture's image on colour ``rgb``, in linear storage (``srgb=False``) as the
    plain parts' base colours are read, so a printed part's ground renders as a plain
    part of its colour does."""
    pixels = np.array(image(texture, rgb, aspect))
    return render.RenderTexture2D(pixels, "R8G8B8A8Unorm", srgb=False)


def render_material(part: Part) -> render.RenderMaterial:
    m = MATERIALS[part.material]
    alpha = 1.0 - 0.6 * m.transmission
    material = render.RenderMaterial(
        base_color=[*part.rgb, alpha],
        metallic=m.metallic,
        roughness=m.roughness,
        specular=0.5,
    )
    if part.texture is not None:
        material.base_color = [1.0, 1.0, 1.0, alpha]
        shape = aspect(part.shape, part.size)
        material.base_color_texture = _texture(part.texture, part.rgb, shape)
    return material


def _add_visual(builder: sapien.ActorBuilder, part: Part, pose: sapien.Pose) -> None:
    mat = render_material(part)
    s = part.size
    if part.texture is not None:  # a box or a cylinder: the unit mesh with UVs, scaled
        scale = list(s) if part.shape == "box" else [s[1], s[0], s[0]]
        builder.add_visual_from_file(str(mesh_path(part.shape)), pose, scale=scale, material=mat)
    elif part.shape == "box":
        builder.add_box_visual(pose, half_size=s, material=mat)
    elif part.shape == "sphere":
        builder.add_sphere_visual(pose, radius=s[0], material=mat)
    elif part.shape == "cylinder":
        builder.add_cylinder_visual(pose, radius=s[0], half_length=s[1], material=mat)
    elif part.shape == "capsule":
        builder.add_capsule_visual(pose, radius=s[0], half_length=s[1], material=mat)
    elif part.shape == "mesh":
        builder.add_visual_from_file(part.mesh, pose, material=mat)
    else:
        builder.add_visual_from_file(_unit_sphere_mesh(), pose, scale=s, material=mat)


def add_part(builder: sapien.ActorBuilder, part: Part) -> None:
    """Add one part's visual and (unless decorative) collision shape to ``builder``."""
    pose = sapien.Pose(p=list(part.pos), q=list(part.quat))
    _add_visual(builder, part, pose)
    s = part.size
    if part.visual_only:
        return
    kw = dict(material=physical_material(part.material), density=part.density)
    if part.shape == "box":
        builder.add_box_collision(pose, half_size=s, **kw)
    elif part.shape == "sphere":
        builder.add_sphere_collision(pose, radius=s[0], **kw)
    elif part.shape == "cylinder":
        builder.add_cylinder_collision(pose, radius=s[0], half_length=s[1], **kw)
    elif part.shape == "capsule":
        builder.add_capsule_collision(pose, radius=s[0], half_length=s[1], **kw)
    elif part.shape == "mesh":
        builder.add_convex_collision_from_file(part.mesh, pose, **kw)
    else:
        builder.add_convex_collision_from_file(_unit_sphere_mesh(), pose, scale=s, **kw)


def actor_builder(scene, instance: Instance) -> sapien.ActorBuilder:
    """A dynamic-actor builder holding every part of ``instance``; its textures only where
    ``scene`` renders (a texture made without a renderer starts one on SAPIEN's default
    device, and a rendering env made later in the process could not start its own)."""
    renders = getattr(scene, "can_render", lambda: True)()  # our bare scenes always render
    builder = scene.create_actor_builder()
    for part in instance.parts if renders else plain(instance).parts:
        add_part(builder, part)
    return builder
