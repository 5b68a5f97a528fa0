"""Planned motions as ``pd_joint_pos`` actions within the episode's horizon: joint paths are
time-parametrized at the least speed-up of the rig's joint limits that fits the steps left
to them, holds are played as they are."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from instructmove_ms.planning import Rig, time_parametrize

SPEEDUPS = (1.0, 1.5, 2.0)  # of the rig's joint limits, where the horizon asks for it


@dataclass(frozen=True)
class Segment:
    """Arm joint targets with the gripper action ``gripper``: a path to time-parametrize, or
    (``hold``) targets played one per step as they are."""

    targets: np.ndarray
    gripper: float
    hold: bool = False


def hold(q: np.ndarray, steps: int, gripper: float) -> Segment:
    """Configuration ``q`` held for ``steps`` steps."""
    return Segment(np.repeat(np.asarray(q)[None], steps, axis=0), gripper, hold=True)


def fitted(rig: Rig, segments: list[Segment], steps: int) -> np.ndarray:
    """The actions of ``segments`` in order, sped up by the least of ``SPEEDUPS`` that fits
    them into ``steps`` (the fastest where none does)."""
    for speedup in SPEEDUPS:
        limits = rig.limits.faster(speedup)
        actions = np.vstack(
            [
                rig.actions(s.targets if s.hold else time_parametrize(s.targets, limits), s.gripper)
                for s in segments
            ]
        )
        if len(actions) <= steps:
            break
    return actions
