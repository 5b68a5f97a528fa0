"""Declarative task specifications, read by the shared engine in ``tasks.base``."""

from __future__ import annotations

from dataclasses import dataclass, field

from instructmove_ms.layout import Workspace
from instructmove_ms.sampler import RoleSpec


@dataclass(frozen=True)
class Thresholds:
    """Stage thresholds, in metres.

    ``reach``: the TCP is within this distance of the object's box. Layouts keep at least
    ``clearance`` between footprints and ``reach`` is below half of it, so one TCP position
    can never be within ``reach`` of two objects of a fresh layout: the reached object is
    unambiguous (the reference's 0.2 m from an object origin spans several neighbours).
    ``lift``: the object, grasped by the robot, is this much above its initial height.
    ``place_height`` and ``place_speed``: a placed object rests on the receptacle's floor
    (its bottom within this height of the floor) and moves slower than this.
    """

    reach: float = 0.02
    lift: float = 0.03
    place_height: float = 0.03  # resting within this above the receptacle's floor
    place_speed: float = 0.05  # m/s: the placed object has come to rest


@dataclass(frozen=True)
class TaskSpec:
    """What defines a task family: composition, constraints, language and scoring."""

    env_id: str
    family: str
    default_robot: str
    supported_robots: tuple[str, ...]
    cue: str  # how the instruction singles out the goal: category|attribute|spatial|place
    roles: tuple[RoleSpec, ...]  # who is in the scene, with default counts and constraints
    count_limits: dict[str, tuple[int, int]]  # role -> allowed (min, max) count
    templates: tuple[str, ...]  # slots: {target}; for place also {prep} and {destination}
    attributes: tuple[str, ...] = ()  # attribute cue: what may tell the target apart
    relations: tuple[str, ...] = ()  # spatial cue: relations to the reference
    max_episode_steps: int = 300
    clearance: float = 0.05
    workspace: Workspace = field(default_factory=Workspace)
    thresholds: Thresholds = field(default_factory=Thresholds)

    def role(self, name: str) -> RoleSpec:
        return next(r for r in self.roles if r.name == name)

    @property
    def is_place(self) -> bool:
        return self.cue == "place"
