"""Office stationery, office tools and electronic accessories."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..textures import Texture
from .registry import generator

BRIGHT = ["red", "blue", "green", "black", "yellow", "orange", "purple", "pink"]


@generator("marker", size=(0.11, 0.16), synonyms=("marker", "marker pen", "felt-tip marker"))
def marker(d: Design) -> Traits:
    color = d.choice(BRIGHT)
    body = d.choice(["white", "white", "black", "gray"])
    r = d.uniform(0.008, 0.011)
    length = d.uniform(0.12, 0.14)
    cap_len = length * 0.3
    d.rod("barrel", r, length - cap_len, (-cap_len / 2, 0, r), "plastic", body)
    d.rod("cap", r + 0.001, cap_len, ((length - cap_len) / 2, 0, r), "plastic", color)
    d.box(
        "clip",
        (cap_len * 0.35, 0.002, 0.0015),
        ((length - cap_len) / 2, 0, 2 * r + 0.0015),
        "plastic",
        color,
    )
    return Traits((body, color), "plastic", "cylinder")


@generator(
    "tv_remote", size=(0.13, 0.22), synonyms=("tv remote", "television remote", "tv remote control")
)
def tv_remote(d: Design) -> Traits:
    color = d.choice(["black", "black", "gray", "white", "silver"])
    button = "white" if color == "black" else "black"
    lx, ly, lz = d.uniform(0.15, 0.19), d.uniform(0.04, 0.05), d.uniform(0.018, 0.024)
    d.box("body", (lx / 2, ly / 2, lz / 2), (0, 0, lz / 2), "plastic", color)
    d.add(
        "power",
        "cylinder",
        (0.0045, 0.0012),
        (lx / 2 - 0.015, 0, lz + 0.0006),
        "rubber",
        "red",
        quat=(0.7071068, 0.0, -0.7071068, 0.0),
        visual_only=True,
    )
    for row in range(4):
        for col in (-1, 0, 1):
            d.box(
                f"button_{row}_{col}",
                (0.004, 0.0045, 0.0008),
                (lx / 2 - 0.04 - row * 0.014, col * 0.011, lz + 0.0008),
                "rubber",
                button,
                visual_only=True,
            )
    return Traits((color,), "plastic", "cuboid")


@generator(
    "usb_drive",
    size=(0.04, 0.08),
    synonyms=("usb drive", "flash drive", "usb stick", "thumb drive"),
)
def usb_drive(d: Design) -> Traits:
    color = d.choice(BRIGHT + ["silver"])
    lx, ly, lz = d.uniform(0.04, 0.055), d.uniform(0.016, 0.022), d.uniform(0.008, 0.011)
    d.box("body", (lx / 2, ly / 2, lz / 2), (0, 0, lz / 2), "plastic", color)
    d.box("connector", (0.006, 0.006, 0.0025), (lx / 2 + 0.006, 0, lz / 2), "metal", "silver")
    return Traits((color,), "plastic", "cuboid")


@generator("eraser", size=(0.04, 0.08), synonyms=("eraser", "rubber eraser"), revision=3)
def eraser_3(d: Design) -> Traits:
    """Revision 3: a soft block eraser, its used end worn round and smudged grey with
    rubbings lying beside it, the rest in a thin printed card sleeve (the square two-tone
    block read as a pencil case or a box)."""
    color = d.choice(["white", "white", "pink", "blue", "green"])
    sleeve = d.choice(["blue", "black", "red", "yellow"])
    ink = "white" if sleeve in ("blue", "black", "red") else "black"
    lx, ly, lz = d.uniform(0.045, 0.06), d.uniform(0.019, 0.024), d.uniform(0.011, 0.013)
    rz = lz / 2
    core = lx - 2 * rz
    d.box("block", (core / 2, ly / 2, lz / 2), (0, 0, lz / 2), "rubber", color)
    d.rod("worn_end", rz, ly, (core / 2, 0, rz), "rubber", color, axis="y")
    d.rod("back_end", rz * 0.8, ly, (-core / 2 + rz * 0.1, 0, rz * 0.8), "rubber", color, axis="y")
    d.box(
        "back_fill",
        (rz * 0.5, ly / 2, lz / 2),
        (-core / 2 + rz * 0.1, 0, lz / 2),
        "rubber",
        color,
    )
    smudge = "gray" if color != "blue" else "black"
    d.ellipsoid(
        "smudge",
        (rz * 0.55, ly * 0.4, rz * 0.7),
        (core / 2 + rz * 0.5, 0, rz * 1.0),
        "rubber",
        smudge,
        visual_only=True,
    )
    cover = lx * d.uniform(0.5, 0.6)
    d.box(  # a quarter turn (its extents swapped): ERASER on its top read from the front
        "card_sleeve",
        (ly / 2 + 0.0005, cover / 2, lz / 2 + 0.0005),
        (-lx / 2 + rz * 0.6 + cover / 2, 0, lz / 2),
        "paper",
        sleeve,
        yaw=math.pi / 2,
        visual_only=True,
        texture=Texture("label_words_eraser", (ink, sleeve)),
    )
    for k in range(d.choice([3, 4, 5])):  # rubbings, curled crumbs of eraser
        a, dist = d.uniform(-0.9, 0.9), d.uniform(0.007, 0.012)
        pos = (lx / 2 + dist * math.cos(a), dist * math.sin(a) * 1.4, 0.0012)
        d.rod(
            f"rubbing_{k}",
            0.0011,
            d.uniform(0.003, 0.006),
            pos,
            "rubber",
            smudge if k % 2 else color,
            capsule=True,
            visual_only=True,
        )
    return Traits((color, sleeve), "rubber", "cuboid")
