"""Procedural generators, one per category; importing this package registers them all."""

from . import desktop, food, household, kitchen  # noqa: F401  (registration)
from .registry import GENERATORS, CategoryGenerator, generator

__all__ = ["GENERATORS", "CategoryGenerator", "generator"]
