"""Registry of category generators."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..design import Design, Traits


@dataclass(frozen=True)
class CategoryGenerator:
    """How to build instances of one category, and what holds for all of them."""

    category: str
    build: Callable[[Design], Traits]
    synonyms: tuple[str, ...]  # nouns a person uses for it, most common first
    size: tuple[float, float]  # plausible range of the largest dimension, metres
    graspable: bool = True
    container: bool = False


GENERATORS: dict[str, CategoryGenerator] = {}


def generator(
    category: str,
    *,
    size: tuple[float, float],
    synonyms: tuple[str, ...] = (),
    graspable: bool = True,
    container: bool = False,
):
    """Register ``build`` as the generator of ``category``.

    ``size`` is the category prior on the largest dimension (checked on every instance);
    ``synonyms`` are the nouns people use, most common first (default: the category name);
    a ``container`` generator declares its interior with ``Design.interior``.
    """

    def register(build: Callable[[Design], Traits]) -> Callable[[Design], Traits]:
        if category in GENERATORS:
            raise ValueError(f"category {category!r} has two generators")
        nouns = synonyms or (category.replace("_", " "),)
        GENERATORS[category] = CategoryGenerator(category, build, nouns, size, graspable, container)
        return build

    return register
