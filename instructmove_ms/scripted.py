"""Scripted reference behaviour: move the TCP over an object, privileged or blind.

The oracle goes to the instruction's target (privileged); the language-blind policy goes to
a random candidate. Both servo the TCP with the ``pd_ee_delta_pose`` controller: above the
object first, then down onto its top.
"""

from __future__ import annotations

import numpy as np
import torch

SERVO_GAIN = 1.5
STEP_LIMIT = 0.1  # metres per unit action of pd_ee_delta_pose
OPEN, CLOSED = 1.0, -1.0  # normalised gripper actions


def tcp_position(env) -> np.ndarray:
    return env.unwrapped.agent.tcp_positions()[0, 0].cpu().numpy()


def servo(env, goal, gripper: float, steps: int = 60, tol: float = 0.005) -> dict:
    """Move the first arm's TCP towards ``goal`` (world xyz, orientation kept); returns the
    last step's info."""
    goal = np.asarray(goal, dtype=float)
    info: dict = {}
    for _ in range(steps):
        action = np.zeros(env.action_space.shape[-1], dtype=np.float32)
        action[:3] = np.clip((goal - tcp_position(env)) / STEP_LIMIT * SERVO_GAIN, -1.0, 1.0)
        action[6] = gripper
        _, _, _, _, info = env.step(torch.from_numpy(action)[None])
        if np.linalg.norm(goal - tcp_position(env)) < tol:
            break
    return info


def hold(env, gripper: float, steps: int) -> dict:
    """Keep the TCP where it is for ``steps`` steps with the gripper at ``gripper``."""
    return servo(env, tcp_position(env), gripper, steps, tol=-1.0)


def object_top(env, index: int) -> np.ndarray:
    u = env.unwrapped
    spec = u.episode
    inst = u.catalog[spec.objects[index].uuid]
    return u.objects[index].pose.p[0].cpu().numpy() + np.array([0.0, 0.0, inst.height])


def reach_object(env, index: int, steps: int = 80) -> dict:
    """Go above object ``index``, then onto its top; returns the final info."""
    top = object_top(env, index)
    clear = (
        max(
            o.height for o in (env.unwrapped.catalog[x.uuid] for x in env.unwrapped.episode.objects)
        )
        + 0.08
    )
    servo(env, np.array([top[0], top[1], clear]), 1.0, steps, tol=0.03)
    return servo(env, top - np.array([0.0, 0.0, 0.01]), 1.0, steps)


def choose(spec, rng: np.random.Generator, privileged: bool) -> int:
    """The oracle's object (the target) or the blind policy's (a random candidate)."""
    if privileged:
        return spec.target
    return int(spec.candidates[int(rng.integers(len(spec.candidates)))])
