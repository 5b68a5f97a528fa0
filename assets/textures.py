"""Printed and patterned looks: a part's texture recipe and the image it draws.

A :class:`Texture` is a small recipe (a pattern, the vocabulary colours printed on the
part's own colour, and a pictogram), so identity hashes the recipe, not pixels. Its image
is drawn when an actor is built (``image``): the part's colour is the ground and covers
most of the image, so the part's annotated colour stays its dominant colour. Images are
square and cover every face of a box and the side of a cylinder (wrapped around it); a
cylinder's round ends show the image's inscribed disc (see ``uv_meshes``).

Nothing here names a brand: a "wordmark" is a row of letter-like strokes, and the word
patterns (``WORDS``) print what a product is (TOOTHPASTE, SODA), in a Hershey font.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, partial

import cv2
import numpy as np

from .vocab import COLORS

SIZE = 256  # pixels on a side
#: Pictograms a label can carry.
MOTIFS = ("", "fruit", "chip", "leaf", "cookie", "cheese", "drop", "tooth", "staple")


@dataclass(frozen=True)
class Texture:
    """What a part has printed on it: ``pattern`` (one of ``PATTERNS``) in ``inks``
    (vocabulary colours, on the part's own colour), with pictogram ``motif``."""

    pattern: str
    inks: tuple[str, ...] = ()
    motif: str = ""

    def __post_init__(self) -> None:
        if self.pattern not in PATTERNS:
            raise ValueError(
                f"unknown texture pattern {self.pattern!r}; allowed: {sorted(PATTERNS)}"
            )
        bad = [c for c in self.inks if c not in COLORS]
        if bad:
            raise ValueError(f"unknown ink colour {bad[0]!r}; allowed: {sorted(COLORS)}")
        if self.motif not in MOTIFS:
            raise ValueError(f"unknown motif {self.motif!r}; allowed: {list(MOTIFS)}")
        if len(self.inks) < NEEDED_INKS[self.pattern]:
            raise ValueError(
                f"pattern {self.pattern!r} prints {NEEDED_INKS[self.pattern]} inks, "
                f"got {list(self.inks)}"
            )

    def record(self) -> dict:
        return {"pattern": self.pattern, "inks": list(self.inks), "motif": self.motif}


def _bgr(rgb) -> tuple[int, int, int, int]:
    """An RGBA fill for OpenCV drawing on an RGBA image."""
    return tuple(int(round(255 * float(v))) for v in rgb) + (255,)


def _shade(rgb, factor: float) -> tuple[float, float, float]:
    return tuple(float(min(max(v * factor, 0.0), 1.0)) for v in rgb)


def _wordmark(img: np.ndarray, center: tuple[int, int], width: int, height: int, ink) -> None:
    """A row of letter-like strokes (no real letters: nothing to read, nothing to brand)."""
    color, thick = _bgr(ink), max(2, height // 6)
    letters = 5
    step = width / letters
    x0, y0 = center[0] - width / 2, center[1]
    for k in range(letters):
        cx = int(x0 + step * (k + 0.5))
        rx, ry = int(step * 0.32), int(height * 0.32)
        if k % 3 == 0:  # an "o"
            cv2.ellipse(img, (cx, y0), (rx, ry), 0, 0, 360, color, thick, cv2.LINE_AA)
        elif k % 3 == 1:  # an "l" with a foot
            cv2.line(img, (cx, y0 - int(height * 0.5)), (cx, y0 + ry), color, thick, cv2.LINE_AA)
            cv2.line(img, (cx, y0 + ry), (cx + rx, y0 + ry), color, thick, cv2.LINE_AA)
        else:  # an "n"
            cv2.ellipse(img, (cx, y0), (rx, ry), 0, 180, 360, color, thick, cv2.LINE_AA)
            for side in (-rx, rx):
                cv2.line(img, (cx + side, y0), (cx + side, y0 + ry), color, thick, cv2.LINE_AA)


def _motif(img: np.ndarray, motif: str, center: tuple[int, int], radius: int, ink) -> None:
    """Pictogram ``motif`` in ``ink`` (its own details in fixed colours)."""
    c, r = center, radius
    green, dark, white = _bgr(COLORS["green"]), _bgr(COLORS["brown"]), _bgr(COLORS["white"])
    if motif == "fruit":
        cv2.circle(img, c, r, _bgr(ink), -1, cv2.LINE_AA)
        cv2.circle(img, (c[0] - r // 3, c[1] - r // 3), max(2, r // 5), white, -1, cv2.LINE_AA)
        cv2.ellipse(img, (c[0] + r // 3, c[1] - r), (r // 2, r // 5), -30, 0, 360, green, -1)
    elif motif == "chip":
        pts = [
            (
                c[0] + int(r * math.cos(a) * (1 + 0.08 * math.sin(5 * a))),
                c[1] + int(0.7 * r * math.sin(a)),
            )
            for a in np.linspace(0, 2 * math.pi, 40, endpoint=False)
        ]
        cv2.fillPoly(img, [np.array(pts, np.int32)], _bgr(ink), cv2.LINE_AA)
        cv2.ellipse(img, c, (r // 2, r // 5), 10, 200, 340, _bgr(_shade(ink, 0.75)), 2)
    elif motif == "leaf":
        cv2.ellipse(img, c, (r, r // 2), -35, 0, 360, _bgr(ink), -1, cv2.LINE_AA)
        cv2.line(img, (c[0] - r // 2, c[1] + r // 3), (c[0] + r // 2, c[1] - r // 3), white, 2)
    elif motif == "cookie":
        cv2.circle(img, c, r, _bgr(ink), -1, cv2.LINE_AA)
        for a in np.linspace(0.3, 2 * math.pi, 6, endpoint=False):
            p = (c[0] + int(0.55 * r * math.cos(a)), c[1] + int(0.55 * r * math.sin(a)))
            cv2.circle(img, p, max(2, r // 8), dark, -1, cv2.LINE_AA)
    elif motif == "cheese":
        tri = np.array(
            [(c[0] - r, c[1] + r // 2), (c[0] + r, c[1] + r // 2), (c[0] + r, c[1] - r // 2)]
        )
        cv2.fillPoly(img, [tri.astype(np.int32)], _bgr(ink), cv2.LINE_AA)
        cv2.circle(img, (c[0] + r // 2, c[1] + r // 6), max(2, r // 6), _bgr(_shade(ink, 0.8)), -1)
    elif motif == "drop":
        cv2.circle(img, (c[0], c[1] + r // 3), int(r * 0.6), _bgr(ink), -1, cv2.LINE_AA)
        tri = np.array(
            [
                (c[0] - int(r * 0.55), c[1] + r // 5),
                (c[0] + int(r * 0.55), c[1] + r // 5),
                (c[0], c[1] - r),
            ]
        )
        cv2.fillPoly(img, [tri.astype(np.int32)], _bgr(ink), cv2.LINE_AA)
    elif motif == "staple":
        pts = np.array(
            [
                (c[0] - r, c[1] + r // 2),
                (c[0] - r, c[1] - r // 3),
                (c[0] + r, c[1] - r // 3),
                (c[0] + r, c[1] + r // 2),
            ]
        )
        cv2.polylines(img, [pts.astype(np.int32)], False, _bgr(ink), max(3, r // 4), cv2.LINE_AA)
    elif motif == "tooth":
        cv2.ellipse(img, (c[0], c[1] - r // 4), (r, int(r * 0.6)), 0, 180, 360, _bgr(ink), -1)
        cv2.rectangle(img, (c[0] - r, c[1] - r // 4), (c[0] + r, c[1] + r // 5), _bgr(ink), -1)
        for side in (-1, 1):
            root = (c[0] + side * r // 2, c[1] + r // 2)
            cv2.ellipse(img, root, (r // 3, r // 2), 0, 0, 360, _bgr(ink), -1, cv2.LINE_AA)


def _ground(img: np.ndarray) -> np.ndarray:
    return img[0, 0, :3] / 255.0


def _centres(img: np.ndarray, span: float) -> tuple[list[float], float]:
    """Where a group ``span`` heights wide repeats across the image (once per
    ``span`` of width, so a wrapped cylinder shows one from every side) and its scale (below
    1 where the image is narrower than the group)."""
    h, w = img.shape[:2]
    n = max(1, int(w / (span * h)))
    return [(k + 0.5) * w / n for k in range(n)], min(1.0, w / (span * h))


def _sticker(img, inks, motif, y: float = 0.5) -> None:
    """Wordmarks in the first ink, each with the pictogram in the last ink beside it, on
    the part's own colour, centred at ``y`` of the height."""
    h = img.shape[0]
    cy = int(y * h)
    centres, scale = _centres(img, 1.3 if motif else 0.9)
    word_h, radius = int(0.18 * h * scale), int(0.3 * h * scale)
    for cx in centres:
        if motif:  # the pictogram large (what a shopper spots first), the wordmark beside
            at = (int(cx - 0.36 * h * scale), cy)
            _wordmark(img, at, int(0.5 * h * scale), word_h, COLORS[inks[0]])
            _motif(img, motif, (int(cx + 0.3 * h * scale), cy), radius, COLORS[inks[-1]])
        else:
            _wordmark(img, (int(cx), cy), int(0.75 * h * scale), word_h, COLORS[inks[0]])


def _label(img, inks, motif) -> None:
    """A band across the middle in the first ink carrying a sticker in the other inks (a
    wordmark in the part's colour where none is given)."""
    h, w = img.shape[:2]
    ground = tuple(_ground(img))
    cv2.rectangle(img, (0, int(0.34 * h)), (w, int(0.66 * h)), _bgr(COLORS[inks[0]]), -1)
    if len(inks) > 1:
        _sticker(img, inks[1:], motif)
    else:
        for cx in _centres(img, 0.9)[0]:
            _wordmark(img, (int(cx), h // 2), int(0.75 * h), int(0.18 * h), ground)


def _badge(img, inks, motif) -> None:
    """A round badge (for a disc): a ring in the first ink around the pictogram, drawn in
    the last ink, at the centre."""
    h, w = img.shape[:2]
    c, r = (w // 2, h // 2), min(w, h)
    cv2.circle(img, c, int(0.44 * r), _bgr(COLORS[inks[0]]), int(0.05 * r), cv2.LINE_AA)
    _motif(img, motif, c, int(0.26 * r), COLORS[inks[-1]])


def _ribbon(img: np.ndarray, ink: str) -> None:
    """A ribbon in ``ink`` waving around the lower third (a whole number of times, seamless
    where a cylinder's side closes)."""
    h, w = img.shape[:2]
    waves = max(1, round(w / (2 * h)))
    xs = np.arange(0, w + 1, 4)
    ys = h * (0.66 + 0.1 * np.sin(2 * math.pi * waves * xs / w))
    upper = np.stack([xs, ys - 0.06 * h], axis=1)
    lower = np.stack([xs[::-1], ys[::-1] + 0.06 * h], axis=1)
    cv2.fillPoly(
        img, [np.concatenate([upper, lower]).astype(np.int32)], _bgr(COLORS[ink]), cv2.LINE_AA
    )


def _wave(img, inks, motif) -> None:
    """A ribbon waving around (a whole number of times, seamless where a cylinder's side
    closes) under wordmarks, all in the first ink."""
    _ribbon(img, inks[0])
    _sticker(img, inks, "", y=0.34)


def _dial(img, inks, motif) -> None:
    """A dial (for a clock's face, whose hands are parts): twelve ticks in the first ink
    around the centre, the quarters longer."""
    h, w = img.shape[:2]
    c, r = (w // 2, h // 2), min(w, h)
    ink = _bgr(COLORS[inks[0]])
    for k in range(12):
        a = 2 * math.pi * k / 12
        inner = 0.3 if k % 3 == 0 else 0.36
        p0 = (int(c[0] + inner * r * math.cos(a)), int(c[1] + inner * r * math.sin(a)))
        p1 = (int(c[0] + 0.43 * r * math.cos(a)), int(c[1] + 0.43 * r * math.sin(a)))
        cv2.line(img, p0, p1, ink, 9 if k % 3 == 0 else 5, cv2.LINE_AA)
    cv2.circle(img, c, 10, ink, -1, cv2.LINE_AA)


#: The lit segments of each digit of a seven-segment display, as (x0, y0, x1, y1) in a
#: digit cell one unit wide and two high.
_SEGMENTS = {
    "a": (0, 0, 1, 0),
    "b": (1, 0, 1, 1),
    "c": (1, 1, 1, 2),
    "d": (0, 2, 1, 2),
    "e": (0, 1, 0, 2),
    "f": (0, 0, 0, 1),
    "g": (0, 1, 1, 1),
}
_LIT = {"0": "abcdef", "1": "bc", "2": "abged", "3": "abgcd", "7": "abc", "8": "abcdefg"}


def _digits(img, inks, motif) -> None:
    """A seven-segment time (twelve thirty-eight, say) in the first ink, the width of the
    image, with the colon between hours and minutes."""
    h, w = img.shape[:2]
    cell = min(w / 5.6, h * 0.38)  # a digit's width
    x0, y0 = (w - 5.2 * cell) / 2, (h - 2 * cell) / 2  # the last digit ends at 5.2 cells
    ink, thick = _bgr(COLORS[inks[0]]), max(2, int(cell * 0.16))
    for k, digit in enumerate("12 38"):
        left = x0 + k * 1.1 * cell
        if digit == " ":
            for dy in (0.6, 1.4):
                centre = (int(left + 0.45 * cell), int(y0 + dy * cell))
                cv2.circle(img, centre, thick // 2 + 1, ink, -1, cv2.LINE_AA)
            continue
        for seg in _LIT[digit]:
            a, b, c, d = _SEGMENTS[seg]
            p0 = (int(left + a * cell * 0.8), int(y0 + b * cell))
            p1 = (int(left + c * cell * 0.8), int(y0 + d * cell))
            cv2.line(img, p0, p1, ink, thick, cv2.LINE_AA)


def _grain(img, inks, motif) -> None:
    """Wood grain: wavy darker lines along the image, in shades of the ground colour."""
    h, w = img.shape[:2]
    ground = _ground(img)
    xs = np.arange(0, w + 1, 4)
    for k in range(9):
        y0 = (k + 0.5) * h / 9
        ys = y0 + 4 * np.sin(2 * math.pi * (xs / h * (1 + k % 3)) + k)
        pts = np.stack([xs, ys], axis=1).astype(np.int32)
        cv2.polylines(img, [pts], False, _bgr(_shade(ground, 0.85)), 2 + k % 2, cv2.LINE_AA)


def _weave(img, inks, motif) -> None:
    """Woven fabric: alternating lighter and darker threads across and along."""
    h, w = img.shape[:2]
    ground = _ground(img)
    step = 8
    for k in range(0, max(w, h), step):
        shade = 0.88 if (k // step) % 2 else 1.06
        cv2.line(img, (k, 0), (k, h), _bgr(_shade(ground, shade)), 2)
        cv2.line(img, (0, k), (w, k), _bgr(_shade(ground, 2.0 - shade)), 2)


PATTERNS = {
    "label": _label,
    "sticker": _sticker,
    "badge": _badge,
    "wave": _wave,
    "dial": _dial,
    "digits": _digits,
    "grain": _grain,
    "weave": _weave,
}
#: How many inks each pattern prints at least.
NEEDED_INKS = {
    "label": 1,
    "sticker": 1,
    "badge": 1,
    "wave": 1,
    "dial": 1,
    "digits": 1,
    "grain": 0,
    "weave": 0,
}


def _pores(img, inks, motif) -> None:
    """Foam: small round pores of many sizes, darker shades of the ground, scattered over
    the image (the same scatter on every machine: a fixed seed)."""
    h, w = img.shape[:2]
    ground = _ground(img)
    rng = np.random.default_rng(7)
    count = int(w * h / 420)
    xs, ys = rng.uniform(0, w, count), rng.uniform(0, h, count)
    sizes, shades = rng.uniform(2.5, 7.0, count), rng.uniform(0.6, 0.82, count)
    for x, y, size, shade in zip(xs, ys, sizes, shades, strict=True):
        centre = (int(x), int(y))
        cv2.circle(img, centre, int(round(size)), _bgr(_shade(ground, shade)), -1, cv2.LINE_AA)


PATTERNS["pores"] = _pores
NEEDED_INKS["pores"] = 0


#: Printed words: key -> the lines a real product shows of its kind (upper case, no brand).
#: Each key gives two patterns: ``print_<key>`` (the words once, centred: a box's face) and
#: ``wrap_<key>`` (the words twice, at a quarter and three quarters of the width: a
#: cylinder's side, one copy facing +x and one -x when it stands upright).
WORDS: dict[str, tuple[str, ...]] = {
    "toothpaste": ("TOOTHPASTE",),
    "face_wash": ("FACE", "WASH"),
    "cleanser": ("FACIAL", "CLEANSER"),
    "sanitizer": ("HAND", "SANITIZER"),
    "lotion": ("BODY", "LOTION"),
    "lotion_hand": ("HAND", "LOTION"),
    "floss": ("FLOSS",),
    "soda": ("SODA",),
    "cola": ("COLA",),
    "lemonade": ("LEMON", "SODA"),
    "paprika": ("PAPRIKA",),
    "cinnamon": ("CINNAMON",),
    "oregano": ("OREGANO",),
    "curry": ("CURRY",),
    "ginger": ("GINGER",),
    "pepper": ("PEPPER",),
    "juice": ("JUICE",),
    "milk": ("MILK",),
    "chips": ("CHIPS",),
    "gum": ("GUM",),
    "chocolate": ("CHOCOLATE",),
    "glue": ("GLUE",),
    "eraser": ("ERASER",),
    "staples": ("STAPLES",),
    "cheese": ("STRING", "CHEESE"),
    "cookies": ("COOKIES",),
    "shampoo": ("SHAMPOO",),
    "mode": ("MODE",),
    "fan": ("FAN",),
    "temp": ("TEMP",),
    "cool": ("COOL",),
    "swing": ("SWING",),
}
#: The Hershey font words are printed in (pure integer rasterisation: the same pixels on
#: every machine; no font file).
WORD_FONT = cv2.FONT_HERSHEY_DUPLEX


def _print_words(img, lines, ink, center, width, height) -> None:
    """``lines`` in ``ink``, centred on ``center`` and as large as fits ``width`` x
    ``height`` pixels, upright in the image (its first row is the top), left to right."""
    thick = max(1, int(round(height / len(lines) * 0.09)))
    sizes = [cv2.getTextSize(t, WORD_FONT, 1.0, thick)[0] for t in lines]
    line_h = max(h for _, h in sizes)
    gap = 0.45 * line_h
    block_w, block_h = max(w for w, _ in sizes), len(lines) * line_h + (len(lines) - 1) * gap
    scale = min(width / block_w, height / block_h)
    thick = max(1, int(round(line_h * scale * 0.14)))
    top = center[1] - block_h * scale / 2
    for k, (text, (w, _)) in enumerate(zip(lines, sizes, strict=True)):
        base = top + ((k + 1) * line_h + k * gap) * scale
        org = (int(round(center[0] - w * scale / 2)), int(round(base)))
        cv2.putText(img, text, org, WORD_FONT, scale, _bgr(ink), thick, cv2.LINE_AA)


def _word_pattern(key: str, wrap: bool):
    """The drawing of ``print_<key>`` or ``wrap_<key>``: the words in the first ink (and
    the pictogram in the last ink under them, where a motif is given)."""
    lines = WORDS[key]

    def draw(img, inks, motif) -> None:
        h, w = img.shape[:2]
        xs = (0.25 * w, 0.75 * w) if wrap else (0.5 * w,)
        width = (0.33 if wrap else 0.86) * w
        text_h = 0.5 * h if motif else 0.72 * h
        cy = 0.34 * h if motif else 0.5 * h
        for x in xs:
            _print_words(img, lines, COLORS[inks[0]], (x, cy), width, text_h)
            if motif:
                _motif(img, motif, (int(x), int(0.78 * h)), int(0.14 * h), COLORS[inks[-1]])

    return draw


#: The word patterns (see ``WORDS``).
WORD_PATTERNS = {
    f"{kind}_{key}": _word_pattern(key, kind == "wrap")
    for key in WORDS
    for kind in ("print", "wrap")
}
PATTERNS.update(WORD_PATTERNS)
NEEDED_INKS.update(dict.fromkeys(WORD_PATTERNS, 1))


# --- labels that print words where the first labels drew a wordmark ---------------------
#: ``write(img, center, width, height, ink)``: words (or anything) in a box of that size.
Writer = Callable[[np.ndarray, tuple[int, int], int, int, tuple], None]


#: Azimuth (radians from +x towards +y) that printed words on a standing cylinder face:
#: the front, a little towards +y, where a sheet's camera stands (as the beverage label).
FRONT = 0.5
#: The image column (a fraction of its width) that faces ``FRONT`` on a standing cylinder
#: (turned upright by ``parts.X_TO_Z``: column u faces azimuth pi/2 + 2 pi u).
FRONT_U = (FRONT - math.pi / 2) / (2 * math.pi) % 1.0


def _around(img, centres: list[float], first_words: float, front: float | None) -> list:
    """The x of each group (and of its copies one width either side, so a group crossing
    the seam of a cylinder's side closes round it), the first group's words moved to
    column ``front`` (a fraction of the width) where one is given; the first group first."""
    if front is None:
        return list(centres)
    w = img.shape[1]
    shift = front * w - first_words
    moved = [cx + shift for cx in centres]
    return moved + [cx + k * w for cx in moved for k in (-1, 1)]


def _sticker_with(
    img, inks, motif, write: Writer, y: float = 0.5, front: float | None = None
) -> None:
    """``_sticker``'s layout (the words in the first ink, the pictogram in the last ink
    beside them) with ``write`` where it draws a wordmark, given more room: a real word is
    wider than five strokes, so the group repeats less often round a wide surface. Round a
    cylinder, ``front`` is the column the first words are centred on."""
    h = img.shape[0]
    cy = int(y * h)
    centres, scale = _centres(img, 1.9 if motif else 1.2)
    word_h, radius = int(0.3 * h * scale), int(0.3 * h * scale)
    words_dx = -0.36 * h * scale if motif else 0.0
    for cx in _around(img, centres, centres[0] + words_dx, front):
        if motif:
            write(img, (int(cx + words_dx), cy), int(1.0 * h * scale), word_h, COLORS[inks[0]])
            _motif(img, motif, (int(cx + 0.56 * h * scale), cy), radius, COLORS[inks[-1]])
        else:
            write(img, (int(cx), cy), int(1.05 * h * scale), word_h, COLORS[inks[0]])


def _label_with(img, inks, motif, write: Writer, front: float | None = None) -> None:
    """``_label``'s layout (the band across the middle in the first ink) with ``write``
    where it draws a wordmark (in the part's colour where no other ink is given)."""
    h, w = img.shape[:2]
    ground = tuple(_ground(img))
    cv2.rectangle(img, (0, int(0.34 * h)), (w, int(0.66 * h)), _bgr(COLORS[inks[0]]), -1)
    if len(inks) > 1:
        _sticker_with(img, inks[1:], motif, write, front=front)
    else:
        centres, scale = _centres(img, 1.2)
        for cx in _around(img, centres, centres[0], front):
            write(img, (int(cx), h // 2), int(1.05 * h * scale), int(0.26 * h), ground)


def _wave_with(img, inks, motif, write: Writer, front: float | None = None) -> None:
    """``_wave``'s ribbon under ``write``'s words, all in the first ink."""
    _ribbon(img, inks[0])
    _sticker_with(img, inks, "", write, y=0.34, front=front)


def _writer(key: str, around: bool) -> Writer:
    """Writes the words of ``key``, bolder on an image that is squeezed narrower (a wide
    surface), so their strokes survive the squeeze; ``around`` a cylinder's side (the
    image is its whole girth) no wider than a third of the image: read from one side."""

    def write(img, center, width, height, ink) -> None:
        if around:
            width = min(width, int(0.3 * img.shape[1]))
        squeeze = min(max(img.shape[1] / img.shape[0], 1.0), 2.5)
        lines = WORDS[key]
        thick = max(1, int(round(height / len(lines) * 0.09)))
        sizes = [cv2.getTextSize(t, WORD_FONT, 1.0, thick)[0] for t in lines]
        line_h = max(h for _, h in sizes)
        gap = 0.45 * line_h
        block_w = max(w for w, _ in sizes)
        block_h = len(lines) * line_h + (len(lines) - 1) * gap
        scale = min(width / block_w, height / block_h)
        thick = max(1, int(round(line_h * scale * 0.14 * math.sqrt(squeeze))))
        top = center[1] - block_h * scale / 2
        for k, (text, (w, _)) in enumerate(zip(lines, sizes, strict=True)):
            base = top + ((k + 1) * line_h + k * gap) * scale
            org = (int(round(center[0] - w * scale / 2)), int(round(base)))
            cv2.putText(img, text, org, WORD_FONT, scale, _bgr(ink), thick, cv2.LINE_AA)

    return write


#: The layouts of ``label``, ``sticker`` and ``wave`` printing words: ``<layout>_words_<key>``
#: (a flat face) and ``<layout>_around_<key>`` (a cylinder's side) draw what ``<layout>``
#: draws, the words of ``WORDS[key]`` in place of each wordmark.
LAYOUTS = {"label": _label_with, "sticker": _sticker_with, "wave": _wave_with}
#: The words of those patterns: pattern -> (layout, key, around a cylinder).
LAYOUT_WORDS: dict[str, tuple[str, str, bool]] = {
    f"{layout}_{kind}_{key}": (layout, key, kind == "around")
    for key in WORDS
    for layout in LAYOUTS
    for kind in ("words", "around")
}
for _name, (_layout, _key, _round) in LAYOUT_WORDS.items():
    PATTERNS[_name] = partial(
        LAYOUTS[_layout], write=_writer(_key, _round), front=FRONT_U if _round else None
    )
    NEEDED_INKS[_name] = 1


def _pictogram(img, inks, motif) -> None:
    """``_sticker``'s pictograms (in the last ink) alone, centred, no wordmark: a wrapper
    too narrow to print a word the right way up."""
    h = img.shape[0]
    centres, scale = _centres(img, 1.3)
    for cx in centres:
        _motif(img, motif, (int(cx), h // 2), int(0.3 * h * scale), COLORS[inks[-1]])


def _ruled(img, inks, motif) -> None:
    """A blank card to write on: two ruled lines in the first ink (nothing printed)."""
    h, w = img.shape[:2]
    ink, thick = _bgr(COLORS[inks[0]]), max(2, h // 40)
    for y in (0.42, 0.7):
        cv2.line(img, (int(0.1 * w), int(y * h)), (int(0.9 * w), int(y * h)), ink, thick)


PATTERNS.update(pictogram=_pictogram, ruled=_ruled)
NEEDED_INKS.update(pictogram=1, ruled=1)


def _tortoise(img, inks, motif) -> None:
    """Tortoiseshell: soft blotches, darker and a few lighter amber shades of the ground,
    scattered over about a third of the image (the same scatter on every machine: a fixed
    seed)."""
    h, w = img.shape[:2]
    ground = _ground(img)
    rng = np.random.default_rng(11)
    count = max(8, int(w * h / 600))
    for _ in range(count):
        centre = (int(rng.uniform(0, w)), int(rng.uniform(0, h)))
        axes = (int(rng.uniform(0.03, 0.08) * h), int(rng.uniform(0.015, 0.04) * h))
        shade = rng.choice([0.25, 0.35, 0.5, 1.6, 1.6])
        angle = float(rng.uniform(0, 180))
        color = _bgr(_shade(ground, shade))
        cv2.ellipse(img, centre, axes, angle, 0, 360, color, -1, cv2.LINE_AA)
    img[:] = cv2.GaussianBlur(img, (0, 0), 2.0)


def _place_setting(img, inks, motif) -> None:
    """A place setting printed in the first ink, seen by a diner at the image's right
    edge: a plate (two rings) in the middle, a fork below it and a knife above it, both
    pointing left (away from the diner), drawn at the image's real shape."""
    h, w = img.shape[:2]
    ink = _bgr(COLORS[inks[0]])
    aa = cv2.LINE_AA
    radius = int(min(0.4 * w, 0.3 * h))
    c = (w // 2, h // 2)
    cv2.circle(img, c, radius, ink, max(3, radius // 14), aa)
    cv2.circle(img, c, int(radius * 0.66), ink, max(2, radius // 24), aa)
    left, right = int(0.14 * w), int(0.86 * w)
    span = right - left
    unit = max(2, int(0.022 * h))  # a handle's half width
    # the fork, below the plate: a handle, a rounded head and four tines
    fy = int(c[1] + radius + 0.5 * (h / 2 - radius))
    neck = left + int(0.42 * span)
    cv2.line(img, (neck, fy), (right, fy), ink, 2 * unit, aa)
    cv2.circle(img, (right, fy), int(unit * 1.3), ink, -1, aa)
    head_top, head_bottom = fy - int(2.6 * unit), fy + int(2.6 * unit)
    root = left + int(0.3 * span)
    cv2.ellipse(img, (root, fy), (int(0.12 * span), int(2.6 * unit)), 0, -90, 90, ink, -1, aa)
    cv2.rectangle(img, (root - int(0.04 * span), head_top), (root, head_bottom), ink, -1)
    tine = max(1, int(0.5 * unit))
    for k in range(4):
        y = int(head_top + tine / 2 + k * (head_bottom - head_top - tine) / 3)
        cv2.line(img, (left, y), (root, y), ink, tine + 1, aa)
    # the knife, above the plate: a handle and a long blade with a rounded tip
    ky = int(c[1] - radius - 0.5 * (h / 2 - radius))
    blade_root = left + int(0.5 * span)
    cv2.line(img, (blade_root, ky), (right, ky), ink, int(2.2 * unit), aa)
    cv2.circle(img, (right, ky), int(unit * 1.2), ink, -1, aa)
    blade = np.array(
        [
            (blade_root, ky - int(1.2 * unit)),
            (left + int(0.12 * span), ky - int(1.6 * unit)),
            (left, ky),
            (left + int(0.05 * span), ky + int(1.6 * unit)),
            (blade_root, ky + int(1.6 * unit)),
        ],
        np.int32,
    )
    cv2.fillPoly(img, [blade], ink, aa)


def _place_setting_woven(img, inks, motif) -> None:
    """``_place_setting`` printed over woven cloth (``_weave``)."""
    _weave(img, inks, motif)
    _place_setting(img, inks, motif)


PATTERNS.update(
    tortoise=_tortoise, place_setting=_place_setting, place_setting_woven=_place_setting_woven
)
NEEDED_INKS.update(tortoise=0, place_setting=1, place_setting_woven=1)


def _sparkle(img: np.ndarray, center: tuple[float, float], size: float, ink) -> None:
    """A four-pointed sparkle (a clean shine) ``size`` pixels from its centre to a tip."""
    cx, cy = center
    pinch = 0.22 * size
    pts = [
        (cx, cy - size),
        (cx + pinch, cy - pinch),
        (cx + size, cy),
        (cx + pinch, cy + pinch),
        (cx, cy + size),
        (cx - pinch, cy + pinch),
        (cx - size, cy),
        (cx - pinch, cy - pinch),
    ]
    cv2.fillPoly(img, [np.array(pts, np.int32)], _bgr(ink), cv2.LINE_AA)


#: A molar's outline (the tooth of a dental sign: a crown with two cusps, two roots),
#: x across and y down, both -1..1; rounded off by ``_smooth``.
_MOLAR = [
    (-0.98, -0.5), (-0.8, -0.95), (-0.42, -1.0), (0.0, -0.78), (0.42, -1.0), (0.8, -0.95),
    (0.98, -0.5), (0.9, 0.05), (0.72, 0.5), (0.66, 0.98), (0.4, 1.0), (0.26, 0.5),
    (0.0, 0.3), (-0.26, 0.5), (-0.4, 1.0), (-0.66, 0.98), (-0.72, 0.5), (-0.9, 0.05),
]  # fmt: skip


def _smooth(points: list[tuple[float, float]], rounds: int = 3) -> np.ndarray:
    """A closed polygon rounded off by Chaikin's corner cutting."""
    pts = np.asarray(points, float)
    for _ in range(rounds):
        nxt = np.roll(pts, -1, axis=0)
        pts = np.stack([0.75 * pts + 0.25 * nxt, 0.25 * pts + 0.75 * nxt], axis=1).reshape(-1, 2)
    return pts


def _molar(img: np.ndarray, center: tuple[float, float], radius: float, ink) -> None:
    """A molar ``radius`` pixels to either side (and up and down) of ``center``."""
    pts = np.asarray(center) + radius * _smooth(_MOLAR)
    cv2.fillPoly(img, [np.round(pts).astype(np.int32)], _bgr(ink), cv2.LINE_AA)


def _tooth_shine(img, inks, motif) -> None:
    """A tooth in the first ink as wide as the image allows, a sparkle at its shoulder and
    a smaller one across it in the last ink: a clean-teeth print."""
    h, w = img.shape[:2]
    r = 0.44 * min(w, 0.55 * h)
    c = (w * 0.5, h * 0.56)
    _molar(img, c, r, COLORS[inks[0]])
    _sparkle(img, (c[0] + 0.62 * r, c[1] - 1.5 * r), 0.42 * r, COLORS[inks[-1]])
    _sparkle(img, (c[0] - 0.55 * r, c[1] - 1.4 * r), 0.24 * r, COLORS[inks[-1]])


def _toothbrush(img, inks, motif) -> None:
    """A toothbrush seen side on, along the image's longer side: standing head up in a
    tall image (its bristles to the right), lying head left in a wide one (bristles up);
    the handle in the first ink, the tufts of bristles in the last."""
    h, w = img.shape[:2]
    tall = h >= w
    length, across = (h, w) if tall else (w, h)
    unit = min(0.78 * length, 3.8 * across)  # the brush's length
    start = (length - unit) / 2
    axis = (across - 0.22 * unit) / 2 + 0.045 * unit  # the handle's middle line

    def at(s: float, t: float) -> tuple[int, int]:
        """The pixel ``s`` brush lengths from the head's tip and ``t`` across from the
        handle's middle line (towards the bristles)."""
        a, b = start + s * unit, axis + t * unit
        return (int(round(b)), int(round(a))) if tall else (int(round(a)), int(round(across - b)))

    handle, bristle = _bgr(COLORS[inks[0]]), _bgr(COLORS[inks[-1]])
    aa = cv2.LINE_AA
    profile = [(0.0, 0.04), (0.27, 0.04), (0.36, 0.022), (0.5, 0.028), (0.62, 0.048), (0.97, 0.045)]
    edge = [at(s, hw) for s, hw in profile] + [at(s, -hw) for s, hw in profile[::-1]]
    cv2.fillPoly(img, [np.array(edge, np.int32)], handle, aa)
    for s, hw in (profile[0], profile[-1]):  # round ends
        cv2.circle(img, at(s, 0.0), max(1, int(hw * unit)), handle, -1, aa)
    tufts, root, tip = 5, 0.03, 0.17
    pitch = 0.25 / tufts
    for k in range(tufts):
        s = 0.015 + k * pitch
        quad = [at(s, root), at(s + 0.72 * pitch, root), at(s + 0.72 * pitch, tip), at(s, tip)]
        cv2.fillPoly(img, [np.array(quad, np.int32)], bristle, aa)


PATTERNS.update(tooth_shine=_tooth_shine, toothbrush=_toothbrush)
NEEDED_INKS.update(tooth_shine=1, toothbrush=1)

#: Every pattern that prints words -> the key of its words in ``WORDS``.
PRINTED_WORDS: dict[str, str] = {
    **{name: name.split("_", 1)[1] for name in WORD_PATTERNS},
    **{name: key for name, (_, key, _) in LAYOUT_WORDS.items()},
}


def first_words(texture: Texture, aspect: float = 1.0) -> tuple[tuple[float, ...], tuple]:
    """Where ``image`` draws the first copy of the words of a ``LAYOUT_WORDS`` pattern:
    (their ink, or None for the part's own colour; (x0, y0, x1, y1), the pixels of the
    square image their box covers)."""
    layout, key, around = LAYOUT_WORDS[texture.pattern]
    aspect = min(max(aspect, ASPECTS[0]), ASPECTS[1])
    width = int(round(SIZE * aspect))
    canvas = np.zeros((SIZE, width, 4), np.uint8)
    canvas[:, :] = 1  # a ground no ink has: the part's own colour is told apart below
    found = []

    def write(img, center, w, h, ink) -> None:
        if not found:
            mask = np.zeros((*img.shape[:2], 4), np.uint8)
            _writer(key, around)(mask, center, w, h, (1.0, 1.0, 1.0))
            mask = mask[..., 0]
            ys, xs = np.nonzero(mask)
            ground = tuple(_ground(img))
            found.append((None if tuple(ink) == ground else tuple(ink), xs, ys))

    LAYOUTS[layout](canvas, texture.inks, texture.motif, write, front=FRONT_U if around else None)
    ink, xs, ys = found[0]
    sx = SIZE / width
    box = (
        int(xs.min() * sx),
        int(ys.min()),
        int(math.ceil((xs.max() + 1) * sx)),
        int(ys.max() + 1),
    )
    return ink, box


#: Patterns for a disc (a cylinder's round end shows the image's inscribed circle): drawn
#: square whatever the part's side.
ROUND = ("badge", "dial")
#: The widest and narrowest surfaces an image is drawn for (width over height).
ASPECTS = (0.25, 4.0)


@cache
def image(texture: Texture, rgb: tuple[float, float, float], aspect: float = 1.0) -> np.ndarray:
    """The RGBA image (SIZE x SIZE, uint8) of ``texture`` printed on a part of colour
    ``rgb`` whose surface is ``aspect`` times as wide as high (see ``uv_meshes.aspect``):
    drawn at that shape (square for ``ROUND`` patterns), then squeezed to the square the
    meshes stretch back; read-only."""
    aspect = 1.0 if texture.pattern in ROUND else min(max(aspect, ASPECTS[0]), ASPECTS[1])
    canvas = np.zeros((SIZE, int(round(SIZE * aspect)), 4), np.uint8)
    canvas[:, :] = _bgr(rgb)
    PATTERNS[texture.pattern](canvas, texture.inks, texture.motif)
    img = cv2.resize(canvas, (SIZE, SIZE), interpolation=cv2.INTER_AREA)
    img.setflags(write=False)
    return img
