"""Float noise for tests: floats moved by a few ULPs, the stored held-out sets, the robots'
grippers."""

from __future__ import annotations

import math

from instructmove_ms.assets.catalog import Instance
from instructmove_ms.heldout import load_set
from instructmove_ms.splits import EVAL_SPLITS
from instructmove_ms.tasks import TASKS

ROBOTS = ("franka", "piperx")


def nudged(value, ulps: int):
    """``value`` with every float moved ``ulps`` ULPs (up for even positions in a sequence,
    down for odd ones), the other values as they are."""
    if isinstance(value, float):
        step = math.inf if ulps > 0 else -math.inf
        for _ in range(abs(ulps)):
            value = math.nextafter(value, step)
        return value
    if isinstance(value, list | tuple):
        return type(value)(nudged(v, ulps if k % 2 == 0 else -ulps) for k, v in enumerate(value))
    if isinstance(value, dict):
        return {k: nudged(v, ulps) for k, v in value.items()}
    return value


def nudged_instance(inst: Instance, ulps: int) -> Instance:
    return Instance.from_record(nudged(inst.to_record(), ulps))


def stored_sets():
    for env_id in sorted(TASKS):
        for robot in ROBOTS:
            for split in EVAL_SPLITS:
                yield env_id, robot, split, load_set(env_id, robot, split)


def opening(robot: str) -> float:
    from mani_skill.agents.registration import REGISTERED_AGENTS

    return REGISTERED_AGENTS[robot].agent_cls.gripper.max_width
