"""One planned attempt per episode and family: the synthesizer the demo generator calls.

A synthesizer takes an env just reset to an episode (``pd_joint_pos`` control) and returns
the per-step stage flags of what it executed plus ``None`` on success or the failure reason.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from .pick import PICK_TASKS, STAGES, rollout
from .place import PLACE_STAGES, SETTLE_STEPS
from .script import MotionScript
from .timing import steps_left

#: Failure reasons, counted per run: no IK solution for any grasp or place pose, no
#: collision-free path, the object left the gripper, the object missed the receptacle.
FAILURES = ("no_ik", "no_plan", "grasp_slipped", "place_missed")
#: Rollouts per scene at most: a grasp that slipped (in physics, though its plan was
#: collision-free) is followed by a rollout with the next grasp plan from a fresh reset.
GRASP_TRIALS = 3

Flags = list[dict[str, bool]]
Synthesizer = Callable[..., tuple[Flags, str | None]]


def synthesize(env, variant: int = 0, stages: tuple[str, ...] = STAGES) -> tuple[Flags, str | None]:
    """Play the episode's ``MotionScript`` (one pick attempt, passing over ``variant`` grasp
    plans) within the horizon; returns the ``stages`` flags of every step and None where the
    task's own success check passes at the end, else the failure reason: ``"no_ik"`` /
    ``"no_plan"`` (a pick, relay or place found none), ``"grasp_slipped"`` (not held after a
    lift) or ``"place_missed"`` (all executed, the target does not rest in the receptacle).
    A dropped object gets up to ``SETTLE_STEPS`` to come to rest."""
    script, flags, last = MotionScript(variant=variant), [], None
    while steps_left(env) > 0 and (motion := script.next(env)) is not None:
        if isinstance(motion, str):
            return flags, motion
        flags += rollout(env, motion[: steps_left(env)], stages)
        last = motion[-1:]
    for _ in range(min(SETTLE_STEPS, steps_left(env))):
        if last is None or flags[-1]["success"]:
            break
        flags += rollout(env, last, stages)
    if flags and flags[-1]["success"]:
        return flags, None
    return flags, "place_missed" if "place" in stages else "grasp_slipped"


def family_stages(task: str) -> tuple[str, ...]:
    """The per-step stage flags recorded for ``task``'s family."""
    return STAGES if task in PICK_TASKS else PLACE_STAGES


def synthesizer(task: str) -> Synthesizer:
    """The synthesizer of ``task``'s family."""
    return partial(synthesize, stages=family_stages(task))


@dataclass(frozen=True)
class SceneOutcome:
    """The last rollout of a scene: its stage flags, failure reason (None: kept), the grasp
    ``variant`` it played and how many rollouts the scene took."""

    flags: Flags
    failure: str | None
    variant: int
    rollouts: int


def synthesize_scene(
    env, seed: int, synthesize: Synthesizer, discard: Callable[[], None] = lambda: None
) -> SceneOutcome:
    """Reset ``env`` to ``seed`` and synthesize; a rollout that fails after moving is
    discarded (``discard``, e.g. dropping a recorder's buffer) and the scene is reset and
    tried with the next grasp plan, ``GRASP_TRIALS`` rollouts at most. A failure before any
    motion (no IK or plan) ends the scene: further variants only have fewer plans."""
    rollouts = 0
    for variant in range(GRASP_TRIALS):
        env.reset(seed=seed)
        flags, failure = synthesize(env, variant)
        rollouts += bool(flags)
        if failure is None or not flags or variant == GRASP_TRIALS - 1:
            break
        discard()
    return SceneOutcome(flags, failure, variant, rollouts)
