"""Turning a printed part so its words face the reader (nothing about its shape changes)."""

from __future__ import annotations

import dataclasses
import math

from ..parts import IDENTITY, Part, axis_angle_quat

#: The quarter turn about z that reads a box's top from the front (+x).
QUARTER = axis_angle_quat((0.0, 0.0, 1.0), math.pi / 2)


def top_to_front(part: Part) -> Part:
    """An unturned box whose largest face is its top, given a quarter turn about z with its
    half extents swapped (the same box, the same bounds), so the image on its top reads
    from the front; any other part unchanged."""
    if part.shape != "box" or part.quat != IDENTITY:
        return part
    x, y, z = part.size
    if x * y <= max(x * z, y * z):
        return part
    return dataclasses.replace(part, size=(y, x, z), quat=QUARTER)
