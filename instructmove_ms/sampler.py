"""Seeded role sampling: which instances of a snapshot play which role in an episode.

Roles are declared with constraints (match or differ on category, super_category, colour,
shape, material, size, name, extent or look, against another role or among the role's own
members) and capability tags. Each slot takes, among the instances that satisfy every
constraint, the one with the lowest hash of (seed, role, slot, uuid): rendezvous hashing,
so the draw depends only on the seed and on which instances qualify, never on their order
in the catalog.

Two samplers are kept (``SAMPLERS``). Sampler 1 (InstructMove 1.0) draws the target from the
split's partition and its rivals from the seen one, with the held-out instances of
``catalog.Instance.held_out`` (about one in five). Sampler 2 (symmetric) draws the
candidate group as one role, every member from the split's partition, with
``HELD_OUT_PER_CATEGORY`` instances of each category held out (``symmetric`` merges a goal
role with its rivals; the composer then picks the goal among the group).
"""

from __future__ import annotations

import dataclasses
import hashlib
from dataclasses import dataclass
from functools import lru_cache

from .assets.catalog import Catalog, Instance, is_held_out_category, stable_hash
from .splits import SPLITS
from .validation import check_choice

ATTRIBUTES = (
    "category",
    "super_category",
    "color",
    "shape",
    "material",
    "size",
    "name",
    "extent",
    "look",
)
RELATIONS = ("match", "differ", "smaller", "larger")
#: "smaller" / "larger" on "extent" (the largest dimension) need this ratio, so that a person
#: sees the difference at a glance.
EXTENT_RATIO = 1.3
#: A stick: its longest side this many times its middle one, the middle one at most
#: ``STICK_WIDTH`` metres (a pen, a knife, a toothbrush). Two sticks sharing a colour whose
#: lengths lie within ``STICK_RATIO`` read as one another at the cameras' resolution.
STICK_ASPECT = 4.0
STICK_WIDTH = 0.03
STICK_RATIO = 1.5
TAGS = ("graspable", "container")
EACH_OTHER = "each_other"
POOLS = ("target", "distractor", "any")
#: The samplers an episode may come from: 1 is InstructMove 1.0's, 2 the symmetric one.
SAMPLERS = (1, 2)
#: The envs' default: the sampler of the current benchmark's stored sets (InstructMove
#: 2.0's), so that training scenes hold out what those sets test (a test checks the two
#: agree).
SAMPLER = 2
#: Sampler 2 holds out this many instances of each seen category for unseen_instance (those
#: of lowest hash): PickAttribute needs three of one category, PickSpatial two.
HELD_OUT_PER_CATEGORY = 4


@dataclass(frozen=True)
class Constraint:
    """``attribute`` must ``relation`` ("match" or "differ") that of role ``other``
    (or of the role's other members when ``other`` is "each_other"); "smaller", "larger"
    and "differ" on "extent" ask for ``EXTENT_RATIO`` between the largest dimensions;
    "differ" on "look" asks that no two be ``lookalike``."""

    attribute: str
    relation: str
    other: str

    def __post_init__(self) -> None:
        check_choice("constraint attribute", self.attribute, ATTRIBUTES)
        check_choice("constraint relation", self.relation, RELATIONS)
        if self.relation in ("smaller", "larger") and self.attribute != "extent":
            raise ValueError("'smaller' and 'larger' compare the 'extent' attribute only")
        if self.attribute == "extent" and self.relation == "match":
            raise ValueError("'extent' takes 'smaller', 'larger' or 'differ'")
        if self.attribute == "look" and self.relation != "differ":
            raise ValueError("'look' takes 'differ' only")

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


@lru_cache(maxsize=16)
def partition(catalog: Catalog, sampler: int = SAMPLER) -> dict[str, str]:
    """uuid -> the split ``catalog``'s instance belongs to under ``sampler``: seen,
    unseen_instance or unseen_category. Held-out categories are the same for both samplers;
    sampler 1 held out the instances of ``Instance.held_out``, sampler 2 the
    ``HELD_OUT_PER_CATEGORY`` of lowest hash in each category."""
    check_choice("sampler", sampler, SAMPLERS)
    out = {}
    for category in catalog.categories:
        members = catalog.of_category(category)
        if is_held_out_category(category):
            out.update((i.uuid, "unseen_category") for i in members)
            continue
        ranked = sorted(members, key=lambda i: stable_hash(f"instance/{i.uuid}"))
        held = (
            {i.uuid for i in members if i.held_out}
            if sampler == 1
            else {i.uuid for i in ranked[:HELD_OUT_PER_CATEGORY]}
        )
        out.update((i.uuid, "unseen_instance" if i.uuid in held else "seen") for i in members)
    return out


def split_of(inst: Instance, catalog: Catalog, sampler: int = SAMPLER) -> str:
    """The partition ``inst`` of ``catalog`` belongs to under ``sampler``."""
    return partition(catalog, sampler)[inst.uuid]


