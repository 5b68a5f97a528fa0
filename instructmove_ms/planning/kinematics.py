"""Forward and inverse kinematics of one arm of a robot model (SAPIEN's pinocchio model).

Poses are in the robot's base frame. The arm's configuration ``q`` holds only its arm joints;
the other joints (fingers, a second arm) stay at ``ArmKinematics.qpos`` values.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence

import numpy as np
import sapien

from .robot import RobotModel


class ArmKinematics:
    """FK and IK of arm ``arm`` of ``robot`` (its end effector: the arm's TCP), the other
    joints at ``qpos`` (the robot's full configuration)."""

    def __init__(self, robot: RobotModel, arm: int, qpos: np.ndarray) -> None:
        self.links = list(robot.links)
        self.joints = list(robot.joints)
        self.arm = np.array([self.joints.index(n) for n in robot.arms[arm].joints])
        self.ee_index = self.links.index(robot.arms[arm].ee_link)
        self.model = robot.model
        self.lower, self.upper = robot.lower[self.arm], robot.upper[self.arm]
        #: Full configuration the arm joints are written into (fingers etc. keep theirs).
        self.qpos = np.array(qpos, dtype=float)
        self._mask = np.zeros(len(self.joints), dtype=np.int32)
        self._mask[self.arm] = 1

    @property
    def dof(self) -> int:
        return len(self.arm)

    def with_qpos(self, qpos: np.ndarray) -> ArmKinematics:
        """A copy (sharing the model) whose joints outside the arm sit at ``qpos``."""
        out = copy.copy(self)
        out.qpos = np.asarray(qpos, dtype=float)
        return out

    def full(self, q: np.ndarray) -> np.ndarray:
        """The robot's full configuration with the arm joints set to ``q``."""
        full = self.qpos.copy()
        full[self.arm] = q
        return full

    def link_poses(self, q: np.ndarray) -> list[sapien.Pose]:
        """Every link's pose for arm configuration ``q``, in ``self.links`` order."""
        self.model.compute_forward_kinematics(self.full(q))
        return [self.model.get_link_pose(i) for i in range(len(self.links))]

    def fk(self, q: np.ndarray) -> sapien.Pose:
        """End-effector pose for arm configuration ``q``."""
        self.model.compute_forward_kinematics(self.full(q))
        return self.model.get_link_pose(self.ee_index)

    def within_limits(self, q: np.ndarray) -> bool:
        return bool(np.all(q >= self.lower) and np.all(q <= self.upper))

    def ik(
        self,
        pose: sapien.Pose,
        seeds: Sequence[np.ndarray] = (),
        num_random: int = 8,
        rng: np.random.Generator | None = None,
        max_iterations: int = 200,
        accept: Callable[[np.ndarray], bool] | None = None,
    ) -> np.ndarray | None:
        """An arm configuration within the joint limits that puts the end effector at
        ``pose``, or None. Tries ``seeds`` first, then ``num_random`` uniform samples; returns
        the solution closest to the first seed. ``accept(q) -> bool`` can reject solutions
        (e.g. colliding ones)."""
        rng = rng if rng is not None else np.random.default_rng(0)
        starts = [np.asarray(s, dtype=float) for s in seeds]
        starts += [rng.uniform(self.lower, self.upper) for _ in range(num_random)]
        solutions = []
        for start in starts:
            full, ok, _ = self.model.compute_inverse_kinematics(
                self.ee_index,
                pose,
                initial_qpos=self.full(start),
                active_qmask=self._mask,
                max_iterations=max_iterations,
            )
            q = _wrap_into(full[self.arm], self.lower, self.upper)
            if ok and self.within_limits(q) and (accept is None or accept(q)):
                if not seeds:
                    return q
                solutions.append(q)
        if not solutions:
            return None
        ref = np.asarray(seeds[0], dtype=float)
        return min(solutions, key=lambda q: float(np.abs(q - ref).sum()))


def _wrap_into(q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """Shift revolute angles by multiples of 2 pi into [lower, upper] where that is possible."""
    out = q.copy()
    for shift in (2 * np.pi, -2 * np.pi):
        moved = out + shift
        fix = ((out < lower) | (out > upper)) & (moved >= lower) & (moved <= upper)
        out[fix] = moved[fix]
    return out
