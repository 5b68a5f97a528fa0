"""A small vocabulary for composing objects from convex parts with seeded variation."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .parts import (
    IDENTITY,
    X_TO_Y,
    X_TO_Z,
    Part,
    Region,
    axis_angle_quat,
    quat_mul,
    rest_offset,
    shifted,
)
from .vocab import COLORS


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
    ):
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
