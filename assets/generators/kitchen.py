"""Tableware, ware and utensils."""

from __future__ import annotations

import math

from ..design import Design, Traits
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


@generator("spice_jar", size=(0.07, 0.12), synonyms=("spice jar", "seasoning jar"))
def spice_jar(d: Design) -> Traits:
    lid = d.choice(["red", "black", "silver", "white", "green"])
    content = d.choice(["red", "brown", "green", "orange", "beige"])
    r = d.uniform(0.02, 0.026)
    h = d.uniform(0.08, 0.1)
    d.upright("jar", r, h - 0.018, 0.0, "glass", "transparent", solid_fraction=0.35)
    d.upright("spice", r - 0.002, (h - 0.02) * 0.6, 0.002, "organic", content, visual_only=True)
    d.upright("lid", r + 0.0015, 0.018, h - 0.018, "plastic", lid)
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
