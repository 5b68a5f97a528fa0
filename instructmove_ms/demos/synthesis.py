"""One planned attempt per episode and family: the synthesizer the demo generator calls.

A synthesizer takes an env just reset to an episode (``pd_joint_pos`` control) and returns
the per-step stage flags of what it executed plus ``None`` on success or the failure reason.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

from .pick import PICK_TASKS, STAGES, rollout
from .place import PLACE_STAGES, SETTLE_STEPS, steps_left
from .script import MotionScript

#: Failure reasons, counted per run: no IK solution for any grasp or place pose, no
#: collision-free path, the object left the gripper, the object missed the receptacle.
FAILURES = ("no_ik", "no_plan", "grasp_slipped", "place_missed")

Flags = list[dict[str, bool]]
Synthesizer = Callable[..., tuple[Flags, str | None]]


def synthesize(env, stages: tuple[str, ...] = STAGES) -> tuple[Flags, str | None]:
    """Play the episode's ``MotionScript`` (one pick attempt) within the horizon; returns the
    ``stages`` flags of every step and None where the task's own success check passes at
    the end, else the failure reason: ``"no_ik"`` / ``"no_plan"`` (a pick, relay or place
    found none), ``"grasp_slipped"`` (not held after a lift) or ``"place_missed"`` (all
    executed, the target does not rest in the receptacle). A dropped object gets up to
    ``SETTLE_STEPS`` to come to rest."""
    script, flags, last = MotionScript(), [], None
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


def synthesizer(task: str) -> Synthesizer:
    """The synthesizer of ``task``'s family."""
    return synthesize if task in PICK_TASKS else partial(synthesize, stages=PLACE_STAGES)
