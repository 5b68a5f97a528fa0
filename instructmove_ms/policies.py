"""Reference policies in ManiSkill's evaluator convention.

A policy is a class with ``get_obs_mode()``, ``get_control_mode()``, ``reset(obs)`` and
``act(obs)``. Privileged reference policies also get ``bind(env)``, which the evaluator
calls before each episode, to read the scene (a learned policy never does).

- ``PlannerOraclePolicy`` (``oracle``): plays the demo generator's collision-free planned
  pick (and place) of the instruction's target (privileged): the upper bound.
- ``OraclePolicy`` (``scripted``): a scripted top-down servo to the instruction's target
  (privileged) that grasps and lifts it; for PlaceA2B it then carries it over the goal
  receptacle and opens.
- ``PlannerBlindPolicy`` (``blind``): the oracle's planned motions for a random candidate:
  what a policy that ignores the language can score (about 1/|G|).
- ``BlindPolicy`` (``scripted-blind``): the scripted skill on a random candidate.
- ``RandomPolicy``: random actions.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace

import numpy as np
import torch

from .scripted import CLOSED, OPEN, SERVO_GAIN, STEP_LIMIT, _ee_action, arm_for, tcp_position

GRASP_DEPTH = 0.035  # below an object's top, where the fingers close
CLEARANCE = 0.08  # above the tallest object while moving across the table
MAX_WAYPOINT_STEPS = 90  # give up on a waypoint the arm cannot reach


class RandomPolicy:
    def __init__(self, seed: int = 0, obs_mode: str = "state") -> None:
        self.rng = np.random.default_rng(seed)
        self.obs_mode = obs_mode
        self.space = None

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return "pd_joint_delta_pos"

    def bind(self, env) -> None:
        self.space = env.action_space

    def reset(self, obs) -> None:
        pass

    def act(self, obs) -> np.ndarray:
        low, high = self.space.low, self.space.high
        return self.rng.uniform(low, high).astype(np.float32)


class OraclePolicy:
    """Top-down scripted pick (and place) of a chosen object, with the nearest arm."""

    def __init__(self, seed: int = 0) -> None:
        self.rng = np.random.default_rng(seed)
        self.env = None

    def get_obs_mode(self) -> str:
        return "state"

    def get_control_mode(self) -> str:
        return "pd_ee_delta_pose"

    def choose(self, spec) -> tuple[int, int]:
        """(object, destination or -1): the goal, or random ones when there is none."""
        obj = spec.target if spec.target >= 0 else int(self.rng.choice(spec.candidates))
        if not spec.destinations:
            return obj, -1
        dest = spec.goal_destination
        return obj, dest if dest >= 0 else int(self.rng.choice(spec.destinations))

    def bind(self, env) -> None:
        self.env = env

    def reset(self, obs) -> None:
        u = self.env.unwrapped
        spec = u.episode
        self.index, dest = self.choose(spec)
        inst = u.catalog[spec.objects[self.index].uuid]
        top = u.objects[self.index].pose.p[0].cpu().numpy() + [0.0, 0.0, inst.height]
        clear = max(u.catalog[o.uuid].height for o in spec.objects) + CLEARANCE
        grasp = top - [0.0, 0.0, min(GRASP_DEPTH, inst.height / 2)]
        self.arm = arm_for(self.env, top)
        plan = [
            ([*top[:2], clear], OPEN, 0.03),
            (grasp, OPEN, 0.006),
            (grasp, CLOSED, -12),
            ([*top[:2], clear], CLOSED, 0.02),
        ]
        if dest >= 0:
            region = u.catalog[spec.objects[dest].uuid].interior
            centre = u.objects[dest].pose.p[0].cpu().numpy() + np.asarray(region.center)
            over = [centre[0], centre[1], clear]
            drop = [centre[0], centre[1], region.center[2] + region.height + inst.height]
            plan += [
                (over, CLOSED, 0.02),
                (drop, CLOSED, 0.01),
                (drop, OPEN, -10),
                (over, OPEN, 0.03),
            ]
        self.plan, self.waited = plan, 0

    def act(self, obs) -> torch.Tensor:
        goal, gripper, tol = self.plan[0]
        here = tcp_position(self.env, self.arm)
        delta = np.clip((np.asarray(goal) - here) / STEP_LIMIT * SERVO_GAIN, -1.0, 1.0)
        close = tol > 0 and np.linalg.norm(goal - here) < tol
        done = close or (tol < 0 and self.waited >= -tol) or self.waited >= MAX_WAYPOINT_STEPS
        self.waited = 0 if done else self.waited + 1
        if done and len(self.plan) > 1:
            self.plan = self.plan[1:]
        return torch.from_numpy(_ee_action(self.env, self.arm, delta, gripper))[None]


class BlindPolicy(OraclePolicy):
    """The oracle's skill on a random candidate (and destination): it ignores the text."""

    def choose(self, spec) -> tuple[int, int]:
        dest = int(self.rng.choice(spec.destinations)) if spec.destinations else -1
        return int(self.rng.choice(spec.candidates)), dest


