"""PlaceA2B: put the named object in or on the named receptacle."""

from __future__ import annotations

from mani_skill.utils.registration import register_env

from instructmove_ms.sampler import EACH_OTHER, Constraint, RoleSpec

from .base import InstructMoveEnv
from .spec import TaskSpec

#: Objects small enough to fit inside any destination of the pool.
MAX_OBJECT_FOOTPRINT = 0.09
MIN_INTERIOR = 0.1

PLACE_A2B = TaskSpec(
    env_id="PlaceA2B-InstructMove",
    family="place_a2b",
    cue="place",
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
        "put the {target} {prep} the {destination}",
        "place the {target} {prep} the {destination}",
        "move the {target} {prep} the {destination}",
        "pick up the {target} and put it {prep} the {destination}",
        "set the {target} {prep} the {destination}",
        "take the {target} and place it {prep} the {destination}",
        "can you put the {target} {prep} the {destination}",
        "please move the {target} {prep} the {destination}",
    ),
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
    - positions, yaw, template and the preposition (on for flat destinations), robot joints

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
