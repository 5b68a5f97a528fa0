"""Contact sheets: every instance of a super-category, photographed and labelled; and the
recognition sheet, one unlabelled close-up per category with its key beside it."""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np
from tqdm import tqdm

from ..files import atomic_path
from .catalog import Instance
from .sim import add_camera, look_at, spawn, table_scene

TILE = 192


def photograph(
    instances: list[Instance], tile: int = TILE, progress: str | None = None
) -> list[np.ndarray]:
    """One RGB tile per instance, from the front-left and above, framed by its size (with a
    progress bar named ``progress`` if given)."""
    scene = table_scene(render=True)
    camera = add_camera(scene, "sheet", tile, tile, math.radians(40), 0.005, 10.0)
    images = []
    for inst in tqdm(instances, desc=progress, unit="object", disable=progress is None):
        entity = spawn(scene, inst, z=0.0)
        radius = max(float(np.linalg.norm(inst.dims)) / 2, 0.03)
        center = np.array([0.0, 0.0, inst.height / 2])
        eye = center + radius * 2.9 * np.array([0.75, 0.45, 0.6]) / np.linalg.norm(
            [0.75, 0.45, 0.6]
        )
        camera.set_local_pose(look_at(eye, center))
        scene.update_render()
        camera.take_picture()
        rgba = camera.get_picture("Color")
        images.append((np.clip(rgba[..., :3], 0, 1) * 255).astype(np.uint8))
        scene.remove_entity(entity)
    return images


def label(image: np.ndarray, lines: list[str]) -> np.ndarray:
    out = np.ascontiguousarray(image[..., ::-1])  # BGR for OpenCV
    for k, text in enumerate(lines):
        y = 14 + 13 * k
        cv2.putText(out, text, (4, y), cv2.FONT_HERSHEY_SIMPLEX, 0.36, (0, 0, 0), 2, cv2.LINE_AA)
        cv2.putText(
            out, text, (4, y), cv2.FONT_HERSHEY_SIMPLEX, 0.36, (255, 255, 255), 1, cv2.LINE_AA
        )
    return out


def contact_sheet(instances: list[Instance], path: Path, columns: int = 10) -> Path:
    """Write a labelled grid of ``instances`` (one row per category) to ``path`` (PNG)."""
    tiles = photograph(instances)
    rows: dict[str, list[np.ndarray]] = {}
    for inst, img in zip(instances, tiles, strict=True):
        text = [
            f"{inst.category} #{inst.index}",
            "/".join(inst.colors),
            f"{inst.material} {inst.height * 100:.1f}cm",
        ]
        rows.setdefault(inst.category, []).append(label(img, text))
    return _write_grid(path, list(rows.values()), columns)


def recognition_sheet(instances: list[Instance], out: Path, columns: int = 10) -> tuple[Path, Path]:
    """``out/recognition.png``: one close-up per category of ``instances`` (its first
    instance), numbered and otherwise unlabelled, in an order that says nothing of the
    names (by identity hash); ``out/recognition_key.png``: the same tiles with each category
    under its number. A reviewer names every numbered object, then checks the key."""
    first: dict[str, Instance] = {}
    for inst in instances:
        first.setdefault(inst.category, inst)
    chosen = sorted(first.values(), key=lambda inst: inst.uuid)
    tiles = photograph(chosen, progress="close-ups")
    numbered = [label(img, [str(k + 1)]) for k, img in enumerate(tiles)]
    keyed = [
        label(img, [str(k + 1), inst.category.replace("_", " ")])
        for k, (inst, img) in enumerate(zip(chosen, tiles, strict=True))
    ]
    return (
        _write_grid(out / "recognition.png", [numbered], columns),
        _write_grid(out / "recognition_key.png", [keyed], columns),
    )


def _write_grid(path: Path, rows: list[list[np.ndarray]], columns: int) -> Path:
    """Write ``rows`` of BGR tiles to ``path`` (PNG), each wrapped at ``columns`` and padded
    with white."""
    blank = np.full((TILE, TILE, 3), 255, np.uint8)
    grid = []
    for row in rows:
        for start in range(0, len(row), columns):
            chunk = row[start : start + columns]
            grid.append(np.concatenate(chunk + [blank] * (columns - len(chunk)), axis=1))
    with atomic_path(path) as tmp:
        cv2.imwrite(str(tmp), np.concatenate(grid, axis=0))
    return path
