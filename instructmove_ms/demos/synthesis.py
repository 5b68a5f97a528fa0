"""One planned attempt per episode and family: the synthesizer the demo generator calls.

A synthesizer takes an env just reset to an episode (``pd_joint_pos`` control) and returns
the per-step stage flags of what it executed plus ``None`` on success or the failure reason.
"""

from __future__ import annotations

from collections.abc import Callable

from .pick import PICK_TASKS, plan_pick, rollout

#: Failure reasons, counted per run: no IK solution for any grasp or place pose, no
#: collision-free path, the object left the gripper, the object missed the receptacle.
FAILURES = ("no_ik", "no_plan", "grasp_slipped", "place_missed")

Flags = list[dict[str, bool]]
Synthesizer = Callable[..., tuple[Flags, str | None]]


def synthesize_pick(env) -> tuple[Flags, str | None]:
    """Plan a pick of the target, run it; success is the task's own check at the end."""
    actions = plan_pick(env)
    if isinstance(actions, str):
        return [], actions
    flags = rollout(env, actions)
    return flags, None if flags and flags[-1]["success"] else "grasp_slipped"


def synthesizer(task: str) -> Synthesizer:
    """The synthesizer of ``task``'s family."""
    if task in PICK_TASKS:
        return synthesize_pick
    from .place import synthesize_place  # PlaceA2B

    return synthesize_place
