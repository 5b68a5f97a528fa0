"""Contact sheets of stored held-out episodes, for people to review: the first episodes of
a set seen from the robot's first scene camera, each with its instruction underneath."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from .files import atomic_path
from .heldout import load_set
from .perturb_sheet import sheet_env
from .video import FONT, wrap

#: Tile size: the default 16:9 camera resolution, times 1.5.
TILE_WIDTH, TILE_HEIGHT = 240, 135
TEXT_SCALE, LINE = 0.4, 14


def _tile(image: np.ndarray, caption: str) -> np.ndarray:
    """``image`` (RGB) over a white band holding ``caption``, wrapped, as BGR."""
    lines = wrap(caption, TILE_WIDTH - 8, TEXT_SCALE)
    band = np.full((LINE * 3 + 6, TILE_WIDTH, 3), 255, np.uint8)
    for k, line in enumerate(lines[:3]):
        y = LINE * (k + 1)
        cv2.putText(band, line, (4, y), FONT, TEXT_SCALE, (0, 0, 0), 1, cv2.LINE_AA)
    return np.concatenate([np.ascontiguousarray(image[..., ::-1]), band], axis=0)


def episode_sheet(
    env_id: str,
    robot: str,
    split: str,
    path: Path,
    count: int = 20,
    columns: int = 4,
    folder: Path | None = None,
    version: int | None = None,
) -> Path:
    """Write a PNG grid of the first ``count`` stored episodes of (env, robot, split), from
    the package's sets of ``version`` or those in ``folder``."""
    specs = load_set(env_id, robot, split, folder, version)[:count]
    env = sheet_env(env_id, robot, TILE_WIDTH, TILE_HEIGHT)
    try:
        camera = env.unwrapped.agent.scene_cameras[0]
        tiles = []
        for index, spec in enumerate(specs):
            obs, _ = env.reset(options={"episode": spec})
            image = obs["sensor_data"][camera]["rgb"][0].cpu().numpy()
            tiles.append(_tile(image, f"{index}. {spec.instruction}"))
    finally:
        env.close()
    blank = np.full_like(tiles[0], 255)
    tiles += [blank] * (-len(tiles) % columns)
    rows = [np.concatenate(tiles[k : k + columns], axis=1) for k in range(0, len(tiles), columns)]
    with atomic_path(path) as tmp:
        cv2.imwrite(str(tmp), np.concatenate(rows, axis=0), [cv2.IMWRITE_PNG_COMPRESSION, 9])
    return path
