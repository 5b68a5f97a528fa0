"""Forward and inverse kinematics of one arm of a live env's robot (SAPIEN's pinocchio model).

Poses are in the robot's base frame. The arm's configuration ``q`` holds only its arm joints;
the other joints (fingers, a second arm) stay at ``ArmKinematics.qpos`` values.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence

import numpy as np
import sapien


class ArmKinematics:
    """FK and IK for the joints ``joint_names`` of ``robot``, with ``ee_link`` as end effector.

    ``robot`` is a ManiSkill articulation (``env.unwrapped.agent.robot``, one sub-scene).
    """

    def __init__(self, robot, joint_names: Sequence[str], ee_link: str) -> None:
        self.links = [link.name for link in robot.get_links()]
        self.joints = [j.name for j in robot.get_active_joints()]
        self.arm = np.array([self.joints.index(n) for n in joint_names])
        self.ee_index = self.links.index(ee_link)
        self.model = robot._objs[0].create_pinocchio_model()
        limits = robot.get_qlimits()[0].cpu().numpy().astype(float)
        self.lower, self.upper = limits[self.arm, 0], limits[self.arm, 1]
        #: Full configuration the arm joints are written into (fingers etc. keep theirs).
        self.qpos = robot.get_qpos()[0].cpu().numpy().astype(float)
        self._mask = np.zeros(len(self.joints), dtype=np.int32)
        self._mask[self.arm] = 1

    @classmethod
    def from_env(cls, env, arm: int = 0) -> ArmKinematics:
        """The kinematics of arm ``arm`` of the env's agent (Franka: the only arm)."""
        agent = env.unwrapped.agent
        return cls(agent.robot, arm_joint_names(agent, arm), agent.tcp_links[arm].name)

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


def arm_joint_names(agent, arm: int) -> list[str]:
    """The joints of arm ``arm`` of an InstructMove agent (which lists every arm joint, arm
    by arm, in ``arm_joint_names``)."""
    names = list(agent.arm_joint_names)
    per_arm = len(names) // len(agent.tcp_links)
    return names[arm * per_arm : (arm + 1) * per_arm]


def _wrap_into(q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """Shift revolute angles by multiples of 2 pi into [lower, upper] where that is possible."""
    out = q.copy()
    for shift in (2 * np.pi, -2 * np.pi):
        moved = out + shift
        fix = ((out < lower) | (out > upper)) & (moved >= lower) & (moved <= upper)
        out[fix] = moved[fix]
    return out
