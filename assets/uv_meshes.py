"""Unit box and cylinder meshes with texture coordinates, for textured parts.

SAPIEN's cylinder primitive carries no texture coordinates, and its box lays an image out
over its faces in its own way, so a textured box or cylinder is drawn from these meshes,
scaled to the part: the box spans [-1, 1] on each axis (scaled by its half extents), the
cylinder runs along x from -1 to 1 with radius 1 (scaled by half length, radius, radius),
as SAPIEN's primitives do. Every face of the box shows the whole image upright (the sides
with the image's top up, the top and bottom with it along y); the cylinder's side wraps
the image once around, its top towards +x, and its ends show the image's inscribed disc.

The files ship with the package; ``instructmove assets build`` writes them again
(``write_meshes``; a test checks that the shipped ones are what this module writes).
"""

from __future__ import annotations

import math
from importlib import resources
from pathlib import Path

SEGMENTS = 48
SHAPES = ("box", "cylinder")


def _obj(vertices, uvs, normals, faces) -> str:
    """OBJ text; ``faces`` are triangles of (vertex, uv, normal) index triples, 0-based."""
    lines = [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in vertices]
    lines += [f"vt {u:.6f} {v:.6f}" for u, v in uvs]
    lines += [f"vn {x:.6f} {y:.6f} {z:.6f}" for x, y, z in normals]
    lines += ["f " + " ".join(f"{a + 1}/{b + 1}/{c + 1}" for a, b, c in tri) for tri in faces]
    return "\n".join(lines) + "\n"


def _quads(quads) -> str:
    """OBJ text of quads given as (four corners counter-clockwise from outside, their
    (u, v), normal)."""
    vertices, uvs, normals, faces = [], [], [], []
    for corners, coords, normal in quads:
        base = len(vertices)
        vertices += corners
        uvs += coords
        normals.append(normal)
        n = len(normals) - 1
        idx = [(base + k, base + k, n) for k in range(4)]
        faces += [(idx[0], idx[1], idx[2]), (idx[0], idx[2], idx[3])]
    return _obj(vertices, uvs, normals, faces)


def box_obj() -> str:
    """The unit box, each face showing the whole image."""
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    quads = []
    # sides: (outward axis, right-hand direction seen from outside)
    for normal, right in (
        ((1, 0, 0), (0, 1, 0)),
        ((0, 1, 0), (-1, 0, 0)),
        ((-1, 0, 0), (0, -1, 0)),
        ((0, -1, 0), (1, 0, 0)),
    ):
        corners = [
            tuple(n + r * sx for n, r in zip(normal, right, strict=True))[:2] + (sz,)
            for sx, sz in ((-1, -1), (1, -1), (1, 1), (-1, 1))
        ]
        quads.append((corners, square, normal))
    quads.append(([(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)], square, (0, 0, 1)))
    quads.append(([(-1, 1, -1), (1, 1, -1), (1, -1, -1), (-1, -1, -1)], square, (0, 0, -1)))
    return _quads(quads)


def cylinder_obj(segments: int = SEGMENTS) -> str:
    """The unit cylinder along x: its side wraps the image around once, its ends show the
    image's inscribed disc."""
    vertices, uvs, normals, faces = [], [], [], []
    for k in range(segments + 1):  # the seam is doubled so the image closes around
        a = 2 * math.pi * k / segments
        y, z = math.cos(a), math.sin(a)
        for x in (-1.0, 1.0):
            vertices.append((x, y, z))
            uvs.append((k / segments, (x + 1) / 2))
        normals.append((0.0, y, z))
    for k in range(segments):
        lo0, hi0, lo1, hi1 = 2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3
        faces += [
            ((lo0, lo0, k), (lo1, lo1, k + 1), (hi1, hi1, k + 1)),
            ((lo0, lo0, k), (hi1, hi1, k + 1), (hi0, hi0, k)),
        ]
    for x in (-1.0, 1.0):  # the ends
        normals.append((x, 0.0, 0.0))
        n = len(normals) - 1
        center = len(vertices)
        vertices.append((x, 0.0, 0.0))
        uvs.append((0.5, 0.5))
        for k in range(segments):
            a = 2 * math.pi * k / segments
            vertices.append((x, math.cos(a), math.sin(a)))
            uvs.append((0.5 + 0.5 * math.cos(a), 0.5 + 0.5 * math.sin(a) * x))
        for k in range(segments):
            a, b = center + 1 + k, center + 1 + (k + 1) % segments
            tri = ((center, center, n), (a, a, n), (b, b, n))
            faces.append(tri if x > 0 else (tri[0], tri[2], tri[1]))
    return _obj(vertices, uvs, normals, faces)


WRITERS = {"box": box_obj, "cylinder": cylinder_obj}


def aspect(shape: str, size: tuple[float, ...]) -> float:
    """Width over height of the surface an image covers on a part of ``shape`` and
    ``size``, rounded to a hundredth: a box's largest face, a cylinder's side (its ends
    where it is a disc, no longer than its radius)."""
    if shape == "box":
        x, y, z = size
        faces = {y * z: y / z, x * z: x / z, x * y: x / y}  # area -> width / height
        return round(faces[max(faces)], 2)
    radius, half = size
    return 1.0 if 2 * half <= radius else round(math.pi * radius / half, 2)


def mesh_path(shape: str) -> Path:
    """The shipped file of the textured unit ``shape``."""
    folder = resources.files("instructmove_ms.assets").joinpath("meshes")
    return Path(str(folder)) / f"uv_{shape}.obj"


def write_meshes() -> list[Path]:
    """Write every shipped mesh file (atomically); returns their paths."""
    from ..files import write_text

    return [write_text(mesh_path(shape), WRITERS[shape]()) for shape in SHAPES]
