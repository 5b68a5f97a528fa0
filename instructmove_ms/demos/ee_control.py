"""Recorded ``pd_joint_pos`` demos converted to end-effector control, one end effector per arm.

ManiSkill's replay converts joint-position demos to ``pd_ee_delta_pose`` only for a robot
whose arm controller is keyed ``arm`` with a single end effector. This converter drives every
end-effector controller of the target mode (the PiperX's ``arm_left`` and ``arm_right``, the
Franka's ``arm``). Per recorded step it steps a ``pd_joint_pos`` copy of the env with the
recorded action, takes each end effector's pose at the copy's joint targets (forward
kinematics) as the goal and steps the converted env with the delta from the end effector's
current pose; while a delta had to be clipped to the action range the step is repeated,
``MAX_REPEATS`` times at most. The other controllers (grippers) get the recorded values.
An episode is kept when the converted rollout passes the task's success check.

Outputs follow ManiSkill's naming next to the source (or in ``out_dir``):
``<stem>.<obs_mode>.<control_mode>.physx_cpu.h5`` + ``.json``, which the plain replay plays
to other observation modes, and ``.episodes.json`` with each kept episode's ``EpisodeSpec``
and per-step stage flags of the converted rollout. The files are written into a temporary
folder and moved into place when complete.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch
from mani_skill.agents.controllers import PDEEPosController, PDEEPoseController
from mani_skill.agents.controllers.pd_joint_pos import PDJointPosController
from mani_skill.utils.geometry.rotation_conversions import matrix_to_euler_angles
from mani_skill.utils.gym_utils import inv_scale_action
from mani_skill.utils.wrappers import RecordEpisode
from tqdm import tqdm

from instructmove_ms.export.source import EpisodeSource, Trajectory, load_trajectory
from instructmove_ms.files import OutputLock, clean_stale, staging, write_json
from instructmove_ms.validation import check_choice

MAX_REPEATS = 4  # converted steps per recorded step at most (a clipped delta is repeated)
FRAME = "root_translation:root_aligned_body_rotation"


@dataclass
class ConvertReport:
    """Episodes read and kept (converted rollout successful), and the converted trajectory."""

    total: int
    kept: int
    path: Path


def _joint_goal(env) -> np.ndarray:
    """The robot's qpos with every joint-position controller's joints at their targets."""
    agent = env.unwrapped.agent
    qpos = agent.robot.get_qpos()[0].cpu().numpy().copy()
    for ctrl in agent.controller.controllers.values():
        if isinstance(ctrl, PDJointPosController) and ctrl._target_qpos is not None:
            qpos[ctrl.active_joint_indices.cpu().numpy()] = ctrl._target_qpos[0].cpu().numpy()
    return qpos


def ee_action(ctrl: PDEEPosController, goal) -> tuple[np.ndarray, bool]:
    """The normalised delta action moving ``ctrl``'s end effector to ``goal`` (a
    ``sapien.Pose`` in the robot's root frame), clipped to the action range; also whether it
    had to be clipped."""
    use_target = ctrl.config.use_target and ctrl._target_pose is not None
    current = (ctrl._target_pose if use_target else ctrl.ee_pose_at_base).sp
    low, high = (b[:3].cpu().numpy() for b in (ctrl.action_space_low, ctrl.action_space_high))
    action = inv_scale_action(goal.p - current.p, low, high)
    if isinstance(ctrl, PDEEPoseController):  # the controller scales rotation by rot_lower
        goal_rot, current_rot = (p.to_transformation_matrix()[:3, :3] for p in (goal, current))
        euler = matrix_to_euler_angles(torch.from_numpy(goal_rot @ current_rot.T), "XYZ").numpy()
        action = np.concatenate([action, euler / ctrl.config.rot_lower])
    clipped = bool(np.abs(action[:3]).max() > 1)
    action[:3] = np.clip(action[:3], -1, 1)
    if action.size == 6 and (norm := np.linalg.norm(action[3:])) > 1:
        action[3:] /= norm
        clipped = True
    return action.astype(np.float32), clipped


def _check_controllers(env, control_mode: str) -> list[str]:
    """The end-effector controller keys of ``control_mode``; errors on ones we cannot drive."""
    controllers = env.unwrapped.agent.controller.controllers
    keys = [k for k, c in controllers.items() if isinstance(c, PDEEPosController)]
    if not keys:
        raise ValueError(
            f"control mode {control_mode!r} has no end-effector controller; convert to it with "
            "python -m mani_skill.trajectory.replay_trajectory -c MODE"
        )
    for key in keys:
        config = controllers[key].config
        if config.frame != FRAME or not config.use_delta or not config.normalize_action:
            raise ValueError(
                f"controller {key!r} of {control_mode!r} must be a normalised delta controller "
                f"in the frame {FRAME!r}, got frame={config.frame!r}"
            )
    return keys


class Converter:
    """A ``pd_joint_pos`` source env and a recording target env of the same task, both reset
    to each recorded episode in turn."""

    def __init__(self, env_id: str, env_kwargs: dict, control_mode: str, obs_mode: str, folder):
        self.source = gym.make(env_id, **{**env_kwargs, "obs_mode": "state"})
        modes = self.source.unwrapped.agent.supported_control_modes
        check_choice("control_mode", control_mode, modes)
        target = gym.make(
            env_id, **{**env_kwargs, "obs_mode": obs_mode, "control_mode": control_mode}
        )
        self.keys = _check_controllers(target, control_mode)
        self.name = f"{obs_mode}.{control_mode}.physx_cpu"
        self.target = RecordEpisode(
            target,
            str(folder),
            trajectory_name="converted",
            save_video=False,
            save_on_reset=False,
            source_type="motion_planning",
            source_desc=f"instructmove_ms.demos.ee_control: pd_joint_pos demos to {control_mode}",
        )
        self.stages = self.source.unwrapped.task.stages.flags
        self.pin = self.source.unwrapped.agent.robot.create_pinocchio_model()

    def step(self, action: np.ndarray) -> list[dict[str, bool]]:
        """Play one recorded action; returns the stage flags of each converted step."""
        recorded = self.source.unwrapped.agent.controller.to_action_dict(action)
        self.source.step(action)
        self.pin.compute_forward_kinematics(_joint_goal(self.source))
        controllers = self.target.unwrapped.agent.controller
        flags = []
        for _ in range(MAX_REPEATS):
            actions, clipped = {}, False
            for key, ctrl in controllers.controllers.items():
                if key in self.keys:
                    goal = self.pin.get_link_pose(ctrl.ee_link.index)
                    actions[key], clip = ee_action(ctrl, goal)
                    clipped |= clip
                else:
                    actions[key] = recorded[key]
            step = np.concatenate([actions[key] for key in controllers.controllers])
            _, _, _, _, info = self.target.step(step)
            flags.append({k: bool(info[k][0]) for k in self.stages})
            if not clipped:
                break
        return flags

    def episode(self, reset_kwargs: dict, actions: np.ndarray) -> tuple[list[dict], bool]:
        """Convert one episode; returns its stage flags and whether it succeeded."""
        self.source.reset(**reset_kwargs)
        self.target.reset(**reset_kwargs)
        flags: list[dict[str, bool]] = []
        for action in actions:
            flags += self.step(action)
        return flags, bool(flags and flags[-1]["success"])

    def close(self) -> None:
        self.source.close()
        self.target.close()


def convert(
    traj_path: str | Path,
    control_mode: str = "pd_ee_delta_pose",
    obs_mode: str = "state",
    out_dir: str | Path | None = None,
    count: int | None = None,
) -> ConvertReport:
    """Convert the first ``count`` (default: all) episodes of the ``pd_joint_pos``
    trajectory ``traj_path`` to ``control_mode`` with observations ``obs_mode`` (see the module
    docstring); returns how many episodes were read and kept and the converted ``.h5``."""
    if count is not None and count < 1:
        raise ValueError(f"count must be at least 1, got {count}")
    traj = load_trajectory(traj_path)  # read and checked whole: a fault names its file
    if traj.control_mode != "pd_joint_pos":
        raise ValueError(f"{traj.path} was recorded with {traj.control_mode!r}, not pd_joint_pos")
    episodes = traj.episodes[:count]
    out = Path(out_dir) if out_dir is not None else traj.path.parent
    with OutputLock(out, "instructmove demos convert"):
        clean_stale(out)
        with staging(out) as tmp:
            return _convert(traj, episodes, control_mode, obs_mode, out, tmp)


def _convert(
    traj: Trajectory,
    episodes: tuple[EpisodeSource, ...],
    control_mode: str,
    obs_mode: str,
    out: Path,
    tmp: Path,
) -> ConvertReport:
    """Convert ``episodes`` of ``traj`` in the staging folder ``tmp``, then move the
    outputs into ``out``."""
    converter = Converter(traj.env_id, dict(traj.env_kwargs), control_mode, obs_mode, tmp)
    kept = []
    try:
        for episode in tqdm(episodes, desc=f"to {control_mode}", unit="episode"):
            flags, success = converter.episode(dict(episode.reset_kwargs), episode.actions)
            converter.target.flush_trajectory(save=success)
            if success:
                stages = {k: [step[k] for step in flags] for k in converter.stages}
                spec = converter.target.unwrapped.episode.to_dict()
                kept.append({"episode_id": len(kept), "spec": spec, "stages": stages})
    finally:
        converter.close()
    stem = f"{traj.stem.split('.')[0]}.{converter.name}"
    write_json(tmp / "converted.episodes.json", kept)
    for suffix in (".h5", ".json", ".episodes.json"):
        os.replace(tmp / f"converted{suffix}", out / f"{stem}{suffix}")
    return ConvertReport(len(episodes), len(kept), out / f"{stem}.h5")
