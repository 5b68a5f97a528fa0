"""Bathroom supplies and repair tools."""

from __future__ import annotations

from ..design import Design, Traits
from ..textures import Texture
from .desktop import BRIGHT
from .registry import generator


@generator(
    "sponge", size=(0.07, 0.12), synonyms=("sponge", "kitchen sponge", "scrub sponge"), revision=3
)
def sponge_3(d: Design) -> Traits:
    """Revision 3: a thick block of foam showing its pores all round, under a thin scouring
    pad of the same outline (the first, two plain slabs, was not named)."""
    color = d.choice(["yellow", "yellow", "yellow", "pink", "blue", "orange"])
    pad = d.choice(["green", "green", "green", "blue", "gray"])
    lx, ly = d.uniform(0.09, 0.11), d.uniform(0.06, 0.07)
    foam, scour = d.uniform(0.028, 0.034), d.uniform(0.005, 0.007)
    d.box("foam", (lx / 2, ly / 2, foam / 2), (0, 0, foam / 2), "foam", color)
    d.box("scourer", (lx / 2, ly / 2, scour / 2), (0, 0, foam + scour / 2), "fabric", pad)
    pores = Texture("pores")
    skin = 0.0003
    for k, s in enumerate((-1, 1)):  # the pores, on each side (drawn at its own shape)
        d.box(
            f"pores_x{k}",
            (skin, ly / 2, foam / 2),
            (s * (lx / 2 + skin), 0, foam / 2),
            "foam",
            color,
            visual_only=True,
            texture=pores,
        )
        d.box(
            f"pores_y{k}",
            (lx / 2, skin, foam / 2),
            (0, s * (ly / 2 + skin), foam / 2),
            "foam",
            color,
            visual_only=True,
            texture=pores,
        )
    return Traits((color, pad), "fabric", "cuboid")


@generator("toothbrush", size=(0.15, 0.21))
def toothbrush(d: Design) -> Traits:
    color = d.choice(BRIGHT + ["white"])
    length = d.uniform(0.17, 0.19)
    head = 0.028
    d.box("handle", ((length - head) / 2, 0.007, 0.006), (-head / 2, 0, 0.006), "plastic", color)
    d.box("head", (head / 2, 0.0055, 0.004), ((length - head) / 2, 0, 0.004), "plastic", color)
    d.box(
        "bristles",
        (head / 2 - 0.002, 0.005, 0.006),
        ((length - head) / 2, 0, 0.014),
        "plastic",
        "white",
    )
    return Traits((color,), "plastic", "elongated")


@generator("screwdriver", size=(0.14, 0.26))
def screwdriver(d: Design) -> Traits:
    color = d.choice(["red", "yellow", "blue", "black", "orange", "green"])
    handle_len = d.uniform(0.085, 0.11)
    shaft_len = d.uniform(0.07, 0.12)
    r = d.uniform(0.013, 0.017)
    x0 = -(handle_len + shaft_len) / 2
    d.rod("handle", r, handle_len, (x0 + handle_len / 2, 0, r), "plastic", color, capsule=True)
    d.rod("ferrule", 0.006, 0.012, (x0 + handle_len + 0.004, 0, r), "metal", "silver")
    d.rod("shaft", 0.0032, shaft_len, (x0 + handle_len + shaft_len / 2, 0, r), "metal", "silver")
    d.box("tip", (0.004, 0.0035, 0.0008), (x0 + handle_len + shaft_len, 0, r), "metal", "silver")
    return Traits((color, "silver"), "plastic", "elongated")


@generator("wrench", size=(0.12, 0.22), synonyms=("wrench", "spanner"))
def wrench(d: Design) -> Traits:
    color = d.choice(["silver", "silver", "gray", "black"])
    length = d.uniform(0.14, 0.2)
    w = d.uniform(0.014, 0.018)
    t = d.uniform(0.008, 0.011)
    d.box("handle", (length / 2 - 0.02, w / 2, t / 2), (0, 0, t / 2), "metal", color)
    head_x = length / 2 - 0.014
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"jaw_{k}",
            (0.014, 0.0055, t / 2),
            (head_x, sign * (w / 2 + 0.006), t / 2),
            "metal",
            color,
        )
    d.box("ring", (0.014, w * 0.9, t / 2), (-head_x, 0, t / 2), "metal", color)
    return Traits((color,), "metal", "flat")
