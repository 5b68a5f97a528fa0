"""ManiSkill observation modes, cameras and wrappers on the CPU renderer."""

from __future__ import annotations

import numpy as np
import pytest
from mani_skill.utils.wrappers import FlattenRGBDObservationWrapper
from mani_skill.vector.wrappers.gymnasium import ManiSkillVectorEnv

from conftest import make_env

CAMERAS = ("ext1_camera", "ext2_camera", "wrist_camera")


@pytest.mark.parametrize("obs_mode", ["state", "state_dict"])
def test_state_modes_hold_every_object(obs_mode):
    env = make_env(obs_mode=obs_mode)
    obs, _ = env.reset(seed=0)
    if obs_mode == "state":
        assert obs.ndim == 2 and obs.shape[0] == 1
    else:
        assert obs["extra"]["obj_pose"].shape == (1, 6 * 7)
        assert obs["extra"]["tcp_pose"].shape == (1, 7)
    env.close()


def test_rgbd_cameras_see_the_scene():
    env = make_env(obs_mode="rgbd", render_backend="cpu", render_mode="rgb_array")
    obs, _ = env.reset(seed=0)
    for cam in CAMERAS:
        rgb = obs["sensor_data"][cam]["rgb"][0].numpy()
        depth = obs["sensor_data"][cam]["depth"][0].numpy()
        assert rgb.shape == (90, 160, 3) and depth.shape == (90, 160, 1)
        assert rgb.std() > 5, f"{cam} image is not blank"
        assert (depth > 0).mean() > 0.5, f"{cam} sees surfaces in range"
    # the external cameras see the table: the middle of their depth image is < 1.5 m away
    for cam in ("ext1_camera", "ext2_camera"):
        depth = obs["sensor_data"][cam]["depth"][0].numpy()[30:60, 50:110]
        assert 0 < np.median(depth) < 1500
    frame = env.render()
    assert tuple(frame.shape) == (1, 512, 512, 3)
    env.close()


def test_camera_resolution_is_configurable_with_published_fov():
    env = make_env(
        obs_mode="rgb", render_backend="cpu", sensor_configs=dict(width=1280, height=720)
    )
    obs, _ = env.reset(seed=0)
    assert obs["sensor_data"]["ext1_camera"]["rgb"].shape == (1, 720, 1280, 3)
    params = env.unwrapped.get_sensor_params()["ext1_camera"]["intrinsic_cv"][0].numpy()
    assert params[0, 0] == pytest.approx(500.0, rel=1e-3)
    env.close()


def test_pointcloud_mode():
    env = make_env(obs_mode="pointcloud", render_backend="cpu")
    obs, _ = env.reset(seed=0)
    xyz = obs["pointcloud"]["xyzw"][0].numpy()
    assert xyz.shape[-1] == 4 and (xyz[:, 3] > 0).sum() > 1000
    env.close()


def test_vector_env_and_flatten_wrappers_keep_working():
    env = make_env(obs_mode="rgb", render_backend="cpu")
    env = FlattenRGBDObservationWrapper(env, rgb=True, depth=False, state=True)
    venv = ManiSkillVectorEnv(env, 1, ignore_terminations=True, record_metrics=True)
    obs, info = venv.reset(seed=0)
    assert obs["rgb"].shape[-1] == 3 * len(CAMERAS)
    obs, rew, term, trunc, info = venv.step(venv.action_space.sample())
    assert "reach" in info and info["reach"].shape == (1,)
    assert venv.unwrapped.get_language_instruction()[0]
    venv.close()


@pytest.mark.parametrize("robot", ["franka", "piperx"])
def test_maniskill_recorder_with_info_on_video_works_on_our_envs(robot, tmp_path):
    """ManiSkill's own RecordEpisode with the step info drawn on the video, which fails under
    numpy 2 (our install keeps numpy 1)."""
    import imageio.v2 as imageio
    from mani_skill.utils.wrappers import RecordEpisode

    env = make_env(robot_uids=robot, render_backend="cpu", render_mode="rgb_array")
    env = RecordEpisode(env, str(tmp_path), info_on_video=True)
    env.reset(seed=0)
    for _ in range(4):
        env.step(env.action_space.sample() * 0)
    env.close()
    (video,) = tmp_path.glob("*.mp4")
    assert len(imageio.mimread(video)) == 5, "the reset and 4 steps, with the info drawn"


def test_a_square_image_shows_the_whole_published_view():
    """At 224 x 224 both published fields of view hold (the 16:9 view squeezed): an object
    the visibility certificate measured at the edge of the exterior camera at 160 x 90 stays
    in view (cropped to the vertical field of view alone, no scene camera showed it)."""
    from instructmove_ms.heldout import load_set

    spec = load_set("PlaceA2B-InstructMove", "franka", "unseen_instance", version=7)[50]
    row = next(r for r in spec.certificate["visibility"]["objects"] if r["index"] == 0)
    assert row["pixels"][0] == 0 and row["pixels"][1] > 100  # only ext2 shows it
    env = make_env(
        env_id="PlaceA2B-InstructMove",
        obs_mode="rgb+segmentation",
        render_backend="cpu",
        sensor_configs=dict(width=224, height=224),
    )
    obs, _ = env.reset(options={"episode": spec})
    shown = int(env.unwrapped.objects[0].per_scene_id[0])
    seg = obs["sensor_data"]["ext2_camera"]["segmentation"][0, ..., 0].numpy()
    assert (seg == shown).sum() > 100
    params = env.unwrapped.get_sensor_params()["ext2_camera"]["intrinsic_cv"][0].numpy()
    assert params[0, 0] == pytest.approx(531.9 * 224 / 1280, rel=1e-3)
    assert params[1, 1] == pytest.approx(531.9 * 224 / 720, rel=1e-3)
    env.close()
