"""One planned attempt per episode and family: the synthesizer the demo generator calls.

A synthesizer takes an env just reset to an episode (``pd_joint_pos`` control) and returns
the per-step stage flags of what it executed plus ``None`` on success or the failure reason.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import torch

from instructmove_ms.planning import PlanningScene
from instructmove_ms.tasks.visibility import hidden_objects, measure

from .place import SETTLE_STEPS
from .script import MotionScript

#: Failure reasons, counted per run: no IK solution for any grasp or place pose, no
#: collision-free path, the object left the gripper, the object missed the receptacle.
FAILURES = ("hidden", "no_ik", "no_plan", "grasp_slipped", "place_missed")
#: Rollouts per scene at most: a grasp that slipped (in physics, though its plan was
#: collision-free) is followed by a rollout with the next grasp plan from a fresh reset.
GRASP_TRIALS = 3

Flags = list[dict[str, bool]]
Synthesizer = Callable[[object, int], tuple[Flags, str | None]]


def synthesize(env, variant: int = 0) -> tuple[Flags, str | None]:
    """Play the episode's ``MotionScript`` (one pick attempt, passing over ``variant`` grasp
    plans) within the horizon; returns the family's per-step stage flags
    (``StageSchema.flags``) and None where the task's own success check passes at the end,
    else the failure reason: ``"no_ik"`` / ``"no_plan"`` (a pick, relay or place found
    none), ``"grasp_slipped"`` (not held after a lift, or never placed in an episode
    without a receptacle) or ``"place_missed"`` (all executed, the target does not rest in
    the receptacle). A dropped object gets up to ``SETTLE_STEPS`` to come to rest."""
    scene = PlanningScene.from_env(env)
    script, flags, last = MotionScript(scene, variant=variant), [], None
    while steps_left(env) > 0 and (motion := script.next(env)) is not None:
        if isinstance(motion, str):
            return flags, motion
        flags += rollout(env, motion[: steps_left(env)])
        last = motion[-1:]
    for _ in range(min(SETTLE_STEPS, steps_left(env))):
        if last is None or flags[-1]["success"]:
            break
        flags += rollout(env, last)
    if flags and flags[-1]["success"]:
        return flags, None
    return flags, "place_missed" if scene.destination >= 0 else "grasp_slipped"


def steps_left(env) -> int:
    """Steps left in the episode's horizon."""
    u = env.unwrapped
    return u.task.max_episode_steps - int(u.elapsed_steps[0])


def rollout(env, actions: np.ndarray) -> list[dict[str, bool]]:
    """Step ``env`` through ``actions``; returns each step's stage flags (the family's
    ``StageSchema.flags``) of the single sub-scene; the last one is the outcome. Stops early
    at truncation."""
    stages, flags = env.unwrapped.task.stages.flags, []
    for action in actions:
        _, _, _, truncated, info = env.step(torch.from_numpy(action)[None])
        flags.append({k: bool(info[k][0]) for k in stages})
        if bool(truncated):
            break
    return flags


@dataclass(frozen=True)
class SceneOutcome:
    """The last rollout of a scene: its stage flags, failure reason (None: kept), the grasp
    ``variant`` it played and how many rollouts the scene took."""

    flags: Flags
    failure: str | None
    variant: int
    rollouts: int


def synthesize_scene(
    env,
    seed: int,
    discard: Callable[[], None] = lambda: None,
    synthesizer: Synthesizer = synthesize,
) -> SceneOutcome:
    """Reset ``env`` to ``seed`` and synthesize; a rollout that fails after moving is
    discarded (``discard``, e.g. dropping a recorder's buffer) and the scene is reset and
    tried with the next grasp plan, ``GRASP_TRIALS`` rollouts at most. A failure before any
    motion (no IK or plan) ends the scene: further variants only have fewer plans. A scene
    whose candidates or receptacles the scene cameras do not show (``tasks.visibility``)
    is left out as ``"hidden"`` before any motion."""
    rollouts = 0
    for variant in range(GRASP_TRIALS):
        env.reset(seed=seed)
        if variant == 0 and hidden_objects(measure(env)):
            return SceneOutcome([], "hidden", 0, 0)
        flags, failure = synthesizer(env, variant)
        rollouts += bool(flags)
        if failure is None or not flags or variant == GRASP_TRIALS - 1:
            break
        discard()
    return SceneOutcome(flags, failure, variant, rollouts)
