"""Tableware, ware and utensils."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import X_TO_Z
from ..textures import Texture
from .registry import generator

CERAMIC_COLORS = ["white", "white", "blue", "red", "green", "yellow", "black", "beige", "pink"]


@generator("mug", size=(0.08, 0.13), synonyms=("mug", "coffee mug"), container=True)
def mug(d: Design) -> Traits:
    color = d.choice(CERAMIC_COLORS)
    r = d.uniform(0.03, 0.038)
    h = d.uniform(0.08, 0.105)
    t = 0.005
    d.upright("bottom", r + t, 0.008, 0.0, "ceramic", color)
    d.wall("wall", r, t, h - 0.008, 0.008, "ceramic", color, segments=14)
    # the handle: two arms and a grip, on the +x side
    reach = d.uniform(0.022, 0.03)
    grip_h = h * d.uniform(0.5, 0.65)
    z_mid = h * 0.52
    x_out = r + t + reach
    for name, z in (("handle_top", z_mid + grip_h / 2), ("handle_bottom", z_mid - grip_h / 2)):
        d.box(name, (reach / 2 + 0.002, 0.006, 0.004), (r + t + reach / 2, 0, z), "ceramic", color)
    d.box("handle_grip", (0.004, 0.006, grip_h / 2 + 0.004), (x_out, 0, z_mid), "ceramic", color)
    d.interior((r * 0.7, r * 0.7), floor_z=0.008, rim_z=h)
    return Traits((color,), "ceramic", "cylinder")


@generator("bowl", size=(0.1, 0.2), container=True)
def bowl(d: Design) -> Traits:
    color = d.choice(CERAMIC_COLORS)
    material = d.choice(["ceramic", "ceramic", "plastic", "wood"])
    r_base = d.uniform(0.035, 0.045)
    h = d.uniform(0.045, 0.065)
    flare = d.uniform(0.55, 0.75)
    d.upright("foot", r_base * 0.8, 0.006, 0.0, material, color)
    d.upright("base", r_base + 0.004, 0.006, 0.006, material, color)
    d.wall("wall", r_base, 0.005, h - 0.012, 0.012, material, color, segments=18, flare=flare)
    d.interior((r_base * 0.7, r_base * 0.7), floor_z=0.012, rim_z=h)
    return Traits((color,), material, "hemisphere")


#: The spice a jar's contents show, by their colour: the word its label prints.
SPICE_WORDS = {
    "red": ("wrap_paprika",),
    "brown": ("wrap_cinnamon", "wrap_pepper"),
    "green": ("wrap_oregano",),
    "orange": ("wrap_curry",),
    "beige": ("wrap_ginger",),
}


@generator("spice_jar", size=(0.07, 0.12), synonyms=("spice jar", "seasoning jar"), revision=3)
def spice_jar_3(d: Design) -> Traits:
    """Revision 3: a small glass jar filled to the shoulder with ground spice, a printed
    label round it naming the spice (PAPRIKA, CINNAMON, OREGANO ...), under a screw lid
    whose top is a shaker with its sifter holes (the first, a tall glass half full of
    brown under a lid, read as a glass of iced coffee)."""
    lid = d.choice(["red", "black", "silver", "white", "green"])
    content = d.choice(list(SPICE_WORDS))
    label = d.choice([c for c in ("white", "white", "beige", "black") if c != content])
    ink = (
        "white"
        if label == "black"
        else d.choice([c for c in ("red", "green", "brown", "black") if c != content])
    )
    r = d.uniform(0.02, 0.024)
    h = d.uniform(0.08, 0.095)
    lid_h = d.uniform(0.014, 0.018)
    jar = h - lid_h - 0.004
    d.upright("jar", r, jar, 0.0, "glass", "transparent", solid_fraction=0.35)
    d.upright("spice", r - 0.0015, jar * 0.85, 0.0025, "organic", content, visual_only=True)
    d.upright("neck", r * 0.9, 0.004, jar, "glass", "transparent")
    word = Texture(d.choice(SPICE_WORDS[content]), (ink,))
    quat = X_TO_Z  # the word towards +x (a turn about z would widen its bounds)
    label_h = jar * 0.5
    d.add(
        "label",
        "cylinder",
        (r + 0.0008, label_h / 2),
        (0, 0, jar * 0.2 + label_h / 2),
        "paper",
        label,
        quat=quat,
        visual_only=True,
        texture=word,
    )
    d.upright("lid", r + 0.0015, lid_h, h - lid_h, "plastic", lid)
    top = "white" if lid != "white" else "gray"
    d.upright("sifter", r * 0.8, 0.0008, h, "plastic", top, visual_only=True)
    for k in range(7):
        a = 2 * math.pi * k / 6
        xy = (0.0, 0.0) if k == 6 else (r * 0.45 * math.cos(a), r * 0.45 * math.sin(a))
        d.upright(
            f"sifter_hole_{k}",
            0.0017,
            0.0004,
            h + 0.0008,
            "plastic",
            "black",
            xy=xy,
            visual_only=True,
        )
    return Traits(("transparent", lid), "glass", "cylinder")


def _cutlery_handle(d: Design, colors: list[str], length: tuple[float, float], z: float):
    """The curved handle of a spoon or fork along x: it rises from the head to a hump and
    comes down to rest its tip on the table, as a real one does; returns (material, colour,
    head start, head length)."""
    color = d.choice(colors)
    material = "metal" if color == "silver" else "plastic"
    total = d.uniform(*length)
    head = total * 0.3
    handle = total - head
    x0 = -total / 2
    hump = d.uniform(0.012, 0.018)
    neck, top, tip = (x0 + handle, 0.0, z), (x0 + handle * 0.45, 0.0, hump), (x0, 0.0, 0.0018)
    d.segment("handle_front", "box", neck, top, (0.006, 0.0018), material, color)
    d.segment("handle_back", "box", top, tip, (0.006, 0.0018), material, color)
    return material, color, x0 + handle, head


@generator("spoon", size=(0.12, 0.21))
def spoon(d: Design) -> Traits:
    material, color, x_head, head = _cutlery_handle(
        d, ["silver", "silver", "white", "black", "blue"], (0.15, 0.19), z=0.006
    )
    d.ellipsoid(
        "bowl", (head / 2, 0.018, 0.006), (x_head + head / 2 - 0.004, 0, 0.006), material, color
    )
    return Traits((color,), material, "elongated")


@generator("fork", size=(0.14, 0.22))
def fork(d: Design) -> Traits:
    material, color, x_head, head = _cutlery_handle(
        d, ["silver", "silver", "white", "black"], (0.16, 0.2), z=0.003
    )
    d.box("neck", (0.008, 0.011, 0.0018), (x_head + 0.008, 0, 0.003), material, color)
    tine_len = head - 0.016
    for k, y in enumerate((-0.0085, -0.003, 0.003, 0.0085)):
        d.box(
            f"tine_{k}",
            (tine_len / 2, 0.0014, 0.0016),
            (x_head + 0.016 + tine_len / 2, y, 0.003),
            material,
            color,
        )
    return Traits((color,), material, "elongated")


@generator("plate", size=(0.14, 0.26), synonyms=("plate", "dish"), graspable=False, container=True)
def plate(d: Design) -> Traits:
    color = d.choice(CERAMIC_COLORS)
    r = d.uniform(0.075, 0.1)
    rim_h = d.uniform(0.01, 0.016)
    d.upright("foot", r * 0.6, 0.004, 0.0, "ceramic", color)
    d.upright("floor", r * 0.7, 0.004, 0.004, "ceramic", color)
    flare = math.atan2(r * 0.3, rim_h)
    d.wall("rim", r * 0.7, 0.003, rim_h, 0.006, "ceramic", color, segments=20, flare=flare)
    d.interior((r * 0.5, r * 0.5), floor_z=0.008, rim_z=0.006 + rim_h)
    return Traits((color,), "ceramic", "disk")
