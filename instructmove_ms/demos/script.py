"""The planned motions of one episode, phase by phase, each planned from the live state: pick
the scene's target; for a scene with a destination, place it there, or first relay it to the
other arm of a dual-arm rig (``relay``) where the holding arm finds no place. The demo
synthesizer and the planner oracle policy both play it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from instructmove_ms.planning import PlanningScene

from .pick import plan_pick
from .place import PLACE_RESERVE, plan_place
from .relay import plan_relay


@dataclass
class MotionScript:
    """``next(env)`` observes the env into ``scene`` and gives the next motion:
    ``pd_joint_pos`` actions, a failure reason or None once nothing is left. A pick that
    ends without the target in the hand is planned again, ``pick_attempts`` in all (per arm
    after a relay), each attempt with the next grasp plan. ``variant`` passes over that many
    plans in the first pick (the demo generator's physics trials of the same scene)."""

    scene: PlanningScene
    pick_attempts: int = 1
    variant: int = 0
    picks: int = 0
    arms: list[int] | None = None
    relayed: bool = False
    done: bool = False

    def next(self, env) -> np.ndarray | str | None:
        if not self.done:
            self.scene.observe(env)
        motion = None if self.done else self._plan()
        self.done = self.done or motion is None or isinstance(motion, str)
        return motion

    def _plan(self) -> np.ndarray | str | None:
        scene = self.scene
        if not scene.state.held:
            if self.picks >= self.pick_attempts:
                return "grasp_slipped"
            skip = self.picks + (0 if self.relayed else self.variant)
            self.picks += 1
            reserve = PLACE_RESERVE if scene.destination >= 0 else 0
            return plan_pick(scene, self.arms, scene.steps_left - reserve, skip)
        if scene.destination < 0:
            return None  # picked and held
        self.done = True  # after the place, nothing is left
        place = plan_place(scene)
        others = scene.other_arms()
        if isinstance(place, str) and not self.relayed and others:
            relay = plan_relay(scene)
            if not isinstance(relay, str):
                self.arms, self.relayed, self.picks, self.done = others, True, 0, False
                return relay
        return place
