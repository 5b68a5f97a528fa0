"""The object catalog: generated instances with exact annotations, and their splits."""

from __future__ import annotations

import hashlib
import math
import uuid as uuidlib
from collections.abc import Iterable
from dataclasses import asdict, dataclass, field, replace
from functools import cache, cached_property
from importlib import resources

import numpy as np
import yaml

from .design import Design
from .generators import GENERATORS, LIBRARY, generator_at
from .parts import Part, Region, union_bounds
from .textures import Texture
from .vocab import material_word

#: The snapshot envs and tools load unless told otherwise (``snapshot``).
DEFAULT_SNAPSHOT = "recognisable"

#: Namespace of instance uuids: uuid5(NAMESPACE, "<category>/<index>") never changes.
UUID_NAMESPACE = uuidlib.UUID("6f1c1c9e-3d52-4c55-9c55-6a1e0b1c7a01")
#: About one instance in five is held out for the unseen_instance split, one category in
#: five for unseen_category; both decided by a hash so that growth keeps them stable.
HELD_OUT_MODULUS = 5
#: A receptacle's part that rises this far (m) above its rim off to one side of the
#: opening (a lid standing open, a caddy's back) gives it a back (``Instance.back``).
OVER_RIM = 0.03


@dataclass(frozen=True)
class TaxonomyEntry:
    domain: str
    super_category: str


@cache
def taxonomy() -> dict[str, TaxonomyEntry]:
    """category -> (domain, super_category), from the shipped taxonomy.yaml."""
    text = resources.files("instructmove_ms.assets").joinpath("taxonomy.yaml").read_text()
    tree = yaml.safe_load(text)
    return {
        cat: TaxonomyEntry(domain, sup)
        for domain, supers in tree.items()
        for sup, cats in supers.items()
        for cat in cats
    }


def size_bucket(height: float) -> str:
    return "small" if height < 0.05 else "medium" if height < 0.12 else "large"


def stable_hash(text: str) -> int:
    """A 32-bit hash of ``text``, the same on every machine and Python."""
    return int.from_bytes(hashlib.sha256(text.encode()).digest()[:4], "little")


def _stable_bucket(text: str) -> int:
    return stable_hash(text) % HELD_OUT_MODULUS


def is_held_out_category(category: str) -> bool:
    return _stable_bucket(f"category/{category}") == 0


@dataclass(frozen=True)
class Instance:
    """One generated object with its annotations (exact: derived from its own parts)."""

    uuid: str
    category: str
    index: int
    domain: str
    super_category: str
    parts: tuple[Part, ...] = field(repr=False)
    colors: tuple[str, ...]
    material: str
    shape: str
    nouns: tuple[str, ...]
    is_graspable: bool
    is_container: bool
    interior: Region | None = None  # placement region of a container

    @cached_property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(lowest, highest) corner of the instance's box in its frame (do not modify)."""
        return union_bounds(list(self.parts))

    @cached_property
    def dims(self) -> tuple[float, float, float]:
        lo, hi = self.bounds
        return tuple(float(v) for v in hi - lo)

    @cached_property
    def back(self) -> float | None:
        """Heading (rad in the instance's frame, 0 along +x) of the side where parts rise
        ``OVER_RIM`` above a receptacle's rim beyond its opening (a lid standing open), as
        the nearest of the four axis directions; None where nothing does."""
        if self.interior is None:
            return None
        rim = self.interior.center[2] + self.interior.height
        tall = [
            p for p in self.parts if not p.visual_only and union_bounds([p])[1][2] > rim + OVER_RIM
        ]
        if not tall:
            return None
        lo, hi = union_bounds(tall)
        middle = (lo[:2] + hi[:2]) / 2 - np.asarray(self.interior.center[:2])
        beyond = middle / np.asarray(self.interior.half)
        axis = int(np.argmax(np.abs(beyond)))
        if abs(beyond[axis]) <= 1.0:
            return None
        return (0.0, math.pi / 2)[axis] + (math.pi if beyond[axis] < 0 else 0.0)

    def color_share(self, color: str) -> float:
        """The share of the instance's surface (its parts' areas, prints included) in
        ``color``: a stated colour or one a smaller part shows."""
        total = sum(p.area for p in self.parts)
        return sum(p.area for p in self.parts if p.color == color) / total

    @property
    def height(self) -> float:
        return self.dims[2]

    @property
    def size(self) -> str:
        return size_bucket(self.height)

    @property
    def mass(self) -> float:
        return float(sum(p.mass for p in self.parts))

    @property
    def held_out(self) -> bool:
        """True for the instances InstructMove 1.0 (sampler 1) reserved for the
        unseen_instance split; ``sampler.split_of`` gives each sampler's partition."""
        return _stable_bucket(f"instance/{self.uuid}") == 0

    def to_record(self) -> dict:
        """Everything that defines the instance, as JSON-ready data (see ``from_record``)."""
        record = asdict(self)
        record["parts"] = [asdict(p) for p in self.parts]
        return record

    @classmethod
    def from_record(cls, record: dict) -> Instance:
        fields = dict(record)
        fields["parts"] = tuple(
            Part(
                **{
                    **p,
                    "size": tuple(p["size"]),
                    "pos": tuple(p["pos"]),
                    "quat": tuple(p["quat"]),
                    "rgb": tuple(p["rgb"]),
                    "texture": _texture_of(p.get("texture")),
                }
            )
            for p in record["parts"]
        )
        for key in ("colors", "nouns"):
            fields[key] = tuple(record[key])
        interior = record.get("interior")
        fields["interior"] = (
            None
            if interior is None
            else Region(tuple(interior["center"]), tuple(interior["half"]), interior["height"])
        )
        return cls(**fields)

    def annotation(self) -> dict:
        """The instance's annotation record, as stored in catalog exports."""
        return {
            "uuid": self.uuid,
            "category": self.category,
            "super_category": self.super_category,
            "domain": self.domain,
            "colors": list(self.colors),
            "material": self.material,
            "shape": self.shape,
            "dims": [round(v, 5) for v in self.dims],
            "height": round(self.height, 5),
            "size": self.size,
            "mass": round(self.mass, 5),
            "is_graspable": self.is_graspable,
            "is_container": self.is_container,
            "interior": None
            if self.interior is None
            else {
                "center": [round(v, 5) for v in self.interior.center],
                "half": [round(v, 5) for v in self.interior.half],
                "height": round(self.interior.height, 5),
            },
        }


