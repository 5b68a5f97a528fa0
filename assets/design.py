"""A small vocabulary for composing objects from convex parts with seeded variation."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .parts import (
    IDENTITY,
    TEXTURED_SHAPES,
    X_TO_Y,
    X_TO_Z,
    Part,
    Region,
    axis_angle_quat,
    quat_mul,
    rest_offset,
    shifted,
)
from .textures import Texture
from .vocab import COLORS

Point = tuple[float, float, float]
#: What a material shows of itself on box and cylinder parts that print nothing else.
MATERIAL_TEXTURES = {"wood": Texture("grain"), "fabric": Texture("weave")}


@dataclass(frozen=True)
class Traits:
    """What a generator states about the instance it built (exact by construction)."""

    colors: tuple[str, ...]  # at most two dominant colours
    material: str
    shape: str


class Design:
    """Collects the parts of one instance. ``rng`` drives every random choice."""

    def __init__(self, rng: np.random.Generator) -> None:
        self.rng = rng
        self.parts: list[Part] = []
        self._shades: dict[str, tuple[float, float, float]] = {}
        self._interior: Region | None = None

    # random helpers ------------------------------------------------------------------
    def uniform(self, low: float, high: float) -> float:
        return float(self.rng.uniform(low, high))

    def choice(self, options):
        return options[int(self.rng.integers(len(options)))]

    def shade(self, color: str) -> tuple[float, float, float]:
        """One slightly varied shade per colour name and instance."""
        if color not in self._shades:
            base = np.asarray(COLORS[color])
            jitter = 1.0 + self.rng.uniform(-0.08, 0.08)
            self._shades[color] = tuple(float(v) for v in np.clip(base * jitter, 0.0, 1.0))
        return self._shades[color]

    # primitives ----------------------------------------------------------------------
    def add(
        self,
        name,
        shape,
        size,
        pos,
        material,
        color,
        quat=IDENTITY,
        solid_fraction=1.0,
        visual_only=False,
        texture=None,
    ):
        if texture is None and shape in TEXTURED_SHAPES:
            texture = MATERIAL_TEXTURES.get(material)
        self.parts.append(
            Part(
                name=name,
                shape=shape,
                size=tuple(float(s) for s in size),
                pos=tuple(float(p) for p in pos),
                quat=tuple(float(q) for q in quat),
                material=material,
                color=color,
                rgb=self.shade(color),
                solid_fraction=solid_fraction,
                visual_only=visual_only,
                texture=texture,
            )
        )

    def box(self, name, half, pos, material, color, yaw=0.0, **kw):
        quat = axis_angle_quat((0, 0, 1), yaw) if yaw else IDENTITY
        self.add(name, "box", half, pos, material, color, quat=quat, **kw)

    def upright(self, name, radius, height, z0, material, color, xy=(0.0, 0.0), **kw):
        """A vertical cylinder standing on z = z0."""
        pos = (xy[0], xy[1], z0 + height / 2)
        self.add(name, "cylinder", (radius, height / 2), pos, material, color, quat=X_TO_Z, **kw)

    def rod(self, name, radius, length, center, material, color, axis="x", capsule=False, **kw):
        """A horizontal cylinder (or capsule) along x or y."""
        quat = IDENTITY if axis == "x" else X_TO_Y
        shape = "capsule" if capsule else "cylinder"
        half = length / 2 - (radius if capsule else 0.0)
        self.add(name, shape, (radius, max(half, 1e-4)), center, material, color, quat=quat, **kw)

    def ellipsoid(self, name, radii, center, material, color, **kw):
        self.add(name, "ellipsoid", radii, center, material, color, **kw)

    def sphere(self, name, radius, center, material, color, **kw):
        self.add(name, "sphere", (radius,), center, material, color, **kw)

    def wall(self, name, radius, thickness, height, z0, material, color, segments=16, flare=0.0):
        """A ring of boxes: the side of a mug, cup or bowl. ``flare`` tilts it outwards."""
        slant = height / math.cos(flare)
        outer = radius + thickness + math.sin(flare) * slant  # widest ring: close it there
        chord = 2 * outer * math.tan(math.pi / segments) * 1.02
        for k in range(segments):
            a = 2 * math.pi * k / segments
            r = radius + thickness / 2 + math.sin(flare) * slant / 2
            pos = (r * math.cos(a), r * math.sin(a), z0 + height / 2)
            quat = quat_mul(axis_angle_quat((0, 0, 1), a), axis_angle_quat((0, 1, 0), flare))
            self.add(
                f"{name}_{k}",
                "box",
                (thickness / 2, chord / 2, slant / 2),
                pos,
                material,
                color,
                quat=quat,
            )

    # compound parts ------------------------------------------------------------------
    def slab(
        self,
        name: str,
        half: tuple[float, float, float],
        z0: float,
        material: str,
        color: str,
        xy: tuple[float, float] = (0.0, 0.0),
        **kw,
    ) -> None:
        """A box of half extents ``half`` standing on z = z0, centred at ``xy``."""
        self.box(name, half, (xy[0], xy[1], z0 + half[2]), material, color, **kw)

    def segment(
        self,
        name: str,
        shape: str,
        p0: Point,
        p1: Point,
        cross: float | tuple[float, float],
        material: str,
        color: str,
        **kw,
    ) -> None:
        """A box, cylinder, capsule or ellipsoid from ``p0`` to ``p1``, its width horizontal;
        ``cross`` is the radius of a cylinder or capsule, (half width, half height) of a box or
        ellipsoid."""
        dx, dy, dz = (b - a for a, b in zip(p0, p1, strict=True))
        length = math.sqrt(dx * dx + dy * dy + dz * dz)
        quat = quat_mul(
            axis_angle_quat((0, 0, 1), math.atan2(dy, dx)),
            axis_angle_quat((0, 1, 0), -math.atan2(dz, math.hypot(dx, dy))),
        )
        if shape in ("box", "ellipsoid"):
            size = (length / 2, *cross)
        else:
            size = (cross, max(length / 2 - (cross if shape == "capsule" else 0.0), 1e-4))
        center = tuple((a + b) / 2 for a, b in zip(p0, p1, strict=True))
        self.add(name, shape, size, center, material, color, quat=quat, **kw)

    def hex_rod(
        self,
        name: str,
        apothem: float,
        length: float,
        center: Point,
        material: str,
        color: str,
        yaw: float = 0.0,
    ) -> None:
        """A hexagonal prism along x (turned by ``yaw`` about z), a flat face down: three
        overlapping boxes, half filled so that the mass is exact."""
        half = (length / 2, apothem / math.sqrt(3), apothem)
        for k in range(3):
            quat = axis_angle_quat((1, 0, 0), k * math.pi / 3)
            if yaw:
                quat = quat_mul(axis_angle_quat((0, 0, 1), yaw), quat)
            self.add(
                f"{name}_{k}", "box", half, center, material, color, quat=quat, solid_fraction=0.5
            )

    def stadium(
        self,
        name: str,
        half_len: float,
        radius: float,
        z0: float,
        height: float,
        material: str,
        color: str,
        xy: tuple[float, float] = (0.0, 0.0),
        ends: tuple[str, str] = ("end_0", "end_1"),
        end_fill: float | None = None,
        **kw,
    ) -> None:
        """A vertical prism of rounded-rectangle section, long along x, standing on z = z0 at
        ``xy``: a box and two end cylinders ``{name}_{end}``. ``end_fill`` is the solid fraction
        of the cylinders (default: the box's); half the box's counts their overlap only once."""
        self.slab(name, (half_len, radius, height / 2), z0, material, color, xy=xy, **kw)
        end_kw = kw if end_fill is None else {**kw, "solid_fraction": end_fill}
        for end, x in zip(ends, (-half_len, half_len), strict=True):
            end_xy = (xy[0] + x, xy[1])
            self.upright(f"{name}_{end}", radius, height, z0, material, color, xy=end_xy, **end_kw)

    def flat_ring(
        self,
        name: str,
        radius: float,
        width: float,
        thick: float,
        z0: float,
        material: str,
        color: str,
        center: tuple[float, float] = (0.0, 0.0),
        segments: int = 12,
        **kw,
    ) -> None:
        """A ring of boxes lying flat on z = z0 around ``center``: a scissor loop, a shoulder."""
        chord = 2 * (radius + width / 2) * math.tan(math.pi / segments) * 1.02
        for k in range(segments):
            a = 2 * math.pi * k / segments
            pos = (
                center[0] + radius * math.cos(a),
                center[1] + radius * math.sin(a),
                z0 + thick / 2,
            )
            self.box(
                f"{name}_{k}", (width / 2, chord / 2, thick / 2), pos, material, color, yaw=a, **kw
            )

    def frame(
        self,
        name: str,
        half: tuple[float, float],
        width: float,
        z0: float,
        height: float,
        material: str,
        color: str,
        full: str = "x",
        tags: tuple[int, int] = (0, 1),
        **kw,
    ) -> None:
        """Four walls ``width`` thick on the edges of a rectangle of outer half extents ``half``,
        from z0 up: ``{name}_x{tag}`` at -x and +x, ``{name}_y{tag}`` at -y and +y. The ``full``
        pair runs the whole side and comes first in each tag; the other fits between them."""
        hx, hy = half
        zc = z0 + height / 2
        for tag, s in zip(tags, (-1, 1), strict=True):
            x_wall = (
                f"{name}_x{tag}",
                (width / 2, hy if full == "x" else hy - width, height / 2),
                (s * (hx - width / 2), 0.0, zc),
            )
            y_wall = (
                f"{name}_y{tag}",
                (hx - width if full == "x" else hx, width / 2, height / 2),
                (0.0, s * (hy - width / 2), zc),
            )
            for wall, size, pos in (x_wall, y_wall) if full == "x" else (y_wall, x_wall):
                self.box(wall, size, pos, material, color, **kw)

    def open_box(
        self,
        name: str,
        half: tuple[float, float],
        height: float,
        wall: float,
        material: str,
        color: str,
        floor: float | None = None,
        full: str = "x",
        tags: tuple[int, int] = (0, 1),
        **kw,
    ) -> float:
        """A rectangular container standing on z = 0: a floor ``floor`` thick (default ``wall``)
        and the walls ``{name}_wall_*`` of ``frame``; returns the top of the floor."""
        floor = wall if floor is None else floor
        self.slab(f"{name}_floor", (half[0], half[1], floor / 2), 0.0, material, color, **kw)
        self.frame(
            f"{name}_wall", half, wall, floor, height - floor, material, color, full, tags, **kw
        )
        return floor

    def interior(
        self,
        half: tuple[float, float],
        floor_z: float,
        rim_z: float,
        center: tuple[float, float] = (0.0, 0.0),
    ) -> None:
        """Declare the placement region of a container (in the same frame as the parts)."""
        self._interior = Region((center[0], center[1], floor_z), half, rim_z - floor_z)

    def finish(self) -> tuple[list[Part], Region | None]:
        """The parts resting on z = 0, centred in xy, and the interior moved with them."""
        offset = rest_offset(self.parts)
        interior = self._interior.shifted(offset) if self._interior else None
        return shifted(self.parts, offset), interior
