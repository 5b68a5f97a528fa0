"""What a task family is, as the core sees it: a declarative ``TaskSpec`` holding the
family's ``Cue`` (how its instruction singles out the goal) and its ``StageSchema`` (how an
episode is scored).

Each family declares its spec in its own file under ``tasks/``; the composer, the verifier,
the metrics and the tools read these objects and never test a family's name. Nothing here
needs a simulator.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .layout import Placement, Workspace
from .sampler import Constraint, RoleSpec

if TYPE_CHECKING:
    from .assets.catalog import Catalog, Instance
    from .episode import EpisodeSpec

#: Scene members in scene order: (catalog instance, role name).
Members = list[tuple["Instance", str]]
#: A layout predicate: may object ``i`` go at ``p`` given those ``placed`` so far?
Accept = Callable[[int, Placement, dict[int, Placement]], bool]


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
class StageSchema:
    """A family's latched stages, in order: each counts only once the one before it has.

    The first two are always reaching and lifting the object to move (the env's ``reach``
    and ``lift``); a family may add stages after them. ``success`` names the stage that is
    the task's success. The stage score is the mean of the stage flags (S_pick = 0.5 reach
    + 0.5 lift; S_pnp = 0.25 per stage).
    """

    names: tuple[str, ...]
    success: str

    def __post_init__(self) -> None:
        if len(self.names) < 2:
            raise ValueError(f"a stage schema needs reach and lift stages, got {self.names}")
        if self.success not in self.names:
            raise ValueError(f"success stage {self.success!r} is not one of {self.names}")

    @property
    def reached(self) -> str:
        """The stage that says the object to move was reached."""
        return self.names[0]

    @property
    def flags(self) -> tuple[str, ...]:
        """The per-step flags recorded with a demo: every stage, then ``success``."""
        return (*self.names, "success")

    def score(self, flags: Any) -> Any:
        """The stage score of ``flags`` (..., stages): an array or tensor of the stage
        flags, in order, on its last axis."""
        return flags.sum(-1) * (1.0 / len(self.names))


class Cue:
    """How a family's instruction singles out the goal among the candidates.

    The composer calls ``draw`` (the cue of one composition attempt, a JSON-able dict stored
    in ``EpisodeSpec.cue``, and the roles constrained so that it can single out the target),
    ``admits`` (refuse a cast the cue cannot phrase), ``arrange`` (layout order and
    predicate), ``phrase`` (the words naming the goal object) and ``alternative`` (the cue
    that names another candidate); the symmetric sampler (2) also calls ``group_size`` and
    ``singles_out``, and its added distractors (``perturbation``) ``rivals``; the verifier
    calls ``matches`` and ``explain``.
    Subclasses live with their family in ``tasks/``.
    """

    def draw(
        self, rng: np.random.Generator, roles: tuple[RoleSpec, ...]
    ) -> tuple[dict, tuple[RoleSpec, ...]]:
        raise NotImplementedError

    def rivals(self, cue: dict) -> tuple[Constraint, ...]:
        """The constraints ``draw`` adds to the distractor role under ``cue`` (by default
        none)."""
        return ()

    def group_size(self, cue: dict, count: int) -> int:
        """How many candidates a scene under ``cue`` holds, of the ``count`` asked: as many
        as can all differ in what the cue names (by default all)."""
        return count

    def singles_out(self, cue: dict, group: Sequence[Instance]) -> list[int]:
        """The members of a candidate ``group`` that ``cue`` as drawn can name (by default
        every one; none refuses the group); the symmetric sampler takes the goal uniformly
        among them."""
        return list(range(len(group)))

    def admits(self, cue: dict, assigned: dict[str, list[Instance]]) -> None:
        """Raise ``sampler.RoleError`` where ``cue`` cannot single out the assigned target."""

    def arrange(
        self, cue: dict, index: dict[str, list[int]], count: int
    ) -> tuple[list[int] | None, Accept | None, dict]:
        """(placement order, layout predicate, cue) for a scene of ``count`` objects whose
        roles sit at ``index``; by default any order and layout, the cue unchanged."""
        return None, None, cue

    def phrase(
        self,
        rng: np.random.Generator,
        cue: dict,
        members: Members,
        goal: int,
        split: str,
        sampler: int,
    ) -> str:
        """The words naming object ``goal`` under ``cue`` (they fill a template's
        ``{target}``), as ``sampler``'s episodes say them."""
        raise NotImplementedError

    def alternative(self, cue: dict, members: Members, candidates: Sequence[int], goal: int):
        """The cue that singles out candidate ``goal`` instead of the target (the
        alternative-target condition); by default the same cue."""
        return cue

    def matches(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> bool:
        """Whether candidate ``k`` fits ``spec``'s instruction under its cue."""
        raise NotImplementedError

    def explain(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> dict:
        """What the cue reads of candidate ``k`` (JSON data for the verifier's certificate:
        its attribute value, its bearing from the reference, ...); by default nothing."""
        return {}


@dataclass(frozen=True)
class TaskSpec:
    """A task family: its env id, robots, roles, instruction templates, cue, stages and
    thresholds. Roles named ``target`` and ``distractor`` are the candidate objects,
    ``destination`` and ``distractor_destination`` the candidate receptacles."""

    env_id: str
    family: str
    default_robot: str
    supported_robots: tuple[str, ...]
    cue: Cue
    stages: StageSchema
    roles: tuple[RoleSpec, ...]  # who is in the scene, with default counts and constraints
    count_limits: dict[str, tuple[int, int]]  # role -> allowed (min, max) count
    #: slots: {target}, {it} (its pronoun); with a destination also {destination}, {prep}
    #: (into/onto) and {at} (in/on)
    templates: tuple[str, ...]
    max_episode_steps: int = 300
    clearance: float = 0.05
    workspace: Workspace = field(default_factory=Workspace)
    thresholds: Thresholds = field(default_factory=Thresholds)

    #: templates InstructMove 1.0's sampler (1) still draws and later samplers do not
    #: (fresh readers found them odd)
    retired_templates: tuple[str, ...] = ()

    def templates_of(self, sampler: int) -> tuple[str, ...]:
        """The templates episodes of ``sampler`` are said with."""
        if sampler == 1:
            return self.templates
        return tuple(t for t in self.templates if t not in self.retired_templates)

    def role(self, name: str) -> RoleSpec:
        return next(r for r in self.roles if r.name == name)
