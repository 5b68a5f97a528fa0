"""Registry of category generators, and their revisions.

Every category has one build, registered by ``generator`` with the library revision it came
in (``revision``, 1 unless the category was rebuilt before the 1.0 release). The revision is
part of each instance's identity (``catalog.instance_uuid``). A later library revision
rebuilds a category with ``revised``, on top of its newest build. A snapshot records the
library revision it was frozen at, and ``generator_at`` builds each category with its newest
build at or before it, so a snapshot keeps regenerating its instances exactly. The builds
only snapshots before revision 3 used left the package at 1.0 (commit ee264ad keeps them):
at an older library revision, a category whose build came later has none.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

from ..design import Design, Traits

#: The newest library revision (what ``assets build`` freezes unless told otherwise).
LIBRARY = 3


@dataclass(frozen=True)
class CategoryGenerator:
    """How to build instances of one category, and what holds for all of them."""

    category: str
    build: Callable[[Design], Traits]
    synonyms: tuple[str, ...]  # nouns a person uses for it, most common first
    size: tuple[float, float]  # plausible range of the largest dimension, metres
    graspable: bool = True
    container: bool = False
    revision: int = 1  # the library revision this build came in


#: The newest build of every category.
GENERATORS: dict[str, CategoryGenerator] = {}
#: Every build of every category, by the library revision it came in.
REVISIONS: dict[str, dict[int, CategoryGenerator]] = {}


def generator(
    category: str,
    *,
    size: tuple[float, float],
    synonyms: tuple[str, ...] = (),
    graspable: bool = True,
    container: bool = False,
    revision: int = 1,
):
    """Register ``build`` as the generator of ``category``: its first build, which came in
    library ``revision``.

    ``size`` is the category prior on the largest dimension (checked on every instance);
    ``synonyms`` are the nouns people use, most common first (default: the category name);
    a ``container`` generator declares its interior with ``Design.interior``.
    """
    if not 1 <= revision <= LIBRARY:
        raise ValueError(f"{category}: a build's revision is in 1..{LIBRARY}, got {revision}")

    def register(build: Callable[[Design], Traits]) -> Callable[[Design], Traits]:
        if category in GENERATORS:
            raise ValueError(f"category {category!r} has two generators")
        nouns = synonyms or (category.replace("_", " "),)
        _add(CategoryGenerator(category, build, nouns, size, graspable, container, revision))
        return build

    return register


def revised(category: str, revision: int):
    """Register ``build`` as the generator of ``category`` from library ``revision`` on: the
    same thing (nouns, size prior, kind) built better, on top of its newest build. Earlier
    revisions keep their build."""
    if not 2 <= revision <= LIBRARY:
        raise ValueError(f"{category}: a revision is numbered 2..{LIBRARY}, got {revision}")

    def register(build: Callable[[Design], Traits]) -> Callable[[Design], Traits]:
        if category not in GENERATORS:
            raise ValueError(f"cannot revise {category!r}: it has no generator yet")
        if revision in REVISIONS[category]:
            raise ValueError(f"category {category!r} has two builds at revision {revision}")
        newest = GENERATORS[category].revision
        if revision < newest:
            raise ValueError(
                f"cannot revise {category!r} at revision {revision}: its newest build came in "
                f"revision {newest}"
            )
        _add(dataclasses.replace(GENERATORS[category], build=build, revision=revision))
        return build

    return register


def _add(gen: CategoryGenerator) -> None:
    builds = REVISIONS.setdefault(gen.category, {})
    builds[gen.revision] = gen
    GENERATORS[gen.category] = builds[max(builds)]


def generator_at(category: str, library: int) -> CategoryGenerator:
    """The build of ``category`` that library revision ``library`` uses (its newest build at
    or before it); a ``ValueError`` where its first build came later."""
    if not 1 <= library <= LIBRARY:
        raise ValueError(f"library revision {library} is not in 1..{LIBRARY}")
    builds = REVISIONS[category]
    before = [r for r in builds if r <= library]
    if not before:
        which = "first build" if len(builds) > 1 else "build"
        raise ValueError(
            f"{category} has no build at library revision {library}: its {which} came in "
            f"revision {min(builds)}; snapshots before revision 3 left the package at 1.0, "
            "git checkout ee264ad for them"
        )
    return builds[max(before)]
