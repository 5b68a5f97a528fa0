"""A relay between the two arms of a dual-arm rig, for a goal the holding arm cannot reach.

The arm holding the target sets it down upright on a free spot of the table between the arms
(leaning towards the other arm), opens, rises and returns to its rest configuration, out of
the other arm's way; the other arm then picks the target up again and carries it on.
"""

from __future__ import annotations

import numpy as np
import sapien

from instructmove_ms.planning import PlanningScene

from .place import PLACE_RESERVE, SETTLE_STEPS, Interior, plan_release

#: Spots (base frame, metres): along the table (x) and across it (y, towards the other arm
#: from the middle between the shoulders), tried nearest ``SPOT`` first.
SPOT_X = (0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50)
SPOT_Y = (-0.15, -0.10, -0.05, 0.0, 0.05, 0.10, 0.15, 0.20, 0.25)
SPOT = (0.33, 0.05)
GAP = 0.03  # metres between the target's footprint (a circle round its box) and other boxes
#: Steps the relay leaves of the horizon for the other arm's pick (hurried) and place.
RESERVE = 130 + PLACE_RESERVE


def spots(scene: PlanningScene, holder: int) -> list[np.ndarray]:
    """Free spots (x, y on the table, base frame) for the target, best first: the circle
    round the target's box keeps ``GAP`` from every other object's box."""
    lo, hi = (np.asarray(b) for b in scene.objects[scene.target].instance.bounds)
    clearance = 0.5 * float(np.linalg.norm((hi - lo)[:2])) + GAP
    boxes = [
        (scene.pose(k), *(np.asarray(b) for b in obj.instance.bounds))
        for k, obj in enumerate(scene.objects)
        if k != scene.target
    ]

    def free(spot: np.ndarray) -> bool:
        for pose, lo, hi in boxes:
            local = (pose.inv() * sapien.Pose([spot[0], spot[1], 0.0])).p[:2]
            if (
                np.linalg.norm(np.maximum(np.maximum(lo[:2] - local, local - hi[:2]), 0.0))
                < clearance
            ):
                return False
        return True

    toward = -1.0 if holder == 0 else 1.0  # arm 0 is the left one (+y)
    grid = [np.array([x, toward * y]) for x in SPOT_X for y in SPOT_Y]
    preferred = np.array([SPOT[0], toward * SPOT[1]])
    return sorted(filter(free, grid), key=lambda s: float(np.linalg.norm(s - preferred)))


def plan_relay(scene: PlanningScene) -> np.ndarray | str:
    """``pd_joint_pos`` actions that set the held target down on the first of ``spots`` that
    works and bring the holding arm back to rest, fitted into the horizon less ``RESERVE``
    steps, or the failure reason of the last spot tried (``"no_ik"`` where none is free)."""
    holder = scene.holding_arm()
    rig = scene.rig(holder)
    home = scene.robot.rest[rig.kin.arm]
    reason = "no_ik"
    for x, y in spots(scene, holder):
        frame = np.eye(4)
        frame[:2, 3] = x, y  # the table's top is the base frame's z = 0
        table = Interior(frame, np.array([1.0, 1.0]), 0.0)
        steps = max(scene.steps_left - RESERVE, SETTLE_STEPS)
        actions = plan_release(scene, rig, table, steps, home=home)
        if not isinstance(actions, str):
            return actions
        reason = actions
    return reason
