"""A tiny scripted end-effector controller for physics tests (pd_ee_delta_pose)."""

from __future__ import annotations

import numpy as np
import torch

OPEN, CLOSED = 1.0, -1.0


def tcp(env) -> np.ndarray:
    return env.unwrapped.agent.tcp_pose.p[0].cpu().numpy()


def move_to(env, goal, gripper: float, steps: int = 60, tol: float = 0.004):
    """Servo the TCP to ``goal`` (world xyz) with fixed orientation; returns the last info."""
    info = {}
    for _ in range(steps):
        delta = (np.asarray(goal) - tcp(env)) / 0.1
        action = np.zeros(7, dtype=np.float32)
        action[:3] = np.clip(delta * 1.5, -1.0, 1.0)
        action[6] = gripper
        _, _, _, _, info = env.step(torch.from_numpy(action)[None])
        if np.linalg.norm(np.asarray(goal) - tcp(env)) < tol:
            break
    return info


def hold(env, gripper: float, steps: int):
    info = {}
    for _ in range(steps):
        action = np.zeros(7, dtype=np.float32)
        action[6] = gripper
        _, _, _, _, info = env.step(torch.from_numpy(action)[None])
    return info
