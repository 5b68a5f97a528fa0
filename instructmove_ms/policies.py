"""Reference policies in ManiSkill's evaluator convention.

A policy is a class with ``get_obs_mode()``, ``get_control_mode()``, ``reset(obs)`` and
``act(obs)``. ``reset`` may take ``seed``, the episode's own seed: the random ones here draw
from a generator seeded by (their own seed, the episode's), so an episode's choices do not
depend on which episodes the process ran before it (a resumed evaluation scores what an
uninterrupted one does). Privileged reference policies also get ``bind(env)``, which the
evaluator calls before each episode; they read the episode through a ``PlanningScene``
built for the object (and receptacle) they go for (a learned policy never does).

- ``OraclePolicy`` (``oracle``): plays the demo generator's collision-free planned pick
  (and place) of the instruction's target (privileged): the upper bound.
- ``BlindPolicy`` (``blind``): the oracle's planned motions for a random candidate: what a
  policy that ignores the language can score (about 1/|G|).
- ``ScriptedOraclePolicy`` (``scripted``): a scripted top-down servo to the instruction's
  target that grasps and lifts it; with a receptacle it then carries it over it and opens.
- ``ScriptedBlindPolicy`` (``scripted-blind``): the scripted skill on a random candidate.
- ``RandomPolicy`` (``random``): random actions.
- ``GroundedPolicy`` (``grounded[:CHECKPOINT]``, the shipped checkpoint by default): a
  learned grounding model's choice from the first step's cameras and the instruction, then
  the oracle's planned motions for it.
"""

from __future__ import annotations

import numpy as np
import torch

from .demos.script import MotionScript
from .episode import EpisodeSpec
from .planning import PlanningScene

GRASP_DEPTH = 0.035  # below an object's top, where the fingers close
CLEARANCE = 0.08  # above the tallest object while moving across the table
MAX_WAYPOINT_STEPS = 90  # give up on a waypoint the arm cannot reach
SERVO_GAIN = 1.5
STEP_LIMIT = 0.1  # metres per unit action of pd_ee_delta_pose
OPEN, CLOSED = 1.0, -1.0  # normalised gripper actions


def goal_of(spec: EpisodeSpec) -> tuple[int, int]:
    """(object, receptacle or -1): the instruction's goal."""
    return spec.target, spec.goal_destination


class Seeded:
    """A policy's randomness: a generator seeded by the policy's ``seed``, re-seeded for each
    episode by (``seed``, the episode's seed) when the evaluator passes one."""

    def __init__(self, seed: int = 0) -> None:
        self.seed, self.rng = seed, np.random.default_rng(seed)

    def reseed(self, episode_seed: int | None) -> None:
        if episode_seed is not None:
            self.rng = np.random.default_rng([self.seed, episode_seed])


def random_goal(spec: EpisodeSpec, rng: np.random.Generator) -> tuple[int, int]:
    """A random candidate (and receptacle): the choice of a policy that ignores the text."""
    dest = int(rng.choice(spec.destinations)) if spec.destinations else -1
    return int(rng.choice(spec.candidates)), dest


class RandomPolicy(Seeded):
    def __init__(self, seed: int = 0, obs_mode: str = "state") -> None:
        super().__init__(seed)
        self.obs_mode = obs_mode
        self.space = None

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return "pd_joint_delta_pos"

    def bind(self, env) -> None:
        self.space = env.action_space

    def reset(self, obs, seed: int | None = None) -> None:
        self.reseed(seed)

    def act(self, obs) -> np.ndarray:
        low, high = self.space.low, self.space.high
        return self.rng.uniform(low, high).astype(np.float32)


class ScriptedOraclePolicy(Seeded):
    """Top-down scripted pick (and place) of a chosen object, with the arm whose TCP is
    nearest, by servoing its TCP with ``pd_ee_delta_pose``."""

    def __init__(self, seed: int = 0) -> None:
        super().__init__(seed)
        self.env = None

    def get_obs_mode(self) -> str:
        return "state"

    def get_control_mode(self) -> str:
        return "pd_ee_delta_pose"

    def choose(self, spec: EpisodeSpec) -> tuple[int, int]:
        """(object, receptacle or -1): the goal, or random ones when there is none."""
        obj, dest = goal_of(spec)
        if obj < 0:
            obj = int(self.rng.choice(spec.candidates))
        if spec.destinations and dest < 0:
            dest = int(self.rng.choice(spec.destinations))
        return obj, dest

    def bind(self, env) -> None:
        self.env = env

    def reset(self, obs, seed: int | None = None) -> None:
        self.reseed(seed)
        scene = PlanningScene.from_env(self.env, *self.choose(self.env.unwrapped.episode))
        inst = scene.objects[scene.target].instance
        top = scene.pose(scene.target).p + [0.0, 0.0, inst.height]
        clear = max(o.instance.height for o in scene.objects) + CLEARANCE
        grasp = top - [0.0, 0.0, min(GRASP_DEPTH, inst.height / 2)]
        tcps = scene.state.tcps[:, :2]  # the arm whose TCP is nearest
        self.arm = int(np.argmin(np.linalg.norm(tcps - top[:2], axis=1)))
        self.layout = self.env.unwrapped.agent.action_layout()
        plan = [
            ([*top[:2], clear], OPEN, 0.03),
            (grasp, OPEN, 0.006),
            (grasp, CLOSED, -12),
            ([*top[:2], clear], CLOSED, 0.02),
        ]
        if scene.destination >= 0:
            region = scene.objects[scene.destination].instance.interior
            centre = scene.pose(scene.destination).p + np.asarray(region.center)
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
        here = self.env.unwrapped.agent.tcp_positions()[0, self.arm].cpu().numpy()
        delta = np.clip((np.asarray(goal) - here) / STEP_LIMIT * SERVO_GAIN, -1.0, 1.0)
        close = tol > 0 and np.linalg.norm(goal - here) < tol
        done = close or (tol < 0 and self.waited >= -tol) or self.waited >= MAX_WAYPOINT_STEPS
        self.waited = 0 if done else self.waited + 1
        if done and len(self.plan) > 1:
            self.plan = self.plan[1:]
        action = np.zeros(self.env.action_space.shape[-1], dtype=np.float32)
        action[list(self.layout[self.arm].command[:3])] = delta
        action[[slots.gripper for slots in self.layout]] = gripper
        return torch.from_numpy(action)[None]


