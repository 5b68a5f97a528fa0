"""Office stationery, office tools and electronic accessories."""

from __future__ import annotations

from ..design import Design, Traits
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


@generator("eraser", size=(0.04, 0.08), synonyms=("eraser", "rubber eraser"))
def eraser(d: Design) -> Traits:
    color = d.choice(["white", "pink", "blue", "green"])
    sleeve = d.choice(["blue", "black", "red", "yellow"])
    lx, ly, lz = d.uniform(0.045, 0.065), d.uniform(0.02, 0.026), d.uniform(0.01, 0.013)
    d.box("block", (lx / 2, ly / 2, lz / 2), (0, 0, lz / 2), "rubber", color)
    d.box(
        "sleeve",
        (lx * 0.3, ly / 2 + 0.0008, lz / 2 + 0.0008),
        (-lx * 0.12, 0, lz / 2),
        "paper",
        sleeve,
        visual_only=True,
    )
    return Traits((color, sleeve), "rubber", "cuboid")


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
