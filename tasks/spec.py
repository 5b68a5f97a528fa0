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
    """

    reach: float = 0.02
    lift: float = 0.03


@dataclass(frozen=True)
class TaskSpec:
    """What defines a task family: composition, constraints, language and scoring."""

    env_id: str
    family: str
    default_robot: str
    supported_robots: tuple[str, ...]
    roles: tuple[RoleSpec, ...]  # who is in the scene, with default counts and constraints
    count_limits: dict[str, tuple[int, int]]  # role -> allowed (min, max) count
    templates: tuple[str, ...]
    max_episode_steps: int = 300
    clearance: float = 0.05
    workspace: Workspace = field(default_factory=Workspace)
    thresholds: Thresholds = field(default_factory=Thresholds)

    def role(self, name: str) -> RoleSpec:
        return next(r for r in self.roles if r.name == name)
