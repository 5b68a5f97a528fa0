"""PlaceA2B: put the named object in or on the named receptacle."""

from __future__ import annotations

import torch
from mani_skill.utils.registration import register_env

from instructmove_ms.family import StageSchema, TaskSpec
from instructmove_ms.sampler import EACH_OTHER, Constraint, RoleSpec

from .base import InstructMoveEnv
from .measure import Measured
from .pick_category import CategoryCue
from .stages import rotate, select

#: S_pnp = 0.25 (reach_pick + lift_pick + reach_place + place); success is the place.
PLACE_STAGES = StageSchema(("reach_pick", "lift_pick", "reach_place", "place"), success="place")

#: Objects small enough to fit inside any destination of the pool.
MAX_OBJECT_FOOTPRINT = 0.09
MIN_INTERIOR = 0.1

PLACE_A2B = TaskSpec(
    env_id="PlaceA2B-InstructMove",
    family="place_a2b",
    # the object by its own referring expression; the destination slot names the receptacle
    cue=CategoryCue(kind="place"),
    stages=PLACE_STAGES,
    default_robot="piperx",
    supported_robots=("franka", "piperx"),
    roles=(
        RoleSpec("target", 1, pool="target", max_footprint=MAX_OBJECT_FOOTPRINT),
        RoleSpec(
            "distractor",
            1,
            max_footprint=MAX_OBJECT_FOOTPRINT,
            constraints=(
                Constraint("category", "differ", "target"),
                Constraint("category", "differ", EACH_OTHER),
                Constraint("name", "differ", "target"),
                Constraint("name", "differ", EACH_OTHER),
            ),
        ),
        RoleSpec(
            "destination", 1, require=("container",), min_interior=MIN_INTERIOR, max_footprint=0.26
        ),
        RoleSpec(
            "distractor_destination",
            1,
            require=("container",),
            min_interior=MIN_INTERIOR,
            max_footprint=0.26,
            constraints=(
                Constraint("category", "differ", "destination"),
                Constraint("name", "differ", "destination"),
            ),
        ),
    ),
    count_limits={"distractor": (1, 2)},
    templates=(
        "put the {target} {at} the {destination}",
        "place the {target} {at} the {destination}",
        "move the {target} {prep} the {destination}",
        "pick up the {target} and put {it} {at} the {destination}",
        "take the {target} and put {it} {at} the {destination}",
        "can you put the {target} {at} the {destination}?",
        "could you place the {target} {at} the {destination}?",
        "please put the {target} {at} the {destination}",
    ),
    # "move the comb into the waste bin" reads oddly; InstructMove 1.0's sampler still says it
    retired_templates=("move the {target} {prep} the {destination}",),
    # Longer than the pick families' 300: a dual-arm rig may relay the object between its
    # arms to reach a receptacle on the far side.
    max_episode_steps=500,
)


