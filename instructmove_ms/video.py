"""Episode videos with the instruction drawn on every frame and the outcome at the end.

Frames come from the env's ``render()`` in ``render_mode="rgb_array"`` (its human render
camera). The instruction sits in a dark band at the top, wrapped to the frame's width; the
last frame is held for a second with the outcome in a band at the bottom. Videos are H.264
MP4 files written through imageio's FFmpeg writer (a ManiSkill dependency), atomically.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import cv2
import imageio.v2 as imageio
import numpy as np

from .files import atomic_path

FONT = cv2.FONT_HERSHEY_SIMPLEX
SUCCESS_COLOR = (60, 220, 60)
FAILURE_COLOR = (240, 70, 60)


@dataclass(frozen=True)
class VideoSettings:
    """Which episodes get a video (the first ``first`` of the run, all if None) and how."""

    first: int | None = None
    width: int = 512
    height: int = 512
    fps: int = 30

    @property
    def camera(self) -> dict:
        """``human_render_camera_configs`` for ``gym.make``."""
        return {"width": self.width, "height": self.height}


def _scale(frame: np.ndarray) -> tuple[float, int]:
    """Font scale and line height for a frame of this width."""
    scale = max(0.3, frame.shape[1] / 900)
    return scale, int(28 * scale) + 4


def wrap(text: str, width: int, scale: float) -> list[str]:
    """``text`` split into lines no wider than ``width`` pixels (a long word stays whole)."""
    lines: list[str] = []
    for word in text.split():
        line = f"{lines[-1]} {word}" if lines else word
        if lines and cv2.getTextSize(line, FONT, scale, 1)[0][0] <= width:
            lines[-1] = line
        else:
            lines.append(word)
    return lines or [""]


def _band(frame: np.ndarray, text: str, top: bool, color: tuple[int, int, int]) -> None:
    """Draw ``text`` in place, wrapped, on a darkened band at the top or bottom."""
    scale, step = _scale(frame)
    margin = max(4, frame.shape[1] // 64)
    lines = wrap(text, frame.shape[1] - 2 * margin, scale)
    height = step * len(lines) + margin
    rows = slice(0, height) if top else slice(frame.shape[0] - height, frame.shape[0])
    frame[rows] = frame[rows] // 3
    y0 = rows.start + margin // 2
    for i, line in enumerate(lines):
        baseline = y0 + step * (i + 1) - 4
        cv2.putText(frame, line, (margin, baseline), FONT, scale, color, 1, cv2.LINE_AA)


def overlay(frame: np.ndarray, instruction: str, outcome: str | None = None) -> np.ndarray:
    """A copy of the RGB ``frame`` with the instruction on top and, if given, the outcome
    at the bottom (green for a success)."""
    out = np.ascontiguousarray(frame, dtype=np.uint8).copy()
    _band(out, instruction, top=True, color=(255, 255, 255))
    if outcome is not None:
        color = SUCCESS_COLOR if outcome.startswith("success") else FAILURE_COLOR
        _band(out, outcome, top=False, color=color)
    return out


def outcome_text(success: bool, stages: dict[str, bool], error: str | None) -> str:
    """``success``, the last stage reached, or the policy's error."""
    if error:
        return f"error: {error}"
    if success:
        return "success"
    reached = [name for name, done in stages.items() if done]
    return f"failed; stage reached: {reached[-1] if reached else 'none'}"


def write_video(
    path: Path, frames: list[np.ndarray], instruction: str, outcome: str, fps: int
) -> Path:
    """Write ``frames`` with the overlay, holding the last one for a second with the
    outcome, as an MP4 at ``path`` (atomically)."""
    with (
        atomic_path(path) as tmp,
        imageio.get_writer(
            tmp, format="FFMPEG", fps=fps, codec="libx264", macro_block_size=2, quality=7
        ) as writer,
    ):
        for frame in frames:
            writer.append_data(overlay(frame, instruction))
        last = overlay(frames[-1], instruction, outcome)
        for _ in range(fps):
            writer.append_data(last)
    return path
