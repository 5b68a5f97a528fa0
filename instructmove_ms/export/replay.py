"""Replaying recorded env states in a rendering env: camera frames, joints, links, objects.

Trajectories are recorded with ``obs_mode="state"``, so the cameras have to be rendered
afterwards. Two passes per episode: the first steps the recorded actions from each restored
state (ManiSkill's replay with env states) to get the env's own per-step info, which needs
contacts, and the drive targets each action set; the second restores every recorded state
exactly and renders it. The env runs with ``obs_mode="state"`` and the robot's cameras are
captured only in the second pass, so no frame is rendered twice. The env keeps the recorded
render backend (``cpu`` if it was recorded without one).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import gymnasium as gym
import numpy as np
import sapien
import torch
from mani_skill.sensors.camera import Camera

from instructmove_ms.agents.interface import PolicyInterface

from .source import EpisodeSource, Trajectory, TrajectoryError


@dataclass(frozen=True)
class CameraFrame:
    rgb: np.ndarray  # (H, W, 3) uint8
    depth_mm: np.ndarray | None  # (H, W) uint16, z depth in mm, 0 where nothing was hit
    intrinsic: np.ndarray  # (3, 3) OpenCV camera matrix
    pose: np.ndarray  # (7,) optical frame in the world: x, y, z, qw, qx, qy, qz


@dataclass(frozen=True)
class Frame:
    """What one recorded env state shows; joint arrays follow :attr:`RobotParts.joint_names`."""

    step: int
    qpos: np.ndarray
    qvel: np.ndarray
    effort: np.ndarray
    links: np.ndarray  # (L, 7) world poses of :attr:`RobotParts.link_names`
    objects: np.ndarray  # (K, 7) world poses of the episode's objects, in spec order
    cameras: dict[str, CameraFrame]


@dataclass(frozen=True)
class RobotParts:
    """Names of the robot's parts, fixed for an env."""

    joint_names: tuple[str, ...]
    arms: dict[str, tuple[int, ...]]  # arm -> indices into joint_names
    link_names: tuple[str, ...]
    action_names: tuple[str, ...]
    cameras: tuple[str, ...]
    control_freq: float


_SIM_STATE = ("actors", "articulations")  # what set_state_dict restores
_GAINS = ("stiffness", "damping", "force_limit")  # of each joint drive


def arm_joints(agent, joint_names: list[str]) -> dict[str, tuple[int, ...]]:
    """Active joints per arm: ``left``/``right`` for a robot with ``sides`` (joint names
    prefixed by the side), else one arm ``arm`` holding every joint."""
    sides = [s for s in getattr(agent, "sides", ()) if s] or [""]
    return {
        side or "arm": tuple(
            i for i, n in enumerate(joint_names) if not side or n.startswith(f"{side}_")
        )
        for side in sides
    }


def action_names(agent) -> tuple[str, ...]:
    """``controller[i]`` for each action dimension, in action order."""
    controllers = getattr(agent.controller, "controllers", {"action": agent.controller})
    return tuple(
        f"{key}[{i}]"
        for key, ctrl in controllers.items()
        for i in range(ctrl.single_action_space.shape[0])
    )


def _row(x: torch.Tensor) -> np.ndarray:
    return x[0].detach().cpu().numpy().astype(np.float64)


def _pose_of_matrix(matrix: np.ndarray) -> np.ndarray:
    pose = sapien.Pose(matrix.astype(np.float32))
    return np.concatenate([pose.p, pose.q]).astype(np.float64)


