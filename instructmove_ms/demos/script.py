"""The planned motions of one episode, phase by phase, each planned from the live state: pick
the target; for an episode with a goal receptacle, place it there, or first relay it to the
other arm of a dual-arm rig (``relay``) where the holding arm finds no place. The demo
synthesizer and the planner oracle policy both play it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .pick import plan_pick
from .place import PLACE_RESERVE, plan_place
from .relay import other_arm, plan_relay
from .timing import steps_left


@dataclass
class MotionScript:
    """``next(env)`` gives the next motion: ``pd_joint_pos`` actions, a failure reason or
    None once nothing is left. A pick that ends without the target in the hand is planned
    again, ``pick_attempts`` in all (per arm after a relay), each attempt with the next
    grasp plan. ``variant`` passes over that many plans in the first pick (the demo
    generator's physics trials of the same scene)."""

    pick_attempts: int = 1
    variant: int = 0
    picks: int = 0
    arms: list[int] | None = None
    relayed: bool = False
    done: bool = False

    def next(self, env) -> np.ndarray | str | None:
        motion = None if self.done else self._plan(env)
        self.done = self.done or motion is None or isinstance(motion, str)
        return motion

    def _plan(self, env) -> np.ndarray | str | None:
        u = env.unwrapped
        spec = u.episode
        if not bool(u.agent.is_grasping(u.objects[spec.target])[0]):
            if self.picks >= self.pick_attempts:
                return "grasp_slipped"
            skip = self.picks + (0 if self.relayed else self.variant)
            self.picks += 1
            reserve = PLACE_RESERVE if spec.goal_destination >= 0 else 0
            return plan_pick(env, self.arms, steps_left(env) - reserve, skip)
        if spec.goal_destination < 0:
            return None  # picked and held
        self.done = True  # after the place, nothing is left
        place = plan_place(env)
        if isinstance(place, str) and not self.relayed and other_arm(env):
            relay = plan_relay(env)
            if not isinstance(relay, str):
                self.arms, self.relayed, self.picks, self.done = other_arm(env), True, 0, False
                return relay
        return place
