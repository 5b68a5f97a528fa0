"""Picture sheets of the perturbation axes: one scene at levels 0-3, for judging by eye."""

from __future__ import annotations

from pathlib import Path

import cv2
import gymnasium as gym
import numpy as np

from .assets.sheet import label
from .files import atomic_path
from .perturbation import AXES, MAX_LEVEL, parse_levels

#: Camera resolution of the sheets' tiles (twice the default, 16:9).
SHEET_WIDTH, SHEET_HEIGHT = 320, 180


def axis_sheet(env: gym.Env, seed: int, axis: str, path: Path) -> Path:
    """A PNG grid of the scene of ``seed``: one row per default camera, one column per level
    of ``axis`` (the label says the level and, for language, the instruction)."""
    columns = []
    for level in range(MAX_LEVEL + 1):
        obs, _ = env.reset(seed=seed, options={"perturbation": {axis: level}})
        episode = env.unwrapped.episode
        tiles = []
        for uid, data in obs["sensor_data"].items():
            image = data["rgb"][0].cpu().numpy()
            lines = [f"{axis} {level}  {uid}"]
            if axis == "language":
                lines.append(episode.instruction[:48])
            tiles.append(label(image, lines))
        columns.append(np.concatenate(tiles, axis=0))
    with atomic_path(path) as tmp:
        cv2.imwrite(str(tmp), np.concatenate(columns, axis=1))
    return path


def sheet_env(task: str, robot: str | None, width: int, height: int, **options) -> gym.Env:
    """An rgb env of ``task`` whose cameras render ``width`` x ``height``, for picture
    sheets; ``options`` go to ``gym.make``."""
    return gym.make(
        task,
        robot_uids=robot,
        obs_mode="rgb",
        sensor_configs={"width": width, "height": height},
        **options,
    )


def sheets(task: str, robot: str | None, seed: int, out: Path, axes=AXES) -> list[Path]:
    """One sheet per axis in ``out`` (``<axis>.png``)."""
    for axis in axes:
        parse_levels({axis: 1})  # a ValueError names an unknown axis
    env = sheet_env(task, robot, SHEET_WIDTH, SHEET_HEIGHT)
    try:
        return [axis_sheet(env, seed, axis, Path(out) / f"{axis}.png") for axis in axes]
    finally:
        env.close()
