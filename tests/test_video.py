"""Episode videos: the instruction drawn on every frame, the outcome at the end."""

from __future__ import annotations

import dataclasses

import gymnasium as gym
import imageio.v2 as imageio
import numpy as np
import pytest

from instructmove_ms import heldout
from instructmove_ms.evaluation import evaluate_config
from instructmove_ms.policies import RandomPolicy
from instructmove_ms.video import VideoSettings, outcome_text, overlay, wrap

TASK = "PickCategory-InstructMove"
SETTINGS = VideoSettings(first=1, width=160, height=128, fps=4)
STEPS = 3


@pytest.fixture(scope="module")
def config():
    config = heldout.evaluator_config(TASK, "franka", "seen", episodes=2)
    return dataclasses.replace(config, max_episode_steps=STEPS)


@pytest.fixture(scope="module")
def raw_frame(config):
    """A render of the first episode's initial scene, without overlay."""
    env = gym.make(
        TASK,
        robot_uids="franka",
        obs_mode="state",
        render_mode="rgb_array",
        human_render_camera_configs=SETTINGS.camera,
    )
    episode = config.episodes[0]
    env.reset(seed=episode.seed, options={"episode": episode.spec.to_dict()})
    frame = env.render()[0].cpu().numpy()
    env.close()
    return frame


def test_overlay_draws_the_instruction_on_top_and_the_outcome_below(raw_frame):
    text = "pick up the small red mug that is next to the large blue bowl on the table"
    assert len(wrap(text, raw_frame.shape[1] - 10, 0.3)) > 1, "long instructions wrap"
    drawn = overlay(raw_frame, text)
    assert drawn.shape == raw_frame.shape and drawn.dtype == np.uint8
    changed = np.abs(drawn.astype(int) - raw_frame).sum(axis=2) > 0
    rows = np.flatnonzero(changed.any(axis=1))
    assert rows[0] == 0 and rows[-1] < raw_frame.shape[0] // 2, "only a band at the top"
    ended = overlay(raw_frame, text, outcome_text(False, {"reach": True, "lift": False}, None))
    assert (ended[-5:] != raw_frame[-5:]).any() and (drawn[-5:] == raw_frame[-5:]).all()
    assert outcome_text(True, {}, None) == "success"
    assert outcome_text(False, {"reach": True, "lift": False}, None).endswith("reached: reach")


def test_eval_writes_videos_of_the_first_episodes(tmp_path, config, raw_frame):
    evaluate_config(RandomPolicy(0), config, tmp_path, video=SETTINGS)
    assert not (tmp_path / "videos" / "episode_1.mp4").exists(), "only the first K"
    assert not list((tmp_path / "videos").glob("*.tmp*")), "written atomically"
    with imageio.get_reader(tmp_path / "videos" / "episode_0.mp4") as reader:
        frames = list(reader.iter_data())
    assert len(frames) == 1 + STEPS + SETTINGS.fps, "reset, each step, then a held outcome"
    assert frames[0].shape == (SETTINGS.height, SETTINGS.width, 3)
    diff = np.abs(frames[0].astype(int) - raw_frame).mean(axis=2)
    assert diff[:12].mean() > 30, "the instruction changes the text area"
    assert diff[50:90].mean() < 10, "the scene below it is the raw render (up to compression)"
    held = np.abs(frames[-1].astype(int) - frames[STEPS].astype(int)).mean(axis=2)
    assert held[-12:].mean() > 30 and held[50:90].mean() < 10, "the outcome is drawn at the end"