def _texture_of(record: dict | None) -> Texture | None:
    if record is None:
        return None
    return Texture(record["pattern"], tuple(record["inks"]), record["motif"])


def instance_uuid(category: str, index: int, revision: int = 1) -> str:
    """The uuid of instance ``index`` of ``category`` as built by its generator's
    ``revision`` (a revised build is another asset, with its own uuid and draws)."""
    suffix = "" if revision == 1 else f"@r{revision}"
    return str(uuidlib.uuid5(UUID_NAMESPACE, f"{category}/{index}{suffix}"))


def plain(inst: Instance) -> Instance:
    """``inst`` without its textures (its parts' geometry, colours and masses unchanged)."""
    if all(p.texture is None for p in inst.parts):
        return inst
    parts = tuple(replace(p, texture=None) for p in inst.parts)
    return replace(inst, parts=parts)


def generate_instance(category: str, index: int, library: int = LIBRARY) -> Instance:
    """Build instance ``index`` of ``category`` as library revision ``library`` builds it;
    the same arguments give the same object."""
    if category not in GENERATORS:
        raise KeyError(f"no generator for category {category!r}; known: {sorted(GENERATORS)}")
    gen = generator_at(category, library)
    entry = taxonomy().get(category)
    if entry is None:
        raise KeyError(f"category {category!r} is not in the taxonomy")
    uid = instance_uuid(category, index, gen.revision)
    design = Design(np.random.default_rng(uuidlib.UUID(uid).int % 2**63))
    traits = gen.build(design)
    if not 1 <= len(traits.colors) <= 2:
        raise ValueError(f"{category}: an instance names 1 or 2 colours, got {traits.colors}")
    parts, interior = design.finish()
    if gen.container != (interior is not None):
        raise ValueError(f"{category}: a container declares its interior, and only a container")
    return Instance(
        uuid=uid,
        category=category,
        index=index,
        domain=entry.domain,
        super_category=entry.super_category,
        parts=tuple(parts),
        colors=tuple(dict.fromkeys(traits.colors)),
        material=material_word(traits.material),
        shape=traits.shape,
        nouns=gen.synonyms,
        is_graspable=gen.graspable,
        is_container=gen.container,
        interior=interior,
    )


class Catalog:
    """A frozen set of instances (a snapshot) with look-ups by uuid and category."""

    def __init__(self, name: str, instances: Iterable[Instance]) -> None:
        self.name = name
        self.instances: tuple[Instance, ...] = tuple(instances)
        self._by_uuid = {inst.uuid: inst for inst in self.instances}
        self._by_category: dict[str, list[Instance]] = {}
        for inst in self.instances:
            self._by_category.setdefault(inst.category, []).append(inst)

    def __len__(self) -> int:
        return len(self.instances)

    def __contains__(self, uuid: object) -> bool:
        return uuid in self._by_uuid

    def __getitem__(self, uuid: str) -> Instance:
        try:
            return self._by_uuid[uuid]
        except KeyError:
            raise KeyError(f"uuid {uuid!r} is not in snapshot {self.name!r}") from None

    @property
    def categories(self) -> list[str]:
        return sorted(self._by_category)

    def of_category(self, category: str) -> list[Instance]:
        return list(self._by_category.get(category, []))
