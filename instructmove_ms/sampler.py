"""Seeded role sampling: which instances of a snapshot play which role in an episode.

Roles are declared with constraints (match or differ on category, super_category, colour,
shape, material, size or name, against another role or among the role's own members) and
capability tags. Each slot takes, among the instances that satisfy every constraint, the one
with the lowest hash of (seed, role, slot, uuid): rendezvous hashing, so the draw depends
only on the seed and on which instances qualify, never on their order in the catalog.
"""

from __future__ import annotations

import dataclasses
import hashlib
from dataclasses import dataclass

from .assets.catalog import Catalog, Instance, is_held_out_category
from .splits import SPLITS
from .validation import check_choice

ATTRIBUTES = ("category", "super_category", "color", "shape", "material", "size", "name", "extent")
RELATIONS = ("match", "differ", "smaller", "larger")
#: "smaller" / "larger" on "extent" (the largest dimension) need this ratio, so that a person
#: sees the difference at a glance.
EXTENT_RATIO = 1.3
TAGS = ("graspable", "container")
EACH_OTHER = "each_other"
POOLS = ("target", "distractor", "any")


@dataclass(frozen=True)
class Constraint:
    """``attribute`` must ``relation`` ("match" or "differ") that of role ``other``
    (or of the role's other members when ``other`` is "each_other")."""

    attribute: str
    relation: str
    other: str

    def __post_init__(self) -> None:
        check_choice("constraint attribute", self.attribute, ATTRIBUTES)
        check_choice("constraint relation", self.relation, RELATIONS)
        if (self.relation in ("smaller", "larger")) != (self.attribute == "extent"):
            raise ValueError("'smaller' and 'larger' compare the 'extent' attribute only")

    def __str__(self) -> str:
        return f"{self.attribute} must {self.relation} {self.other}"


@dataclass(frozen=True)
class RoleSpec:
    name: str
    count: int
    pool: str = "distractor"  # "target": the split's pool; "distractor": seen; "any": both
    require: tuple[str, ...] = ("graspable",)
    constraints: tuple[Constraint, ...] = ()
    max_footprint: float | None = None  # largest horizontal extent, metres
    min_interior: float | None = None  # narrowest interior width of a container, metres

    def __post_init__(self) -> None:
        check_choice("role pool", self.pool, POOLS)
        for tag in self.require:
            check_choice("capability tag", tag, TAGS)


def with_constraints(
    roles: tuple[RoleSpec, ...], role: str, *extra: Constraint
) -> tuple[RoleSpec, ...]:
    """``roles`` with ``extra`` constraints added to role ``role``."""
    return tuple(
        dataclasses.replace(r, constraints=r.constraints + extra) if r.name == role else r
        for r in roles
    )


class RoleError(ValueError):
    """No instance satisfies a role's constraints."""


def split_of(inst: Instance) -> str:
    """The partition an instance belongs to: seen, unseen_instance or unseen_category."""
    if is_held_out_category(inst.category):
        return "unseen_category"
    return "unseen_instance" if inst.held_out else "seen"


def split_pools(catalog: Catalog, split: str) -> tuple[list[Instance], list[Instance]]:
    """(target pool, distractor pool) of ``split``.

    train / seen: seen instances (seen differs from train by its held-out episode seeds).
    unseen_instance / unseen_category: targets from that partition. Distractors always come
    from the seen partition.
    """
    check_choice("split", split, SPLITS)
    seen = [i for i in catalog.instances if split_of(i) == "seen"]
    if split in ("train", "seen"):
        return seen, seen
    return [i for i in catalog.instances if split_of(i) == split], seen


def _values(inst: Instance, attribute: str) -> frozenset:
    if attribute == "color":
        return frozenset(inst.colors)
    if attribute == "name":
        return frozenset(inst.nouns)
    return frozenset([getattr(inst, attribute)])


def names_clash(a: frozenset, b: frozenset) -> bool:
    """True if a noun of one is a word sequence inside a noun of the other ("pen" in "marker
    pen"), so that an instruction naming one could mean the other."""

    def inside(x: str, y: str) -> bool:
        return f" {x} " in f" {y} "

    return any(inside(x, y) or inside(y, x) for x in a for y in b)


