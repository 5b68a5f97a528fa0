"""Attribute vocabularies shared by the generators, annotations and instructions."""

from __future__ import annotations

from dataclasses import dataclass

#: Colour names of the shared vocabulary and a base sRGB value for each.
COLORS: dict[str, tuple[float, float, float]] = {
    "red": (0.80, 0.10, 0.10),
    "orange": (0.95, 0.50, 0.10),
    "yellow": (0.95, 0.85, 0.15),
    "green": (0.20, 0.60, 0.20),
    "blue": (0.15, 0.30, 0.80),
    "purple": (0.50, 0.20, 0.65),
    "pink": (0.95, 0.55, 0.70),
    "brown": (0.45, 0.28, 0.12),
    "black": (0.06, 0.06, 0.06),
    "white": (0.93, 0.93, 0.91),
    "gray": (0.50, 0.50, 0.50),
    "silver": (0.75, 0.75, 0.78),
    "golden": (0.85, 0.65, 0.20),
    "beige": (0.90, 0.82, 0.65),
    "transparent": (0.85, 0.92, 0.95),
}

SHAPES: tuple[str, ...] = (
    "sphere",
    "hemisphere",
    "ellipsoid",
    "cylinder",
    "cone",
    "cube",
    "cuboid",
    "disk",
    "ring",
    "L-shape",
    "T-shape",
    "flat",
    "elongated",
    "irregular",
)


@dataclass(frozen=True)
class Material:
    """Physical and visual properties of a material."""

    density: float  # kg/m^3
    friction: float  # static friction; dynamic is 0.9 of it
    metallic: float
    roughness: float
    transmission: float = 0.0


MATERIALS: dict[str, Material] = {
    "plastic": Material(1050.0, 0.5, 0.0, 0.45),
    "metal": Material(7800.0, 0.45, 0.9, 0.3),
    "aluminium": Material(2700.0, 0.45, 0.9, 0.35),
    "wood": Material(650.0, 0.6, 0.0, 0.75),
    "ceramic": Material(2300.0, 0.55, 0.0, 0.25),
    "glass": Material(2500.0, 0.45, 0.0, 0.05, transmission=0.7),
    "fabric": Material(300.0, 0.8, 0.0, 0.95),
    "rubber": Material(1200.0, 1.0, 0.0, 0.8),
    "paper": Material(700.0, 0.55, 0.0, 0.9),
    "silicone": Material(1100.0, 0.9, 0.0, 0.6),
    "leather": Material(900.0, 0.7, 0.0, 0.7),
    "stone": Material(2600.0, 0.6, 0.0, 0.8),
    "organic": Material(950.0, 0.6, 0.0, 0.6),
    "foam": Material(60.0, 0.9, 0.0, 0.95),
    "wicker": Material(400.0, 0.7, 0.0, 0.9),
}

#: Material names as the shared vocabulary says them ("aluminium" and "foam" are kinds of
#: metal and fabric there).
MATERIAL_WORD: dict[str, str] = {"aluminium": "metal", "foam": "fabric"}


def material_word(material: str) -> str:
    return MATERIAL_WORD.get(material, material)