class PlannerOraclePolicy:
    """Privileged: plays the demo generator's planned motions (``demos.script``) for the
    instruction's target (``pd_joint_pos``): the pick, then for PlaceA2B the place (or a
    relay between a dual-arm rig's arms first), each planned from the state the last one
    left. A pick that ends without the target in the hand is planned again
    (``PICK_ATTEMPTS`` in all). A phase that finds no plan, and every episode without a
    target (the generic, empty and absent-object conditions), leaves the robot holding
    still."""

    PICK_ATTEMPTS = 3

    def __init__(self, seed: int = 0, obs_mode: str = "state") -> None:
        self.obs_mode = obs_mode

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return "pd_joint_pos"

    def bind(self, env) -> None:
        self.env = env

    def reset(self, obs) -> None:
        from .demos.script import MotionScript
        from .planning.rig import Rig

        self.obj, self.dest = self.choose(self.env.unwrapped.episode)
        self.script = MotionScript(self.PICK_ATTEMPTS, done=self.obj < 0)
        self.queue: list[np.ndarray] = []
        self.last = Rig.from_env(self.env).hold.astype(np.float32)

    def choose(self, spec) -> tuple[int, int]:
        """(object, receptacle or -1) to go for: the instruction's goal."""
        return spec.target, spec.goal_destination

    def act(self, obs) -> torch.Tensor:
        if not self.queue and not self.script.done:
            with _aimed_at(self.env, self.obj, self.dest):
                motion = self.script.next(self.env)
            if motion is not None and not isinstance(motion, str):
                self.queue = list(motion)
        if self.queue:
            self.last = self.queue.pop(0)
        return torch.from_numpy(self.last)[None]


class PlannerBlindPolicy(PlannerOraclePolicy):
    """The planner oracle's motions for a random candidate (and receptacle): a policy with
    perfect control that ignores the language, which scores about 1/|G|."""

    def __init__(self, seed: int = 0, obs_mode: str = "state") -> None:
        super().__init__(seed, obs_mode)
        self.rng = np.random.default_rng(seed)

    def choose(self, spec) -> tuple[int, int]:
        dest = int(self.rng.choice(spec.destinations)) if spec.destinations else -1
        return int(self.rng.choice(spec.candidates)), dest


@contextmanager
def _aimed_at(env, obj: int, dest: int) -> Iterator[None]:
    """The planners plan for the episode's target and goal receptacle: let them see ``obj``
    and ``dest`` as those while they plan (nothing steps meanwhile)."""
    u = env.unwrapped
    real = u.episodes[0]
    u.episodes[0] = replace(real, target=obj, goal_destination=dest)
    try:
        yield
    finally:
        u.episodes[0] = real


REFERENCE_POLICIES = {
    "oracle": PlannerOraclePolicy,
    "scripted": OraclePolicy,
    "blind": PlannerBlindPolicy,
    "scripted-blind": BlindPolicy,
    "random": RandomPolicy,
}
