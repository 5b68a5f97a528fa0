"""Procedural generators, one per category; importing this package registers them all."""

from . import (  # noqa: F401  (registration)
    bathroom,
    bedroom,
    desktop,
    electronics,
    food,
    groceries,
    household,
    kitchen,
    kitchenware,
    livingroom,
    receptacles,
    stationery,
    tools,
)
from .registry import (
    GENERATORS,
    LIBRARY,
    REVISIONS,
    CategoryGenerator,
    generator,
    generator_at,
    revised,
)

__all__ = [
    "GENERATORS",
    "LIBRARY",
    "REVISIONS",
    "CategoryGenerator",
    "generator",
    "generator_at",
    "revised",
]
