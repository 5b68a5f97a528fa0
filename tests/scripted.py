"""Test helpers: move a robot's TCP with ``pd_ee_delta_pose`` (a servo, privileged or blind)."""

from __future__ import annotations

import numpy as np
import torch

from instructmove_ms.policies import CLOSED, OPEN, SERVO_GAIN, STEP_LIMIT

__all__ = ["CLOSED", "OPEN", "choose", "hold", "reach_object", "servo"]


def tcp_position(env, arm: int = 0) -> np.ndarray:
    return env.unwrapped.agent.tcp_positions()[0, arm].cpu().numpy()


def _ee_action(env, arm: int, delta: np.ndarray, gripper: float) -> np.ndarray:
    """A ``pd_ee_delta_pose`` action moving ``arm``'s TCP by ``delta`` (normalised), every
    gripper at ``gripper``."""
    layout = env.unwrapped.agent.action_layout()
    action = np.zeros(env.action_space.shape[-1], dtype=np.float32)
    action[list(layout[arm].command[:3])] = delta
    action[[slots.gripper for slots in layout]] = gripper
    return action


def servo(env, goal, gripper: float, steps: int = 60, tol: float = 0.005, arm: int = 0) -> dict:
    """Move ``arm``'s TCP towards ``goal`` (world xyz, orientation kept); returns the last
    step's info."""
    goal = np.asarray(goal, dtype=float)
    info: dict = {}
    for _ in range(steps):
        delta = np.clip((goal - tcp_position(env, arm)) / STEP_LIMIT * SERVO_GAIN, -1.0, 1.0)
        _, _, _, _, info = env.step(torch.from_numpy(_ee_action(env, arm, delta, gripper))[None])
        if np.linalg.norm(goal - tcp_position(env, arm)) < tol:
            break
    return info


def hold(env, gripper: float, steps: int) -> dict:
    """Keep the TCP where it is for ``steps`` steps with the gripper at ``gripper``."""
    return servo(env, tcp_position(env), gripper, steps, tol=-1.0)


def reach_object(env, index: int, steps: int = 80) -> dict:
    """Go above object ``index``, then onto its top, with the arm whose TCP is nearest;
    returns the final info."""
    u = env.unwrapped
    height = u.catalog[u.episode.objects[index].uuid].height
    top = u.objects[index].pose.p[0].cpu().numpy() + [0.0, 0.0, height]
    tcps = u.agent.tcp_positions()[0].cpu().numpy()
    arm = int(np.argmin(np.linalg.norm(tcps[:, :2] - top[:2], axis=1)))
    clear = max(u.catalog[x.uuid].height for x in u.episode.objects) + 0.08
    servo(env, np.array([top[0], top[1], clear]), OPEN, steps, tol=0.03, arm=arm)
    return servo(env, top - np.array([0.0, 0.0, 0.01]), OPEN, steps, arm=arm)


def choose(spec, rng: np.random.Generator, privileged: bool) -> int:
    """The oracle's object (the target) or the blind policy's (a random candidate)."""
    if privileged:
        return spec.target
    return int(spec.candidates[int(rng.integers(len(spec.candidates)))])
