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


def tcp_position(env, arm: int = 0) -> np.ndarray:
    return env.unwrapped.agent.tcp_positions()[0, arm].cpu().numpy()


def _ee_action(env, arm: int, delta: np.ndarray, gripper: float) -> np.ndarray:
    """A ``pd_ee_delta_pose`` action moving ``arm``'s TCP by ``delta`` (normalised): the
    Franka's is [xyz, rpy, gripper]; the PiperX's [left xyz rpy, right xyz rpy, grippers]."""
    action = np.zeros(env.action_space.shape[-1], dtype=np.float32)
    arms = env.unwrapped.agent.tcp_positions().shape[1]
    action[6 * arm : 6 * arm + 3] = delta
    action[6 * arms :] = gripper
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


def object_top(env, index: int) -> np.ndarray:
    u = env.unwrapped
    spec = u.episode
    inst = u.catalog[spec.objects[index].uuid]
    return u.objects[index].pose.p[0].cpu().numpy() + np.array([0.0, 0.0, inst.height])


def arm_for(env, xy) -> int:
    """The arm whose base is nearest ``xy`` (the left one for objects on the left)."""
    tcps = env.unwrapped.agent.tcp_positions()[0].cpu().numpy()
    return int(np.argmin(np.linalg.norm(tcps[:, :2] - np.asarray(xy)[:2], axis=1)))


def reach_object(env, index: int, steps: int = 80) -> dict:
    """Go above object ``index``, then onto its top, with the nearest arm; returns the
    final info."""
    top = object_top(env, index)
    arm = arm_for(env, top)
    clear = (
        max(
            o.height for o in (env.unwrapped.catalog[x.uuid] for x in env.unwrapped.episode.objects)
        )
        + 0.08
    )
    servo(env, np.array([top[0], top[1], clear]), OPEN, steps, tol=0.03, arm=arm)
    return servo(env, top - np.array([0.0, 0.0, 0.01]), OPEN, steps, arm=arm)


def choose(spec, rng: np.random.Generator, privileged: bool) -> int:
    """The oracle's object (the target) or the blind policy's (a random candidate)."""
    if privileged:
        return spec.target
    return int(spec.candidates[int(rng.integers(len(spec.candidates)))])