def split_pools(
    catalog: Catalog, split: str, sampler: int = SAMPLER
) -> tuple[list[Instance], list[Instance]]:
    """(the split's partition, the seen partition) of ``catalog`` under ``sampler``.

    train / seen: seen instances (seen differs from train by its held-out episode seeds).
    unseen_instance / unseen_category: that partition. Sampler 1 drew the target from the
    first and its rivals from the second; sampler 2 draws every candidate from the first.
    """
    check_choice("split", split, SPLITS)
    parts = partition(catalog, sampler)
    seen = [i for i in catalog.instances if parts[i.uuid] == "seen"]
    if split in ("train", "seen"):
        return seen, seen
    return [i for i in catalog.instances if parts[i.uuid] == split], seen


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


def _stick(inst: Instance) -> bool:
    longest, middle, _ = sorted(inst.dims, reverse=True)
    return longest >= STICK_ASPECT * middle and middle <= STICK_WIDTH


def lookalike(a: Instance, b: Instance) -> bool:
    """True if ``a`` and ``b`` could pass for one another in a camera image: two sticks of
    a shared colour and lengths within ``STICK_RATIO`` (a red marker, a red-handled knife),
    or two things of one shape and main colour, their extents within ``EXTENT_RATIO`` (a
    red tomato, a red apple)."""
    longer, shorter = sorted((max(a.dims), max(b.dims)), reverse=True)
    if _stick(a) and _stick(b):
        return longer < STICK_RATIO * shorter and bool(set(a.colors) & set(b.colors))
    same_look = a.shape == b.shape and a.colors[0] == b.colors[0]
    return same_look and longer < EXTENT_RATIO * shorter


def _satisfies(inst: Instance, c: Constraint, others: list[Instance]) -> bool:
    if c.attribute == "look":
        return not any(lookalike(inst, o) for o in others)
    if c.attribute == "extent":  # mine must be smaller (larger, either) than every other's
        mine = max(inst.dims)

        def apart(other: Instance) -> bool:
            larger = mine >= EXTENT_RATIO * max(other.dims)
            smaller = not mine >= (1.0 / EXTENT_RATIO) * max(other.dims)
            return {"larger": larger, "smaller": smaller, "differ": larger or smaller}[c.relation]

        return all(apart(o) for o in others)
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


def _pools(catalog: Catalog, split: str, sampler: int) -> dict[str, list[Instance]]:
    targets, seen = split_pools(catalog, split, sampler)
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
    roles: tuple[RoleSpec, ...],
    catalog: Catalog,
    split: str,
    seed: int | str,
    sampler: int = SAMPLER,
) -> dict[str, list[Instance]]:
    """Assign instances to every role, in order, from ``sampler``'s partition of ``split``;
    the same inputs give the same assignment."""
    pools = _pools(catalog, split, sampler)
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
    sampler: int = SAMPLER,
) -> list[Instance]:
    """``count`` more members of ``role`` for a scene already cast as ``assigned``, under
    the role's constraints (a ``RoleError`` where none qualifies)."""
    used = {i.uuid for group in assigned.values() for i in group}
    pools = _pools(catalog, split, sampler)
    pool = [i for i in pools[role.pool] if _fits(i, role) and i.uuid not in used]
    members = assigned.get(role.name, [])
    where = f"snapshot {catalog.name!r}, split {split!r}"
    slots = range(len(members), len(members) + count)
    return _fill(role, pool, assigned, members, slots, seed, where)[len(members) :]


def symmetric(roles: tuple[RoleSpec, ...], goal: str, rival: str) -> tuple[RoleSpec, ...]:
    """``roles`` with role ``rival`` folded into role ``goal``: one group of both counts,
    drawn from ``goal``'s pool, whose members satisfy ``goal``'s constraints and, towards
    each other, what ``rival``'s asked towards ``goal`` ("differ from the target" becomes
    "differ from each other"; "smaller than the target" becomes "differ in size"). Members
    that differ in category must not look alike either (``lookalike``): the instruction
    names a category, and a lookalike would answer to it in the image. Sampler 2 casts a
    goal and its rivals so, then picks the goal among the group. Unchanged where ``roles``
    has no ``rival``."""
    by_name = {r.name: r for r in roles}
    if rival not in by_name:
        return roles
    first, second = by_name[goal], by_name[rival]
    if (first.require, first.max_footprint, first.min_interior) != (
        second.require,
        second.max_footprint,
        second.min_interior,
    ):
        raise ValueError(f"roles {goal!r} and {rival!r} ask different things of an instance")

    def mutual(c: Constraint) -> Constraint:
        if c.other != goal:
            return c
        relation = "differ" if c.relation in ("smaller", "larger") else c.relation
        return Constraint(c.attribute, relation, EACH_OTHER)

    constraints = first.constraints + tuple(map(mutual, second.constraints))
    if Constraint("category", "differ", EACH_OTHER) in constraints:
        constraints += (Constraint("look", "differ", EACH_OTHER),)
    constraints = tuple(dict.fromkeys(constraints))
    group = dataclasses.replace(first, count=first.count + second.count, constraints=constraints)
    return tuple(group if r.name == goal else r for r in roles if r.name != rival)
