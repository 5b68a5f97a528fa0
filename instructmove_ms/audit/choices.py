"""What a language-blind adversary may see of an episode: its choices and their options.

A ``Choice`` is one decision the instruction settles: which candidate object to take (every
family) or which receptacle to put it in (PlaceA2B). It holds, per option, everything the
spec and the catalog say of it (annotations, dimensions, mass, pose, what the scene cameras
see of it, whether it lies outside the training partition) and, apart, the index of the
answer. Nothing built here reads the instruction, the cue, the roles or the certificate's
verdict: adversaries see ``Choice.options`` only, and only scoring reads ``Choice.answer``.
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..assets.catalog import Catalog, Instance
from ..episode import EpisodeSpec
from ..sampler import split_of

#: The annotated attributes an odd-one-out adversary compares (colour as a set of colours).
CATEGORICAL = ("category", "super_category", "color", "material", "shape", "size")
#: Scene cameras whose visibility figures a stored episode carries (by position).
CAMERA_SLOTS = 2
#: The reference workspace's middle, in the robot's base frame (metres).
WORKSPACE_MIDDLE = (0.4, 0.0)
#: The decisions an episode holds.
KINDS = ("object", "receptacle")


@dataclass(frozen=True)
class Option:
    """One option of a choice, as a blind adversary sees it."""

    values: dict[str, frozenset]  # CATEGORICAL attribute -> its values
    numbers: dict[str, float]  # physical, layout and visibility figures
    novel: bool  # outside the training partition (never in a training scene)


@dataclass(frozen=True)
class Choice:
    """One decision of one episode: its options and (for scoring only) the answer."""

    family: str
    kind: str
    split: str
    robot: str
    seed: int
    options: tuple[Option, ...]
    answer: int

    @property
    def chance(self) -> float:
        return 1.0 / len(self.options)


def _instance_numbers(inst: Instance) -> dict[str, float]:
    dx, dy, dz = inst.dims
    return {
        "height": dz,
        "extent": max(inst.dims),
        "footprint": dx * dy,
        "volume": dx * dy * dz,
        "mass": inst.mass,
        "density": inst.mass / max(dx * dy * dz, 1e-9),
        "parts": float(len(inst.parts)),
        "colours": float(len(inst.colors)),
    }


def _layout_numbers(spec: EpisodeSpec, k: int) -> dict[str, float]:
    x, y = spec.objects[k].pose[:2]
    others = [o.pose[:2] for j, o in enumerate(spec.objects) if j != k]
    gaps = [math.dist((x, y), p) for p in others] or [0.0]
    qw, qz = spec.objects[k].pose[3], spec.objects[k].pose[6]
    yaw = 2 * math.atan2(qz, qw)
    return {
        "x": x,
        "y": y,
        "side": abs(y),
        "robot_distance": math.hypot(x, y),
        "centrality": -math.dist((x, y), WORKSPACE_MIDDLE),
        "nearest_gap": min(gaps),
        "mean_gap": float(np.mean(gaps)),
        "yaw_cos2": math.cos(2 * yaw),
        "yaw_sin2": math.sin(2 * yaw),
    }


def _visibility_numbers(spec: EpisodeSpec, k: int) -> dict[str, float]:
    """Pixels and visible fraction per scene camera (stored episodes only; else empty)."""
    figures = spec.certificate.get("visibility")
    if not figures:
        return {}
    row = next((o for o in figures["objects"] if o["index"] == k), None)
    if row is None:
        return {}
    out = {}
    for c in range(min(CAMERA_SLOTS, len(row["pixels"]))):
        out[f"pixels_{c}"] = float(row["pixels"][c])
        out[f"fraction_{c}"] = float(row["fraction"][c])
    return out


def option_of(spec: EpisodeSpec, catalog: Catalog, k: int) -> Option:
    """What a blind adversary sees of object ``k`` of ``spec``."""
    inst = catalog[spec.objects[k].uuid]
    values = {
        "category": frozenset([inst.category]),
        "super_category": frozenset([inst.super_category]),
        "color": frozenset(inst.colors),
        "material": frozenset([inst.material]),
        "shape": frozenset([inst.shape]),
        "size": frozenset([inst.size]),
    }
    numbers = {
        **_instance_numbers(inst),
        **_layout_numbers(spec, k),
        **_visibility_numbers(spec, k),
    }
    return Option(values, numbers, novel=split_of(inst, catalog, spec.sampler) != "seen")


def decisions(spec: EpisodeSpec, goal: bool = True) -> list[tuple[str, tuple[int, ...], int]]:
    """(kind, option indices into ``spec.objects``, answer index or -1) of each decision of
    an episode: the object (and, with receptacles, the receptacle); ``goal`` True: of a
    normal episode (a ``ValueError`` where it has none)."""
    if goal and spec.target < 0:
        raise ValueError(f"episode of seed {spec.seed} has no goal ({spec.condition})")
    found = [("object", tuple(spec.candidates), spec.target)]
    if spec.destinations:
        found.append(("receptacle", tuple(spec.destinations), spec.goal_destination))
    return found


def choices_of(spec: EpisodeSpec, catalog: Catalog) -> list[Choice]:
    """The choices of a normal episode (see ``decisions``)."""
    return [
        Choice(
            family=spec.family,
            kind=kind,
            split=spec.split,
            robot=spec.robot,
            seed=spec.seed,
            options=tuple(option_of(spec, catalog, k) for k in indices),
            answer=indices.index(answer),
        )
        for kind, indices, answer in decisions(spec)
    ]


def by_decision(choices: Sequence[Choice]) -> dict[tuple[str, str], list[Choice]]:
    """``choices`` grouped by (family, kind), each group in their order."""
    out: dict[tuple[str, str], list[Choice]] = defaultdict(list)
    for c in choices:
        out[(c.family, c.kind)].append(c)
    return out