class ScriptedBlindPolicy(ScriptedOraclePolicy):
    """The scripted skill on a random candidate (and receptacle): it ignores the text."""

    def choose(self, spec: EpisodeSpec) -> tuple[int, int]:
        return random_goal(spec, self.rng)


class OraclePolicy(Seeded):
    """Privileged: plays the demo generator's planned motions (``demos.script``) for the
    instruction's target (``pd_joint_pos``): the pick, then with a receptacle the place (or
    a relay between a dual-arm rig's arms first), each planned from the state the last one
    left. A pick that ends without the target in the hand is planned again
    (``PICK_ATTEMPTS`` in all). A phase that finds no plan, and every episode without a
    target (the generic, empty and absent-object conditions), leaves the robot holding
    still."""

    PICK_ATTEMPTS = 3

    def __init__(self, seed: int = 0, obs_mode: str = "state") -> None:
        super().__init__(seed)
        self.obs_mode = obs_mode

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return "pd_joint_pos"

    def bind(self, env) -> None:
        self.env = env

    def reset(self, obs, seed: int | None = None) -> None:
        self.reseed(seed)
        self.goal = obj, dest = self.choose(self.env.unwrapped.episode)
        scene = PlanningScene.from_env(self.env, obj, dest)
        self.script = MotionScript(scene, self.PICK_ATTEMPTS, done=obj < 0)
        self.queue: list[np.ndarray] = []
        self.last = scene.robot.hold(scene.state.qpos).astype(np.float32)

    def choose(self, spec: EpisodeSpec) -> tuple[int, int]:
        """(object, receptacle or -1) to go for: the instruction's goal."""
        return goal_of(spec)

    def act(self, obs) -> torch.Tensor:
        if not self.queue and not self.script.done:
            motion = self.script.next(self.env)
            if motion is not None and not isinstance(motion, str):
                self.queue = list(motion)
        if self.queue:
            self.last = self.queue.pop(0)
        return torch.from_numpy(self.last)[None]


class BlindPolicy(OraclePolicy):
    """The oracle's planned motions for a random candidate (and receptacle): a policy with
    perfect control that ignores the language, which scores about 1/|G|."""

    def choose(self, spec: EpisodeSpec) -> tuple[int, int]:
        return random_goal(spec, self.rng)


class GroundedPolicy(OraclePolicy):
    """Chooses the object (and receptacle) with a grounding model (``grounding``: crops of
    the candidates in the 224 x 224 cameras at the first step, located by segmentation, and
    the instruction), then plays the oracle's planned motions for its choice: a learned
    chooser with perfect control. Trained without the instruction, it is the image-only
    twin."""

    SIDE = 224  # the cameras' resolution the model learned from

    def __init__(self, checkpoint=None, seed: int = 0) -> None:
        from .grounding import CHECKPOINT
        from .grounding.training import load

        super().__init__(seed)
        self.model = load(checkpoint or CHECKPOINT)

    def get_sensor_configs(self) -> dict:
        return {"width": self.SIDE, "height": self.SIDE}

    def choose(self, spec: EpisodeSpec) -> tuple[int, int]:
        from .audit.choices import decisions
        from .grounding.crops import of_views
        from .grounding.training import choose
        from .readers.material import views_of

        picked = choose(self.model, of_views(views_of(self.env), spec, goal=False))
        goals = [o[p] for (_, o, _), p in zip(decisions(spec, goal=False), picked, strict=True)]
        return goals[0], goals[1] if len(goals) > 1 else -1


REFERENCE_POLICIES = {
    "oracle": OraclePolicy,
    "blind": BlindPolicy,
    "scripted": ScriptedOraclePolicy,
    "scripted-blind": ScriptedBlindPolicy,
    "random": RandomPolicy,
    "grounded": GroundedPolicy,  # the shipped checkpoint; grounded:CHECKPOINT for another
}