class Replayer:
    """One rendering env for a trajectory's episodes (cameras at ``width`` x ``height`` when
    given, else the robot's defaults)."""

    def __init__(self, traj: Trajectory, width: int | None = None, height: int | None = None):
        kwargs = dict(traj.env_kwargs, obs_mode="state")
        if kwargs.get("render_backend", "none") == "none":  # recorded without a renderer
            kwargs["render_backend"] = "cpu"
        if width is not None or height is not None:
            kwargs["sensor_configs"] = {
                k: v for k, v in (("width", width), ("height", height)) if v is not None
            }
        self.traj = traj
        self.env = gym.make(traj.env_id, **kwargs)

    def close(self) -> None:
        self.env.close()

    @property
    def _u(self):
        return self.env.unwrapped

    def rig(self) -> RobotParts:
        agent = self._u.agent
        names = [j.name for j in agent.robot.get_active_joints()]
        return RobotParts(
            joint_names=tuple(names),
            arms=arm_joints(agent, names),
            link_names=tuple(link.name for link in agent.robot.get_links()),
            action_names=action_names(agent),
            cameras=tuple(n for n, s in self._u.scene.sensors.items() if isinstance(s, Camera)),
            control_freq=float(self._u.control_freq),
        )

    def _restore(self, ep: EpisodeSource, k: int) -> None:
        state = {
            group: {name: torch.as_tensor(v[k][None]) for name, v in ep.states[group].items()}
            for group in _SIM_STATE
        }
        self._u.set_state_dict(state)

    def _check_states(self, ep: EpisodeSource) -> None:
        """The recorded states must cover exactly the bodies of the env's scene."""
        scene = self._u.get_state_dict()
        want = sorted(f"{g}/{n}" for g in _SIM_STATE for n in scene.get(g, {}))
        have = sorted(f"{g}/{n}" for g in _SIM_STATE for n in ep.states.get(g, {}))
        if have != want:
            raise TrajectoryError(
                f"{self.traj.path}: traj_{ep.episode_id} holds env states of {have}, but "
                f"{self.traj.env_id}'s scene has {want}"
            )

    def _effort(self, gains: np.ndarray) -> np.ndarray:
        """The PD drives' commanded effort, K (q* - q) + D (qd* - qd) clipped to the force
        limit; ``gains`` holds K, D and the limit per active joint."""
        robot = self._u.agent.robot
        k, d, limit = gains
        force = k * (_row(robot.get_drive_targets()) - _row(robot.get_qpos())) + d * (
            _row(robot.get_drive_velocities()) - _row(robot.get_qvel())
        )
        return np.clip(force, -limit, limit)

    def start(self, ep: EpisodeSource) -> tuple[RobotParts, dict, np.ndarray]:
        """Reset to ``ep`` and step its actions from its restored states: returns the rig,
        the last step's info (plain values) and the drive effort at every state."""
        self.env.reset(**ep.reset_kwargs)
        self._check_states(ep)
        joints = self._u.agent.robot.get_active_joints()
        gains = np.array(
            [[float(getattr(j, key)[0]) for j in joints] for key in _GAINS], dtype=np.float64
        )
        self._restore(ep, 0)
        efforts = [self._effort(gains)]
        info: dict = {}
        for k, action in enumerate(ep.actions):
            _, _, _, _, info = self.env.step(torch.from_numpy(action)[None])
            self._restore(ep, k + 1)
            efforts.append(self._effort(gains))
        return self.rig(), _plain(info), np.asarray(efforts)

    def policy_interface(self) -> PolicyInterface:
        """The robot's joint-space policy interface (the state and action layout)."""
        return self._u.agent.policy_interface()

    def frames(
        self, ep: EpisodeSource, efforts: np.ndarray, steps: int | None = None, depth: bool = True
    ) -> Iterator[Frame]:
        """The first ``steps`` (default: every) recorded states of ``ep`` (after
        :meth:`start`), rendered (colour, and depth unless ``depth`` is False)."""
        u = self._u
        robot = u.agent.robot
        for k in range(ep.steps + 1 if steps is None else steps):
            self._restore(ep, k)
            yield Frame(
                step=k,
                qpos=_row(robot.get_qpos()),
                qvel=_row(robot.get_qvel()),
                effort=efforts[k],
                links=np.stack([_row(link.pose.raw_pose) for link in robot.get_links()]),
                objects=np.array([_row(obj.pose.raw_pose) for obj in u.objects]).reshape(-1, 7),
                cameras=self._render(depth),
            )

    def _render(self, depth: bool) -> dict[str, CameraFrame]:
        u = self._u
        u.scene.update_render(update_sensors=True, update_human_render_cameras=False)
        u.capture_sensor_data()
        params = u.get_sensor_params()
        out = {}
        for name, sensor in u.scene.sensors.items():
            if not isinstance(sensor, Camera):
                continue
            obs = sensor.get_obs(rgb=True, depth=depth, position=False, segmentation=False)
            world_to_cam = np.eye(4)
            world_to_cam[:3] = params[name]["extrinsic_cv"][0].cpu().numpy()
            out[name] = CameraFrame(
                rgb=obs["rgb"][0].cpu().numpy(),
                depth_mm=obs["depth"][0, ..., 0].cpu().numpy().clip(min=0).astype(np.uint16)
                if depth
                else None,
                intrinsic=params[name]["intrinsic_cv"][0].cpu().numpy().astype(np.float64),
                pose=_pose_of_matrix(np.linalg.inv(world_to_cam)),
            )
        return out


def _plain(info: dict) -> dict:
    """An info dict of single-env tensors as JSON values (non-finite floats become None)."""
    out = {}
    for key, value in info.items():
        v = value.reshape(-1)[0].item() if hasattr(value, "reshape") else value
        out[key] = None if isinstance(v, float) and not np.isfinite(v) else v
    return out