@register_env(PLACE_A2B.env_id, max_episode_steps=PLACE_A2B.max_episode_steps)
class PlaceA2BEnv(InstructMoveEnv):
    """**Task Description:**
    Put the named object in (or on) the named receptacle. The table holds two plausible pick
    objects (the target and ``num_distractors`` others, all of different categories) and two
    receptacles of different categories: the goal is one (object, receptacle) pair out of
    |G| = objects x receptacles, and only the instruction says which.

    **Randomizations:**
    - objects (small enough for every receptacle) and receptacles (interiors at least 0.1 m
      wide), from the split's pools
    - positions, yaw (a lid standing open or a caddy's back turned away from the robot,
      within 45 degrees), template and the preposition (on for flat destinations), robot joints
    - with ``perturbation=``: lighting, table, background, cameras, robot joints, layout and
      paraphrase at levels 0-3 (``instructmove_ms.perturbation``), drawn from the seed

    **Success Conditions:**
    - ``reach_pick`` / ``lift_pick``: reach and lift of the target object, as in the pick
      families
    - ``reach_place``: after lift_pick, the centre of the object's box is over the goal
      receptacle's interior (latched)
    - ``place``: the object rests inside that interior (its box's lowest point at most
      0.03 m above the floor and its centre above it, in any orientation; slower than
      0.05 m/s) and the robot has released it
      (latched); ``success`` equals ``place``;
      ``stage_score`` is S_pnp = 0.25 (reach_pick + lift_pick + reach_place + place)
    """

    task = PLACE_A2B
    goal_reward = 3.0  # carrying the target over the goal receptacle (2), releasing it (1)

    def _load_scene(self, options: dict) -> None:
        super()._load_scene(options)
        self._goal = torch.tensor([ep.goal_destination for ep in self.episodes], device=self.device)
        regions = []
        for ep in self.episodes:  # the goal receptacle's interior: floor centre and half size
            region = (
                self.catalog_of(ep)[ep.objects[ep.goal_destination].uuid].interior
                if ep.goal_destination >= 0
                else None
            )
            regions.append([*region.center, *region.half] if region else [0.0] * 5)
        regions_t = torch.tensor(regions, dtype=torch.float32, device=self.device)
        self._goal_center, self._goal_half = regions_t[:, :3], regions_t[:, 3:]
        self._goal_column = self._goal.clamp(min=0)[:, None]
        self._target_mask = torch.zeros_like(self._z0, dtype=torch.bool).scatter_(
            1, self._target_column, True
        )
        self._up = torch.tensor([0.0, 0.0, 1.0], device=self.device)

    def _goal_frame(self, points: torch.Tensor, now: Measured) -> torch.Tensor:
        """``points`` (N, 3) in the goal receptacle's frame, relative to its floor centre."""
        rel = points - select(now.pos, self._goal_column)
        return rotate(select(now.quat, self._goal_column), rel, inverse=True) - self._goal_center

    def _target_in_goal(self, now: Measured) -> tuple[torch.Tensor, torch.Tensor]:
        """The centre (N, 3) and the lowest point's height (N,) of the target's box in the
        goal receptacle's frame, in any orientation (a cup on its side, an egg upside down):
        the box reaches below its centre by its half extents along the goal's up axis."""
        turn = self._of_target(now.quat)
        centre = self._of_target(now.pos) + rotate(turn, self._of_target(self._box_center))
        local = self._goal_frame(centre, now)
        up = rotate(select(now.quat, self._goal_column), self._up.expand_as(centre))
        depth = (rotate(turn, up, inverse=True).abs() * self._of_target(self._box_half)).sum(1)
        return local, local[:, 2] - depth

    def _watched(self, raised: torch.Tensor) -> torch.Tensor:
        """The raised objects and the target: release is part of placing."""
        return raised | self._target_mask

    def _goal_conditions(self, now: Measured, grasped: torch.Tensor) -> list[torch.Tensor]:
        """reach_place: the target's box centre is over the goal interior; place: it rests
        on the floor inside (its lowest point within ``place_height``, its centre above the
        floor), slower than ``place_speed``, released."""
        local, bottom = self._target_in_goal(now)
        over = (self._goal >= 0) & (local[:, :2].abs() <= self._goal_half).all(dim=1)
        th = self.task.thresholds
        # a tilted round object's box dips below the floor: its centre must stay above it
        resting = (local[:, 2] > -0.01) & (bottom < th.place_height)
        still = torch.linalg.norm(self._of_target(now.velocity), dim=1) < th.place_speed
        return [over, over & resting & still & ~self._of_target(grasped)]

    def _goal_reward(
        self,
        reward: torch.Tensor,
        info: dict,
        now: Measured,
        grasped: torch.Tensor,
        lifted: torch.Tensor,
    ) -> torch.Tensor:
        """Carry the lifted target over the goal receptacle (2), release it there (1)."""
        away = torch.linalg.norm(self._goal_frame(self._of_target(now.pos), now)[:, :2], dim=1)
        reward = reward + lifted * grasped.float() * 2.0 * (1.0 - torch.tanh(5.0 * away))
        return reward + info["reach_place"].float() * (~grasped).float()