def _holds(relation: str, attribute: str, mine: frozenset, theirs: frozenset) -> bool:
    if attribute == "name":
        same = names_clash(mine, theirs)
    else:
        same = mine == theirs if relation == "match" else bool(mine & theirs)
    return same if relation == "match" else not same


def _satisfies(inst: Instance, c: Constraint, others: list[Instance]) -> bool:
    if c.attribute == "extent":  # mine must be smaller (larger) than every other's
        ratio = EXTENT_RATIO if c.relation == "larger" else 1.0 / EXTENT_RATIO
        return all(
            (max(inst.dims) >= ratio * max(o.dims)) == (c.relation == "larger") for o in others
        )
    mine = _values(inst, c.attribute)
    return all(_holds(c.relation, c.attribute, mine, _values(o, c.attribute)) for o in others)


def _fits(inst: Instance, role: RoleSpec) -> bool:
    if not all(getattr(inst, f"is_{tag}") for tag in role.require):
        return False
    if role.max_footprint is not None and max(inst.dims[:2]) > role.max_footprint:
        return False
    return role.min_interior is None or (
        inst.interior is not None and 2 * min(inst.interior.half) >= role.min_interior
    )


def rank(seed: int, role: str, slot: int, uuid: str) -> int:
    digest = hashlib.blake2b(f"{seed}:{role}:{slot}:{uuid}".encode(), digest_size=8).digest()
    return int.from_bytes(digest, "little")


def _pools(catalog: Catalog, split: str) -> dict[str, list[Instance]]:
    targets, seen = split_pools(catalog, split)
    known = {i.uuid for i in targets}
    return {
        "target": targets,
        "distractor": seen,
        "any": targets + [i for i in seen if i.uuid not in known],
    }


def _fill(
    role: RoleSpec,
    pool: list[Instance],
    assigned: dict[str, list[Instance]],
    members: list[Instance],
    slots: range,
    seed: int | str,
    where: str,
) -> list[Instance]:
    """``members`` of ``role`` with ``slots`` filled from ``pool``, each by the lowest rank
    among the instances that satisfy every constraint."""
    members = list(members)
    used = {i.uuid for i in members}
    for slot in slots:
        candidates = [i for i in pool if i.uuid not in used]
        for c in role.constraints:
            others = members if c.other == EACH_OTHER else assigned.get(c.other)
            if others is None:
                raise ValueError(f"role {role.name!r} refers to unknown role {c.other!r}")
            candidates = [i for i in candidates if _satisfies(i, c, others)]
            if not candidates:
                raise RoleError(
                    f"role {role.name!r} slot {slot}: no instance satisfies '{c}' in {where} "
                    f"(pool of {len(pool)} with tags {list(role.require)})"
                )
        choice = min(candidates, key=lambda i: rank(seed, role.name, slot, i.uuid))
        members.append(choice)
        used.add(choice.uuid)
    return members


def resolve_roles(
    roles: tuple[RoleSpec, ...], catalog: Catalog, split: str, seed: int
) -> dict[str, list[Instance]]:
    """Assign instances to every role, in order; the same inputs give the same assignment."""
    pools = _pools(catalog, split)
    where = f"snapshot {catalog.name!r}, split {split!r}"
    assigned: dict[str, list[Instance]] = {}
    used: set[str] = set()
    for role in roles:
        pool = [i for i in pools[role.pool] if _fits(i, role) and i.uuid not in used]
        assigned[role.name] = _fill(role, pool, assigned, [], range(role.count), seed, where)
        used.update(i.uuid for i in assigned[role.name])
    return assigned


def more_members(
    role: RoleSpec,
    assigned: dict[str, list[Instance]],
    count: int,
    catalog: Catalog,
    split: str,
    seed: int | str,
) -> list[Instance]:
    """``count`` more members of ``role`` for a scene already cast as ``assigned``, under
    the role's constraints (a ``RoleError`` where none qualifies)."""
    used = {i.uuid for group in assigned.values() for i in group}
    pool = [i for i in _pools(catalog, split)[role.pool] if _fits(i, role) and i.uuid not in used]
    members = assigned.get(role.name, [])
    where = f"snapshot {catalog.name!r}, split {split!r}"
    slots = range(len(members), len(members) + count)
    return _fill(role, pool, assigned, members, slots, seed, where)[len(members) :]
