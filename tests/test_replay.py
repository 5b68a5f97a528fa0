"""Recorded trajectories replay with ManiSkill's own command, its spawned workers included."""

from __future__ import annotations

import json
import subprocess
import sys

import h5py
import numpy as np
from mani_skill.utils.wrappers import RecordEpisode

from conftest import make_env


def _record(out_dir, episodes: int = 2, steps: int = 12) -> str:
    env = make_env(obs_mode="state", render_backend="cpu", control_mode="pd_joint_pos")
    env = RecordEpisode(
        env, str(out_dir), save_video=False, trajectory_name="demo", save_on_reset=True
    )
    rng = np.random.default_rng(0)
    for seed in range(episodes):
        env.reset(seed=seed)
        rest = np.asarray(env.unwrapped.episode.robot_qpos[:8], dtype=np.float32)
        for _ in range(steps):
            action = rest + rng.normal(0, 0.05, size=8).astype(np.float32)
            env.step(action[None])
    env.close()
    return str(out_dir / "demo.h5")


def test_replay_to_rgb_and_delta_control_in_spawned_workers(tmp_path):
    traj = _record(tmp_path)
    cmd = [
        sys.executable,
        "-m",
        "mani_skill.trajectory.replay_trajectory",
        "--traj-path",
        traj,
        "-o",
        "rgb",
        "-c",
        "pd_joint_delta_pos",
        "--save-traj",
        "--num-envs",
        "2",
        "-b",
        "physx_cpu",
        "--allow-failure",
    ]
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=str(tmp_path), timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    converted = tmp_path / "demo.rgb.pd_joint_delta_pos.physx_cpu.h5"
    assert converted.exists()
    meta = json.loads(converted.with_suffix(".json").read_text())
    assert meta["env_info"]["env_id"] == "PickCategory-InstructMove"
    assert len(meta["episodes"]) == 2
    with h5py.File(converted) as f:
        rgb = f["traj_0/obs/sensor_data/ext1_camera/rgb"][()]
        actions = f["traj_0/actions"][()]
        assert rgb.shape[1:] == (90, 160, 3) and rgb.std() > 5
        assert actions.shape[1] == 8


def test_state_replay_reproduces_the_episode(tmp_path):
    traj = _record(tmp_path, episodes=1)
    with h5py.File(traj) as f:
        recorded = f["traj_0/env_states/actors/object_0"][()]
    env = make_env(obs_mode="state")
    meta = json.loads((tmp_path / "demo.json").read_text())
    env.reset(**meta["episodes"][0]["reset_kwargs"])
    pose = env.unwrapped.objects[0].pose.raw_pose[0].numpy()
    np.testing.assert_allclose(pose, recorded[0, :7], atol=1e-5)
    env.close()
