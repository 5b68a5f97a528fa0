"""What the shared task engine needs from a robot, whatever its number of arms."""

from __future__ import annotations

import numpy as np
import torch

from instructmove_ms.layout import Workspace


class InstructMoveAgent:
    """Mixin for ManiSkill agents used by InstructMove tasks.

    A subclass provides ``keyframes["rest"]``, ``arm_joint_names`` (every arm joint, all
    arms), ``tcp_links`` (one TCP link per arm) and ``is_grasping(actor)`` (any arm).
    """

    #: Where objects may be placed: the reference workspace, narrowed to the robot's reach.
    workspace = Workspace()

    @property
    def tcp_links(self) -> list:
        raise NotImplementedError

    def tcp_positions(self) -> torch.Tensor:
        """TCP positions of every arm, (N, arms, 3)."""
        return torch.stack([link.pose.p for link in self.tcp_links], dim=1)

    def tcp_state(self) -> torch.Tensor:
        """TCP poses of every arm, flattened: (N, arms * 7)."""
        return torch.cat([link.pose.raw_pose for link in self.tcp_links], dim=-1)

    def sample_init_qpos(self, rng: np.random.Generator, noise: float) -> np.ndarray:
        """The rest keyframe with Gaussian noise (std ``noise`` rad) on the arm joints,
        clamped to the joint limits."""
        qpos = np.asarray(self.keyframes["rest"].qpos, dtype=float).copy()
        names = [j.name for j in self.robot.get_active_joints()]
        arm = [names.index(n) for n in self.arm_joint_names]
        qpos[arm] += rng.normal(0.0, noise, size=len(arm))
        limits = self.robot.get_qlimits()[0].cpu().numpy()
        return np.clip(qpos, limits[:, 0], limits[:, 1])
