"""Pictures for readers: numbered tiles, pages of them, a box around one object and a grid
ruled in the margin (never on the image itself)."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from ..files import atomic_path

FONT = cv2.FONT_HERSHEY_SIMPLEX
#: Rows and columns of the answer grid of an episode's camera image.
GRID = 8
COLUMNS = "ABCDEFGH"
BOX_COLOR = (255, 0, 255)  # magenta, RGB
#: Tiles a page holds across and down (of the policy's resolution or smaller).
PAGE_COLUMNS, PAGE_ROWS = 6, 5
MARGIN = 18


def _text(image: np.ndarray, text: str, origin: tuple[int, int], scale: float = 0.45) -> None:
    cv2.putText(image, text, origin, FONT, scale, (0, 0, 0), 1, cv2.LINE_AA)


def numbered(image: np.ndarray, number: int) -> np.ndarray:
    """``image`` (RGB) under a white band holding ``number``; the image is untouched."""
    band = np.full((MARGIN, image.shape[1], 3), 255, np.uint8)
    _text(band, str(number), (3, MARGIN - 5))
    return np.concatenate([band, image], axis=0)


def boxed(image: np.ndarray, mask: np.ndarray, pad: int = 3) -> np.ndarray:
    """``image`` with a 1-pixel magenta box ``pad`` pixels around ``mask``'s pixels."""
    ys, xs = np.nonzero(mask)
    out = np.ascontiguousarray(image.copy())
    h, w = mask.shape
    x0, x1 = max(int(xs.min()) - pad, 0), min(int(xs.max()) + pad, w - 1)
    y0, y1 = max(int(ys.min()) - pad, 0), min(int(ys.max()) + pad, h - 1)
    cv2.rectangle(out, (x0, y0), (x1, y1), BOX_COLOR, 1)
    return out


def ruled(image: np.ndarray, title: str) -> np.ndarray:
    """``image`` in a white margin ruled into ``GRID`` x ``GRID`` cells: columns A-H along
    the top, rows 1-8 down the left, ``title`` above."""
    h, w = image.shape[:2]
    out = np.full((h + 2 * MARGIN, w + MARGIN, 3), 255, np.uint8)
    out[2 * MARGIN :, MARGIN:] = image
    _text(out, title, (MARGIN, MARGIN - 5))
    for k in range(GRID):
        x = MARGIN + int((k + 0.5) * w / GRID) - 4
        _text(out, COLUMNS[k], (x, 2 * MARGIN - 4), 0.4)
        y = 2 * MARGIN + int((k + 0.5) * h / GRID) + 4
        _text(out, str(k + 1), (3, y), 0.4)
        for edge in (int(k * w / GRID), int(k * h / GRID)):
            cv2.line(out, (MARGIN + edge, 2 * MARGIN - 3), (MARGIN + edge, 2 * MARGIN - 1), 0)
            cv2.line(out, (MARGIN - 3, 2 * MARGIN + edge), (MARGIN - 1, 2 * MARGIN + edge), 0)
    return out


def cell_key(
    segmentation: np.ndarray, ids: dict[int, int]
) -> tuple[list[list[int]], dict[str, list[int]]]:
    """What an episode answer is scored against, per grid cell of ``segmentation`` (H, W
    per-scene ids): the owners, per cell the object (the value of ``ids``, keyed by
    per-scene id) with the most pixels in it, or -1 for none, where an object the camera
    shows that holds the most pixels of no cell gets the cell that holds most of it, so
    every object shown owns a cell; and per object shown (as a string key) the [row,
    column] of the cell holding most of it, which the brief asks for and another object may
    hold more of."""
    h, w = segmentation.shape
    counts = np.zeros((GRID, GRID, len(ids)), dtype=np.int64)
    for r in range(GRID):
        for c in range(GRID):
            cell = segmentation[
                r * h // GRID : (r + 1) * h // GRID, c * w // GRID : (c + 1) * w // GRID
            ]
            counts[r, c] = [int((cell == sid).sum()) for sid in ids]
    objects = list(ids.values())
    owners = [
        [objects[int(counts[r, c].argmax())] if counts[r, c].any() else -1 for c in range(GRID)]
        for r in range(GRID)
    ]
    most = {
        str(k): [int(v) for v in np.unravel_index(int(counts[..., j].argmax()), (GRID, GRID))]
        for j, k in enumerate(objects)
        if counts[..., j].any()
    }
    owned = {k for row in owners for k in row}
    for k in objects:
        if k not in owned and str(k) in most:
            r, c = most[str(k)]
            owners[r][c] = k
    return owners, most


def write_pages(
    tiles: list[np.ndarray],
    folder: Path,
    stem: str,
    columns: int = PAGE_COLUMNS,
    rows: int = PAGE_ROWS,
) -> list[Path]:
    """``tiles`` (RGB, equal size) as PNG pages of ``columns`` x ``rows``: ``stem``_1.png, ..."""
    per_page = columns * rows
    blank = np.full_like(tiles[0], 255)
    paths = []
    for page, start in enumerate(range(0, len(tiles), per_page), 1):
        chunk = tiles[start : start + per_page]
        chunk += [blank] * (-len(chunk) % columns)
        grid = np.concatenate(
            [np.concatenate(chunk[k : k + columns], axis=1) for k in range(0, len(chunk), columns)]
        )
        paths.append(write_png(folder / f"{stem}_{page}.png", grid))
    return paths


def write_png(path: Path, rgb: np.ndarray) -> Path:
    with atomic_path(path) as tmp:
        cv2.imwrite(
            str(tmp), np.ascontiguousarray(rgb[..., ::-1]), [cv2.IMWRITE_PNG_COMPRESSION, 9]
        )
    return path
