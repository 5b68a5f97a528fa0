"""Asset identity: a content hash that every machine computes alike.

Generated parts differ in the last bit of their floats between BLAS kernels, numpy
releases and CPUs (a ``@`` runs through OpenBLAS; its kernels round differently). The hash
therefore covers each number as an integer count of a quantum, chosen well above that noise
(about 1e-16 relative) and well below anything physical or visible:

==========================  =============  =========================================
quantity                    quantum        against
==========================  =============  =========================================
lengths (size, pos, box)    1 um           0.1 mm, the smallest change a test expects
quaternion components       1e-6           about 2e-6 rad (0.0001 degrees)
colour channels (sRGB)      1e-4           1/255 = 0.0039, one 8-bit step
solid fraction              1e-6           (dimensionless)
part mass (derived)         1 mg           the lightest part weighs grams
mesh piece volume           1e-12 m^3      0.001 mm^3
==========================  =============  =========================================

A number is counted as ``floor(value / quantum + OFFSET)``: the boundaries between counts
sit at 0.382 of a quantum, not at the half, where designed decimal values land exactly (a
leaf of 1,396.5 mg). Two generations of an instance hash alike unless one of their numbers
lies within its noise of a boundary: a few ULPs are about 1e-9 of a quantum for values up
to a metre or ten kilograms, so odds of about 1e-9 per number; the shipped library's
nearest number lies 4.5e-6 of a quantum from a boundary (a test keeps it above 1e-7). The
mass is hashed although it is derived, so a change of a material's density changes
identity too. Snapshots record the scheme (``IDENTITY_SCHEME``); files without one were
written by the exact hash of scheme 1, which ``exact_hash`` still reads.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict

from .catalog import Instance
from .parts import Part

#: The identity scheme snapshots and appearance tables record (1: exact floats).
IDENTITY_SCHEME = 2
#: Quanta, in SI units (see the module docstring).
LENGTH = 1e-6
QUATERNION = 1e-6
COLOR = 1e-4
FRACTION = 1e-6
MASS = 1e-6
VOLUME = 1e-12
#: Where a count changes, in quanta past a multiple of the quantum: the golden ratio's
#: fraction puts the boundaries at 0.382 of a quantum, far from any short decimal.
OFFSET = (math.sqrt(5) - 1) / 2


def quantise(values, quantum: float) -> int | list[int]:
    """``values`` (a number or a sequence of them) as integer counts of ``quantum``."""
    if isinstance(values, int | float):
        return math.floor(float(values) / quantum + OFFSET)
    return [math.floor(float(v) / quantum + OFFSET) for v in values]


#: The quantum of each number of a part the hash counts (its mass is derived).
PART_QUANTA = {
    "size": LENGTH,
    "pos": LENGTH,
    "quat": QUATERNION,
    "rgb": COLOR,
    "solid_fraction": FRACTION,
    "mass": MASS,
    "mesh_volume": VOLUME,
}


def counted(part: Part) -> dict[str, tuple]:
    """The part's counted numbers: name -> (value or values, quantum)."""
    return {key: (getattr(part, key), quantum) for key, quantum in PART_QUANTA.items()}


def _part_record(part: Part) -> dict:
    numbers = {key: quantise(v, q) for key, (v, q) in counted(part).items()}
    words = {k: getattr(part, k) for k in ("name", "shape", "material", "color", "visual_only")}
    record = {**words, **numbers}
    if part.texture is not None:  # counted only where set: untextured parts hash as before
        record["texture"] = part.texture.record()
    return record


def _traits(inst: Instance) -> list:
    return [
        list(inst.colors),
        inst.material,
        inst.shape,
        list(inst.nouns),
        inst.is_graspable,
        inst.is_container,
    ]


def content_hash(inst: Instance) -> str:
    """sha256 of everything that defines the instance (its parts and stated traits), each
    number counted in its quantum; mesh paths are left out (they depend on where a user
    keeps data; a mesh's content is in the uuid)."""
    interior = inst.interior
    payload = {
        "scheme": IDENTITY_SCHEME,
        "parts": [_part_record(p) for p in inst.parts],
        "traits": _traits(inst),
        "interior": None
        if interior is None
        else {
            "center": quantise(interior.center, LENGTH),
            "half": quantise(interior.half, LENGTH),
            "height": quantise(interior.height, LENGTH),
        },
    }
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def exact_hash(inst: Instance) -> str:
    """The scheme-1 hash (every float to its last bit), to read snapshots written by it."""
    payload = {
        "parts": [
            {k: v for k, v in asdict(p).items() if k not in ("mesh", "texture")} for p in inst.parts
        ],
        "traits": [inst.colors, inst.material, inst.shape, inst.nouns]
        + [inst.is_graspable, inst.is_container],
        "interior": None if inst.interior is None else asdict(inst.interior),
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def hash_for(inst: Instance, scheme: int) -> str:
    """The instance's hash under identity ``scheme`` (1 or 2)."""
    if scheme == IDENTITY_SCHEME:
        return content_hash(inst)
    if scheme == 1:
        return exact_hash(inst)
    raise ValueError(f"unknown identity scheme {scheme!r}; allowed: 1, {IDENTITY_SCHEME}")
