"""Objects as unions of convex primitive parts: geometry, volume and bounds by construction."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .textures import Texture
from .vocab import COLORS, MATERIALS

#: shape -> number of size parameters. Cylinders and capsules run along the local x axis
#: (SAPIEN's convention); ``size`` is (radius, half_length). Boxes: half extents.
#: Ellipsoids: semi-axes (convex hull of a scaled unit icosphere). Meshes (imported assets):
#: half extents of the piece, whose OBJ file ``mesh`` is centred on ``pos``.
PRIMITIVES: dict[str, int] = {
    "box": 3,
    "sphere": 1,
    "cylinder": 2,
    "capsule": 2,
    "ellipsoid": 3,
    "mesh": 3,
}

#: The shapes a texture can go on (they have texture coordinates: see ``uv_meshes``).
TEXTURED_SHAPES = ("box", "cylinder")


@dataclass(frozen=True)
class Part:
    """One convex piece of an object, in the object's frame (z up, resting on z = 0)."""

    name: str
    shape: str
    size: tuple[float, ...]
    pos: tuple[float, float, float]
    quat: tuple[float, float, float, float]  # w, x, y, z
    material: str
    color: str
    rgb: tuple[float, float, float]
    solid_fraction: float = 1.0  # < 1 for hollow or filled parts (a can, a bottle)
    visual_only: bool = False  # decoration (a label, a print): no collision, no mass
    mesh: str = ""  # OBJ file of a "mesh" part
    mesh_volume: float = 0.0  # volume of a "mesh" part's convex piece
    texture: Texture | None = None  # print or pattern on a box or cylinder (a look only)

    def __post_init__(self) -> None:
        if self.shape not in PRIMITIVES:
            raise ValueError(f"unknown part shape {self.shape!r}; allowed: {sorted(PRIMITIVES)}")
        if len(self.size) != PRIMITIVES[self.shape] or min(self.size) <= 0:
            raise ValueError(f"part {self.name!r}: bad size {self.size} for a {self.shape}")
        if self.material not in MATERIALS:
            raise ValueError(f"unknown material {self.material!r}; allowed: {sorted(MATERIALS)}")
        if self.color not in COLORS:
            raise ValueError(f"unknown colour {self.color!r}; allowed: {sorted(COLORS)}")
        if (self.shape == "mesh") != bool(self.mesh):
            raise ValueError(f"part {self.name!r}: a mesh file goes with the 'mesh' shape only")
        if self.texture is not None and self.shape not in TEXTURED_SHAPES:
            raise ValueError(
                f"part {self.name!r}: a {self.shape} carries no texture; "
                f"allowed: {list(TEXTURED_SHAPES)}"
            )

    @property
    def volume(self) -> float:
        s = self.size
        if self.shape == "box":
            return 8.0 * s[0] * s[1] * s[2]
        if self.shape == "sphere":
            return 4.0 / 3.0 * math.pi * s[0] ** 3
        if self.shape == "cylinder":
            return math.pi * s[0] ** 2 * 2.0 * s[1]
        if self.shape == "capsule":
            return math.pi * s[0] ** 2 * 2.0 * s[1] + 4.0 / 3.0 * math.pi * s[0] ** 3
        if self.shape == "mesh":
            return self.mesh_volume
        return 4.0 / 3.0 * math.pi * s[0] * s[1] * s[2]

    @property
    def area(self) -> float:
        """Surface area (m^2); an ellipsoid's or a mesh's by Thomsen's formula over its
        half extents (within about 1%)."""
        s = self.size
        if self.shape == "box":
            return 8.0 * (s[0] * s[1] + s[1] * s[2] + s[0] * s[2])
        if self.shape == "sphere":
            return 4.0 * math.pi * s[0] ** 2
        if self.shape == "cylinder":
            return 4.0 * math.pi * s[0] * s[1] + 2.0 * math.pi * s[0] ** 2
        if self.shape == "capsule":
            return 4.0 * math.pi * s[0] * s[1] + 4.0 * math.pi * s[0] ** 2
        a, b, c = (float(v) for v in self.local_half_extents())
        p = 1.6075
        return 4.0 * math.pi * (((a * b) ** p + (a * c) ** p + (b * c) ** p) / 3.0) ** (1.0 / p)

    @property
    def density(self) -> float:
        return MATERIALS[self.material].density * self.solid_fraction

    @property
    def mass(self) -> float:
        return 0.0 if self.visual_only else self.volume * self.density

    def local_half_extents(self) -> np.ndarray:
        """Half extents of the part's own axis-aligned box, before its pose."""
        s = self.size
        if self.shape in ("box", "ellipsoid", "mesh"):
            return np.array(s, dtype=float)
        if self.shape == "sphere":
            return np.full(3, s[0])
        if self.shape == "cylinder":
            return np.array([s[1], s[0], s[0]])
        return np.array([s[1] + s[0], s[0], s[0]])

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned (min, max) corners in the object frame."""
        he = self.local_half_extents()
        rot = quat_to_matrix(self.quat)
        radius = np.abs(rot) @ he
        center = np.asarray(self.pos, dtype=float)
        return center - radius, center + radius


def quat_to_matrix(q: tuple[float, float, float, float]) -> np.ndarray:
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def axis_angle_quat(axis: tuple[float, float, float], angle: float) -> tuple[float, ...]:
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    s = math.sin(angle / 2.0)
    return (math.cos(angle / 2.0), a[0] * s, a[1] * s, a[2] * s)


def quat_mul(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


IDENTITY: tuple[float, float, float, float] = (1.0, 0.0, 0.0, 0.0)
#: Rotations that turn SAPIEN's x-aligned cylinders and capsules upright or sideways.
X_TO_Z = axis_angle_quat((0.0, 1.0, 0.0), -math.pi / 2)
X_TO_Y = axis_angle_quat((0.0, 0.0, 1.0), math.pi / 2)


def union_bounds(parts: list[Part]) -> tuple[np.ndarray, np.ndarray]:
    lows, highs = zip(*(p.bounds() for p in parts), strict=True)
    return np.min(lows, axis=0), np.max(highs, axis=0)


@dataclass(frozen=True)
class Region:
    """A box in the object frame where things can be placed: a container's interior."""

    center: tuple[float, float, float]  # centre of the floor
    half: tuple[float, float]  # half extents in x and y
    height: float  # from the floor up to the rim

    def shifted(self, offset: np.ndarray) -> Region:
        return Region(
            tuple(float(v) for v in np.asarray(self.center) + offset), self.half, self.height
        )


def rest_offset(parts: list[Part]) -> np.ndarray:
    """The shift that puts the lowest point at z = 0 and centres the object in xy."""
    lo, hi = union_bounds(parts)
    return np.array([-(lo[0] + hi[0]) / 2, -(lo[1] + hi[1]) / 2, -lo[2]])


def shifted(parts: list[Part], offset: np.ndarray) -> list[Part]:
    return [
        Part(**{**p.__dict__, "pos": tuple(float(v) for v in np.asarray(p.pos) + offset)})
        for p in parts
    ]
