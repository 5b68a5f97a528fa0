"""The episode specification: the single source of truth for one episode.

It holds the paper's tuple e = (s0, O, D, l, g*, G): the initial state (objects with
uuids and poses, robot joints), the manipulable objects, the destinations, the instruction,
the instruction-consistent goal (``target``) and the candidate goals (``candidates``).
Scene building, the instruction, scoring and later demo generation all read it.
"""

from __future__ import annotations

import json
from dataclasses import MISSING, asdict, dataclass, field, fields

CONDITIONS = ("normal", "alternative_target", "generic", "empty", "absent_object")
#: Version 2 adds the verifier's ``certificate``; version 1 specs (without one) still read.
SPEC_VERSION = 2
READABLE_VERSIONS = (1, 2)


def actor_name(k: int) -> str:
    """The name of the scene actor of ``objects[k]`` (the env builds it, planners find it)."""
    return f"object_{k}"


@dataclass(frozen=True)
class ObjectSpec:
    """One object of the scene: which catalog instance, where, and its role."""

    uuid: str
    category: str
    role: str  # "target" | "distractor" | "reference" | "receptacle"
    pose: tuple[float, ...]  # world frame: x, y, z, qw, qx, qy, qz


@dataclass(frozen=True)
class EpisodeSpec:
    family: str
    robot: str
    snapshot: str
    split: str
    seed: int
    instruction: str
    objects: tuple[ObjectSpec, ...]
    target: int  # index into ``objects`` of the instruction-consistent goal; -1 if none
    candidates: tuple[int, ...]  # indices of the plausible candidate goals
    robot_qpos: tuple[float, ...]
    destinations: tuple[int, ...] = ()  # indices of the candidate receptacles (PlaceA2B)
    goal_destination: int = -1  # index of the instruction-consistent receptacle, -1 if none
    cue: dict = field(default_factory=dict)  # how the instruction singles out the goal
    condition: str = "normal"
    #: the perturbation axes' levels and drawn values (see ``perturbation``); {} for none
    perturbation: dict = field(default_factory=dict)
    #: why the instruction singles out the goal, as the verifier found it (``verify.certify``)
    certificate: dict = field(default_factory=dict)
    #: the sampler that drew the scene (``sampler.SAMPLERS``): 1 is InstructMove 1.0's
    sampler: int = 1
    version: int = field(default=SPEC_VERSION)

    def __post_init__(self) -> None:
        if self.target >= len(self.objects):
            raise ValueError(f"target index {self.target} outside {len(self.objects)} objects")
        if self.target >= 0 and self.target not in self.candidates:
            raise ValueError("the target must be one of the candidate goals")

    def to_dict(self) -> dict:
        """The spec as plain data; empty ``perturbation`` and ``certificate`` and sampler 1
        are left out, so such a spec reads as it did before they existed."""
        data = asdict(self)
        for key in ("perturbation", "certificate"):
            if not data[key]:
                del data[key]
        if data["sampler"] == 1:
            del data["sampler"]
        return data

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_dict(cls, data: dict) -> EpisodeSpec:
        """The spec of ``data``; a ``ValueError`` names missing or unknown fields."""
        declared = fields(cls)
        required = [f.name for f in declared if f.default is f.default_factory is MISSING]
        missing = [k for k in required if k not in data]
        unknown = sorted(set(data) - {f.name for f in declared})
        if missing:
            raise ValueError(f"episode spec lacks {', '.join(missing)}")
        if unknown:
            raise ValueError(f"episode spec has unknown fields {', '.join(unknown)}")
        if data.get("version", SPEC_VERSION) not in READABLE_VERSIONS:
            raise ValueError(
                f"episode spec version {data.get('version')!r}; "
                f"this release reads versions {READABLE_VERSIONS}"
            )
        values = dict(data)
        values["objects"] = tuple(
            ObjectSpec(o["uuid"], o["category"], o["role"], tuple(o["pose"]))
            for o in data["objects"]
        )
        for key in ("candidates", "robot_qpos", "destinations"):
            values[key] = tuple(data.get(key, ()))
        return cls(**values)

    @classmethod
    def from_json(cls, text: str) -> EpisodeSpec:
        return cls.from_dict(json.loads(text))

    @property
    def target_object(self) -> ObjectSpec | None:
        return self.objects[self.target] if self.target >= 0 else None

    @property
    def num_goals(self) -> int:
        """|G|: candidate objects, times candidate receptacles for pick-and-place."""
        return len(self.candidates) * max(1, len(self.destinations))
