"""Receptacles: destinations that objects are placed into or onto."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import axis_angle_quat, quat_mul
from ..textures import Texture
from .registry import generator


def _tray(
    d: Design, hx: float, hy: float, h: float, t: float, material: str, color: str, **kw
) -> None:
    """An open rectangular container: a floor and four walls, all ``t`` thick."""
    d.box("floor", (hx, hy, t / 2), (0, 0, t / 2), material, color, **kw)
    d.frame("wall", (hx, hy), t, t, h - t, material, color, **kw)


def _vessel(
    d: Design,
    r: float,
    h: float,
    t: float,
    floor: float,
    material: str,
    color: str,
    flare: float = 0.0,
    z0: float = 0.0,
    segments: int = 16,
) -> float:
    """A round open vessel (floor disc and wall) on z0; returns the outer radius at the rim."""
    d.upright("floor", r + t, floor, z0, material, color)
    d.wall("wall", r, t, h - floor, z0 + floor, material, color, segments=segments, flare=flare)
    return r + t + math.tan(flare) * (h - floor)


def _metal_or_plastic(d: Design, colors: list[str]) -> tuple[str, str]:
    """Thin aluminium (silver) one time in three, else coloured plastic."""
    if d.rng.random() < 1 / 3:
        return "aluminium", "silver"
    return "plastic", d.choice(colors)


def _rim_ring(
    d: Design,
    top: float,
    t: float,
    height: float,
    z_top: float,
    material: str,
    color: str,
    segments: int,
) -> None:
    """A thickened ring around the rim of a round vessel whose outer rim radius is ``top``."""
    d.wall(
        "rim",
        top - t - 0.001,
        t + 0.004,
        height,
        z_top - height,
        material,
        color,
        segments=segments,
    )


def _round_interior(d: Design, r: float, floor_z: float, rim_z: float) -> None:
    d.interior((r * 0.7, r * 0.7), floor_z=floor_z, rim_z=rim_z)


def _loop_handle(
    d: Design, name: str, x: float, z: float, span: float, material: str, color: str
) -> None:
    """A half-ring handle standing up in the yz plane at ``x``, its feet on z."""
    n, rho = 6, span / 2
    for k in range(n):
        a0, a1 = math.pi * k / n, math.pi * (k + 1) / n
        p0 = (x, rho * math.cos(a0), z + rho * math.sin(a0))
        p1 = (x, rho * math.cos(a1), z + rho * math.sin(a1))
        d.segment(f"{name}_{k}", "capsule", p0, p1, 0.0045, material, color)


#: Wicker's woven look, printed on a basket's walls instead of modelled strand by strand.
WICKER = Texture("weave")


def _woven_wall(
    d: Design,
    name: str,
    radius: float,
    thickness: float,
    height: float,
    z0: float,
    material: str,
    color: str,
    segments: int,
    flare: float,
) -> None:
    """``Design.wall`` printed with the weave: a ring of woven boxes, tilted out by ``flare``."""
    slant = height / math.cos(flare)
    outer = radius + thickness + math.sin(flare) * slant
    chord = 2 * outer * math.tan(math.pi / segments) * 1.02
    r = radius + thickness / 2 + math.sin(flare) * slant / 2
    for k in range(segments):
        a = 2 * math.pi * k / segments
        quat = quat_mul(axis_angle_quat((0, 0, 1), a), axis_angle_quat((0, 1, 0), flare))
        d.add(
            f"{name}_{k}",
            "box",
            (thickness / 2, chord / 2, slant / 2),
            (r * math.cos(a), r * math.sin(a), z0 + height / 2),
            material,
            color,
            quat=quat,
            texture=WICKER,
        )


@generator("basket", size=(0.18, 0.33), graspable=False, container=True, revision=3)
def basket_3(d: Design) -> Traits:
    """Revision 3: a woven basket, round or rectangular (wicker, or rattan-look plastic):
    woven walls (the weave printed on them) over a darker base, a twisted rope rim and a
    loop handle at each end in the darker cane (the smooth, striped first basket read as a
    basin, a tub or a washbasin). At most sixty parts."""
    material = d.choice(["wicker", "wicker", "wicker", "plastic"])
    h = d.uniform(0.08, 0.12)
    if material == "wicker":
        color = d.choice(["golden", "beige", "brown", "golden"])
        stake = "brown" if color != "brown" else "beige"
    else:  # rattan-look plastic
        color, stake = d.choice([("white", "gray"), ("gray", "black"), ("beige", "brown")])
    t = 0.007
    woven = dict(texture=WICKER)
    if d.rng.random() < 0.5:
        hx, hy = d.uniform(0.1, 0.115), d.uniform(0.075, 0.095)
        d.box("floor", (hx, hy, t / 2), (0, 0, t / 2), material, stake, **woven)
        d.frame("wall", (hx, hy), t, t, h - t, material, color, **woven)
        d.frame("rim", (hx + 0.002, hy + 0.002), t + 0.004, h - 0.01, 0.01, material, stake)
        count = int(2 * (hx + hy) / 0.027)
        for k in range(count):  # a twisted rope along the rim
            f = 2 * (hx + hy) * (k + 0.5) / count
            if f < 2 * hx:
                pos, yaw = (-hx + f, hy - t / 2 + 0.001, h + 0.002), 0.0
            else:
                pos, yaw = (hx - t / 2 + 0.001, -hy + f - 2 * hx, h + 0.002), math.pi / 2
            for s in (1, -1):
                x, y = (pos[0], s * pos[1]) if yaw == 0.0 else (s * pos[0], pos[1])
                d.add(
                    f"twist_{k}_{s}",
                    "ellipsoid",
                    (0.016, 0.0065, 0.0055),
                    (x, y, pos[2]),
                    material,
                    stake,
                    quat=quat_mul(axis_angle_quat((0, 0, 1), yaw), axis_angle_quat((0, 1, 0), 0.5)),
                    visual_only=True,
                )
        d.interior((hx - t - 0.004, hy - t - 0.004), floor_z=t, rim_z=h)
        x_handle, span, shape = hx + 0.004, 2 * hy * 0.55, "cuboid"
    else:
        r, flare = d.uniform(0.075, 0.09), d.uniform(0.1, 0.22)
        n = 16
        d.upright("floor", r + t, t, 0.0, material, stake, **woven)
        _woven_wall(d, "wall", r, t, h - t, t, material, color, n, flare)
        top = r + t + math.tan(flare) * (h - t)
        rho, count = top - t / 2, 12
        for k in range(count):  # a rolled rim of cane, twisted round by a binding strand
            a0, a1 = 2 * math.pi * k / count, 2 * math.pi * (k + 1) / count
            p0 = (rho * math.cos(a0), rho * math.sin(a0), h + 0.001)
            p1 = (rho * math.cos(a1), rho * math.sin(a1), h + 0.001)
            d.segment(f"rim_{k}", "capsule", p0, p1, 0.0055, material, stake)
            a = (a0 + a1) / 2
            d.add(
                f"twist_{k}",
                "ellipsoid",
                (0.0066, 0.011, 0.0045),
                (rho * math.cos(a), rho * math.sin(a), h + 0.001),
                material,
                color,
                quat=quat_mul(axis_angle_quat((0, 0, 1), a), axis_angle_quat((1, 0, 0), 0.9)),
                visual_only=True,
            )
        _round_interior(d, r, t, h)
        x_handle, span, shape = top + 0.002, 0.06, "cylinder"
    for k, sign in enumerate((-1, 1)):
        _loop_handle(d, f"handle_{k}", sign * x_handle, h - 0.006, span, material, stake)
    return Traits((color, stake), material, shape)


def _open_lid_frame(hinge, lean: float, up: float, depth: float):
    """Centre and axes of a lid hinged along y at ``hinge`` and swung open over the back
    (-x) to lean ``lean`` rad past upright: its centre ``up`` along the lid from the hinge
    and ``depth`` behind its inner face."""
    n = (math.cos(lean), 0.0, math.sin(lean))  # the inner face's normal
    u = (-math.sin(lean), 0.0, math.cos(lean))  # up the lid, away from the hinge
    c = tuple(hinge[i] - n[i] * depth + u[i] * up for i in range(3))
    return c, n


@generator(
    "waste_bin",
    size=(0.2, 0.32),
    synonyms=("waste bin", "trash can", "garbage bin", "dustbin"),
    graspable=False,
    container=True,
    revision=3,
)
def waste_bin_3(d: Design) -> Traits:
    """Revision 3: a pedal bin, its lid standing open on a hinge at the back, a foot pedal at
    the front and a bin bag lining it, turned over the rim with its slack bunching below
    (the plain open bin read as a cup or a paper cup). Round, or slim and rectangular; the
    round one on a plinth, its walls in few facets (at most sixty parts)."""
    material, color = _metal_or_plastic(d, ["white", "gray", "black", "red", "beige", "blue"])
    bag = d.choice(["black", "black", "gray", "white"] if color != "black" else ["gray", "white"])
    trim = "black" if color != "black" else "gray"
    t = 0.0015 if material == "aluminium" else 0.003
    lean = d.uniform(0.03, 0.12)  # the open lid leans back a little past upright
    lid_t = 0.005
    drop = d.uniform(0.025, 0.04)  # the bag's fold over the rim
    kw = dict(visual_only=True)
    if d.rng.random() < 0.5:
        r = d.uniform(0.073, 0.077)
        h = d.uniform(0.13, 0.145)
        base, n = 0.012, 14  # the bin stands on a plinth ring; few wall facets
        out = r + t
        d.upright("foot_ring", out + 0.003, base + 0.002, 0.0, "plastic", trim)
        _vessel(d, r, h - base, t, 0.004, material, color, z0=base, segments=n)
        lining = h - drop - base - 0.003  # the bag inside, up to its fold
        d.wall("bag_lining", r - 0.0012, 0.0011, lining, base + 0.005, "plastic", bag, segments=n)
        # the bag turned over the rim: one band wrapping it inside, over the top and out
        fold_t = out + 0.0015 - (r - 0.0012)
        fold_z = h - drop + 0.002
        d.wall("bag_fold", r - 0.0012, fold_t, drop + 0.0005, fold_z, "plastic", bag, segments=n)
        for k in range(5):  # slack of the bag bunching below the fold
            a = 2 * math.pi * (k + d.uniform(0.2, 0.8)) / 5
            rho = out + 0.0015
            d.add(
                f"bag_sag_{k}",
                "ellipsoid",
                (0.004, d.uniform(0.012, 0.02), d.uniform(0.006, 0.012)),
                (rho * math.cos(a), rho * math.sin(a), h - drop + 0.002),
                "plastic",
                bag,
                quat=axis_angle_quat((0, 0, 1), a),
                **kw,
            )
        lid_r = out + 0.004
        hinge = (-(out + 0.007), 0.0, h + 0.004)
        c, n = _open_lid_frame(hinge, lean, lid_r + 0.003, lid_t / 2)
        quat = axis_angle_quat((0, 1, 0), -lean)  # a disc, its axis along x, tilted back
        d.add("lid", "cylinder", (lid_r, lid_t / 2), c, material, color, quat=quat)
        top = lid_r
        _round_interior(d, r, base + 0.004, h)
        shape = "cylinder"
    else:  # slim: the lid hinges on a long side
        out, hy = d.uniform(0.062, 0.068), d.uniform(0.088, 0.1)
        h = d.uniform(0.16, 0.175)
        _tray(d, out, hy, h, t, material, color)
        d.frame("foot_ring", (out + 0.003, hy + 0.003), 0.004, 0.0, 0.014, "plastic", trim)
        d.frame("bag_lining", (out - t, hy - t), 0.0011, 0.005, h - 0.006, "plastic", bag)
        d.frame(
            "bag_fold", (out + 0.0015, hy + 0.0015), 0.0015, h - drop + 0.002, drop, "plastic", bag
        )
        d.frame("bag_lip", (out + 0.0027, hy + 0.0027), t + 0.004, h, 0.0025, "plastic", bag)
        for k in range(4):
            x, y = (k % 2 - 0.5) * out * 1.2, (1 if k // 2 else -1) * (hy + 0.0028)
            if k == 3:
                x, y = out + 0.0028, d.uniform(-0.5, 0.5) * hy
            half = (0.004, d.uniform(0.012, 0.02)) if k == 3 else (d.uniform(0.012, 0.02), 0.004)
            sag = d.uniform(0.006, 0.012)
            d.ellipsoid(
                f"bag_sag_{k}", (*half, sag), (x, y, h - drop + 0.002), "plastic", bag, **kw
            )
        hinge = (-(out + 0.007), 0.0, h + 0.004)
        c, n = _open_lid_frame(hinge, lean, out + 0.006, lid_t / 2)
        quat = axis_angle_quat((0, 1, 0), math.pi / 2 - lean)
        d.add("lid", "box", (out + 0.004, hy + 0.004, lid_t / 2), c, material, color, quat=quat)
        top = out + 0.004
        d.interior((out - 0.01, hy - 0.01), floor_z=t, rim_z=h)
        shape = "cuboid"
    d.box("hinge", (0.006, 0.024, 0.008), (-(out + 0.004), 0, h - 0.004), "plastic", trim)
    # a lip at the lid's free edge, to lift it by hand
    u = (-math.sin(lean), 0.0, math.cos(lean))
    tab = tuple(c[i] + u[i] * (top - 0.004) + n[i] * (lid_t / 2 + 0.003) for i in range(3))
    tilt = axis_angle_quat((0, 1, 0), -lean)
    d.add("lid_tab", "box", (0.003, 0.018, 0.004), tab, "plastic", trim, quat=tilt)
    # the foot pedal, stepped on to lift the lid
    width = d.uniform(0.045, 0.06)
    d.box("pedal_arm", (0.008, 0.006, 0.004), (out + 0.007, 0, 0.01), "plastic", trim)
    d.add(
        "pedal",
        "box",
        (0.011, width / 2, 0.0035),
        (out + 0.019, 0, 0.012),
        material,
        color,
        quat=axis_angle_quat((0, 1, 0), -0.2),
    )
    return Traits(tuple(dict.fromkeys((color, bag))), material, shape)


@generator(
    "frying_pan",
    size=(0.24, 0.34),
    synonyms=("frying pan", "skillet", "fry pan"),
    graspable=False,
    container=True,
)
def frying_pan(d: Design) -> Traits:
    color = d.choice(["black", "black", "gray", "red", "silver", "blue"])
    grip = d.choice(["black", "black", "brown"])
    r, h, t = d.uniform(0.06, 0.075), d.uniform(0.035, 0.045), 0.003
    top = _vessel(d, r, h, t, 0.004, "aluminium", color, flare=d.uniform(0.55, 0.7), segments=20)
    length, pitch = d.uniform(0.1, 0.125), d.uniform(0.12, 0.25)
    start = (top - 0.006, 0.0, h - 0.01)
    d.box("bracket", (0.012, 0.008, 0.006), start, "aluminium", "silver")
    quat = axis_angle_quat((0, 1, 0), -pitch)
    center = (
        start[0] + 0.01 + math.cos(pitch) * length / 2,
        0.0,
        start[2] + math.sin(pitch) * length / 2,
    )
    material = "wood" if grip == "brown" else "plastic"
    d.add("handle", "capsule", (0.01, length / 2 - 0.01), center, material, grip, quat=quat)
    _round_interior(d, r, 0.004, h)
    return Traits(tuple(dict.fromkeys((color, grip))), "aluminium", "disk")


@generator(
    "cooking_pot",
    size=(0.18, 0.3),
    synonyms=("cooking pot", "stockpot", "soup pot"),
    graspable=False,
    container=True,
)
def cooking_pot(d: Design) -> Traits:
    color = d.choice(["silver", "silver", "red", "blue", "black", "white", "green"])
    grips = d.choice([color, "black"]) if color == "silver" else d.choice([color, "silver"])
    r, h, t = d.uniform(0.07, 0.095), d.uniform(0.08, 0.13), 0.003
    top = _vessel(d, r, h, t, 0.005, "aluminium", color, segments=20)
    d.wall("rim", r - 0.001, t + 0.003, 0.006, h - 0.006, "aluminium", color, segments=20)
    reach, span = d.uniform(0.022, 0.032), d.uniform(0.045, 0.06)
    z = h - d.uniform(0.015, 0.03)
    for k, sign in enumerate((-1, 1)):
        for j, y in enumerate((-span / 2, span / 2)):
            d.box(
                f"bracket_{k}{j}",
                (reach / 2, 0.004, 0.004),
                (sign * (top + reach / 2), y, z),
                "aluminium",
                grips,
            )
        d.rod(
            f"grip_{k}",
            0.006,
            span + 0.012,
            (sign * (top + reach), 0, z),
            "aluminium",
            grips,
            axis="y",
        )
    _round_interior(d, r, 0.005, h)
    return Traits(tuple(dict.fromkeys((color, grips))), "aluminium", "cylinder")


@generator(
    "cardboard_box",
    size=(0.18, 0.34),
    synonyms=("cardboard box", "shipping box", "moving box"),
    graspable=False,
    container=True,
)
def cardboard_box(d: Design) -> Traits:
    hx, hy, h, t = d.uniform(0.09, 0.13), d.uniform(0.07, 0.1), d.uniform(0.08, 0.14), 0.004
    _tray(d, hx, hy, h, t, "paper", "brown", solid_fraction=0.5)
    depth = hy * 0.9
    for k, sign in enumerate((-1, 1)):  # flaps standing open, splayed outwards
        tilt = d.uniform(0.15, 0.35)
        quat = axis_angle_quat((1, 0, 0), -sign * tilt)
        pos = (0, sign * (hy - t / 2 + math.sin(tilt) * depth / 2), h + math.cos(tilt) * depth / 2)
        d.add(
            f"flap_y{k}",
            "box",
            (hx, t / 2, depth / 2),
            pos,
            "paper",
            "brown",
            quat=quat,
            solid_fraction=0.5,
        )
        tilt = d.uniform(0.15, 0.35)
        quat = axis_angle_quat((0, 1, 0), sign * tilt)
        pos = (sign * (hx - t / 2 + math.sin(tilt) * depth / 2), 0, h + math.cos(tilt) * depth / 2)
        d.add(
            f"flap_x{k}",
            "box",
            (t / 2, hy - t, depth / 2),
            pos,
            "paper",
            "brown",
            quat=quat,
            solid_fraction=0.5,
        )
        d.box(
            f"tape_{k}",
            (0.025, 0.0006, 0.02),
            (0, sign * (hy + 0.0006), h - 0.02),
            "plastic",
            "beige",
            visual_only=True,
        )
    d.box(
        "label",
        (0.0006, hy * 0.4, h * 0.2),
        (hx + 0.0006, 0, h * 0.5),
        "paper",
        "white",
        visual_only=True,
    )
    d.interior((hx - t - 0.004, hy - t - 0.004), floor_z=t, rim_z=h)
    return Traits(("brown",), "paper", "cuboid")


@generator(
    "baking_tray",
    size=(0.25, 0.34),
    synonyms=("baking tray", "baking sheet", "sheet pan"),
    graspable=False,
    container=True,
)
def baking_tray(d: Design) -> Traits:
    color = d.choice(["silver", "silver", "black", "gray"])
    hx, hy, h, t = d.uniform(0.13, 0.165), d.uniform(0.09, 0.115), d.uniform(0.016, 0.025), 0.002
    _tray(d, hx, hy, h, t, "aluminium", color)
    d.frame("rolled_rim", (hx + 0.002, hy + 0.002), 0.007, h - 0.005, 0.005, "aluminium", color)
    colors: tuple[str, ...] = (color,)
    if d.rng.random() < 0.4:
        paper = d.choice(["white", "beige"])
        d.box(
            "baking_paper",
            (hx - 0.006, hy - 0.006, 0.0004),
            (0, 0, t + 0.0004),
            "paper",
            paper,
            visual_only=True,
        )
        colors = (color, paper)
    d.interior((hx - 0.01, hy - 0.01), floor_z=t, rim_z=h)
    return Traits(colors, "aluminium", "flat")


def _lipped_slab(
    d: Design, hx: float, hy: float, thick: float, material: str, color: str, lip: str, round_: bool
) -> None:
    """A flat board or mat with a low raised edge around its top surface."""
    if round_:
        d.upright("slab", hx, thick, 0.0, material, color)
        d.wall("lip", hx - 0.008, 0.008, 0.0025, thick, material, lip, segments=20)
        d.interior((hx * 0.65, hx * 0.65), floor_z=thick, rim_z=thick + 0.0025)
    else:
        d.box("slab", (hx, hy, thick / 2), (0, 0, thick / 2), material, color)
        d.frame("lip", (hx, hy), 0.008, thick, 0.0025, material, lip)
        d.interior((hx - 0.012, hy - 0.012), floor_z=thick, rim_z=thick + 0.0025)


@generator(
    "cutting_board",
    size=(0.2, 0.32),
    synonyms=("cutting board", "chopping board"),
    graspable=False,
    container=True,
)
def cutting_board(d: Design) -> Traits:
    material = d.choice(["wood", "wood", "plastic"])
    color = d.choice(
        ["brown", "beige", "golden"] if material == "wood" else ["white", "green", "blue", "red"]
    )
    thick = d.uniform(0.012, 0.02)
    round_ = d.rng.random() < 0.3
    hx = d.uniform(0.1, 0.12) if round_ else d.uniform(0.1, 0.13)
    hy = hx if round_ else d.uniform(0.075, 0.1)
    _lipped_slab(d, hx, hy, thick, material, color, color, round_)
    tab = d.uniform(0.03, 0.045)
    d.box(
        "handle",
        (tab / 2 + 0.005, 0.028, thick / 2),
        (hx + tab / 2 - 0.005, 0, thick / 2),
        material,
        color,
    )
    d.upright(
        "hang_hole",
        0.008,
        0.0008,
        thick,
        material,
        "black",
        xy=(hx + tab / 2 - 0.004, 0),
        visual_only=True,
    )
    return Traits((color,), material, "disk" if round_ else "flat")


@generator(
    "lunch_box",
    size=(0.16, 0.26),
    synonyms=("lunch box", "lunchbox", "bento box"),
    container=True,
    revision=3,
)
def lunch_box_3(d: Design) -> Traits:
    """Revision 3: a bento lunch box packed with lunch: white rice filling the back half
    (a red pickled plum and a strip of seaweed or black sesame on it), broccoli, rolled
    omelette and sausages or cherry tomatoes in a front pocket, the other one left free;
    its clip-lock lid taken off and put under it (the first, empty, read as a toolbox; a
    sandwich and rows of small fruit under a lid standing open read as a sewing kit)."""
    color = d.choice(["red", "blue", "green", "pink", "orange", "black", "purple"])
    lid = d.choice(["transparent", "transparent", color])
    clip = d.choice(["white", color]) if color != "black" else "white"
    hx, hy = d.uniform(0.085, 0.1), d.uniform(0.06, 0.07)
    h, t = d.uniform(0.032, 0.036), 0.003
    _tray(d, hx, hy, h, t, "plastic", color)
    wall = (h - t) / 2 - 0.003
    split = -hx * d.uniform(0.0, 0.08)  # rice at -x; the side pockets at +x (the front)
    d.box("divider", (t / 2, hy - t, wall), (split, 0, t + wall), "plastic", color)
    px0, px1 = split + t / 2, hx - t
    pw = px1 - px0
    d.box("divider_small", (pw / 2, t / 2, wall), ((px0 + px1) / 2, 0, t + wall), "plastic", color)
    # white rice heaped in its half, a pickled plum in the middle, seaweed or sesame on it
    rx0, rx1 = -hx + t, split - t / 2
    rice_top = h - 0.003
    rice = ((rx1 - rx0) / 2, hy - t, (rice_top - t) / 2)
    rc = ((rx0 + rx1) / 2, 0.0)
    d.box("rice", rice, (rc[0], rc[1], t + rice[2]), "organic", "white")
    d.ellipsoid(
        "rice_heap",
        (rice[0] * 0.95, rice[1] * 0.95, 0.005),
        (rc[0], rc[1], rice_top),
        "organic",
        "white",
        visual_only=True,
    )
    d.ellipsoid(
        "umeboshi", (0.01, 0.01, 0.0065), (rc[0], rc[1], rice_top + 0.005), "organic", "red"
    )
    if d.rng.random() < 0.6:
        d.box(
            "nori",
            (rice[0] * 0.95, 0.007, 0.0006),
            (rc[0], -rice[1] * 0.55, rice_top + 0.0035),
            "organic",
            "black",
            visual_only=True,
        )
    else:
        for k in range(6):  # black sesame seeds
            sx = rc[0] + rice[0] * d.uniform(-0.7, 0.7)
            sy = rc[1] + rice[1] * d.uniform(-0.75, -0.3)
            d.ellipsoid(
                f"sesame_{k}",
                (0.0015, 0.0009, 0.0006),
                (sx, sy, rice_top + 0.0036),
                "organic",
                "black",
                visual_only=True,
            )
    # the side pocket at +y: broccoli, sausages or cherry tomatoes, a rolled omelette
    sy0, sy1 = t / 2, hy - t
    cy = (sy0 + sy1) / 2
    bed = h - t - 0.022  # a lettuce leaf lifts them up to the rim
    d.box(
        "lettuce",
        (pw / 2, (sy1 - sy0) / 2, bed / 2),
        ((px0 + px1) / 2, cy, t + bed / 2),
        "organic",
        "green",
    )
    t_food = t + bed
    bx = px0 + pw * 0.18
    br = min(0.0085, (sy1 - sy0) / 3.6)
    d.upright("broccoli_stalk", 0.0035, 0.01, t_food, "organic", "green", xy=(bx, cy))
    for k, (ox, oy) in enumerate(((-0.7, -0.6), (0.7, -0.6), (-0.5, 0.7), (0.6, 0.6))):
        d.sphere(
            f"broccoli_{k}",
            br,
            (bx + ox * br, cy + oy * br, t_food + 0.01 + br * 0.5),
            "organic",
            "green",
        )
    egg_x = px0 + pw * 0.68
    for k in range(2):  # rolled omelette slices standing on their cut face
        x = egg_x + k * 0.0135
        d.box(
            f"omelette_{k}",
            (0.0065, (sy1 - sy0) * 0.4, 0.011),
            (x, cy, t_food + 0.011),
            "organic",
            "yellow",
        )
        d.box(
            f"omelette_roll_{k}",
            (0.0066, (sy1 - sy0) * 0.3, 0.0004),
            (x, cy, t_food + 0.0223),
            "organic",
            "orange",
            visual_only=True,
        )
    sx = px0 + pw * 0.45
    if d.rng.random() < 0.5:
        for k in range(2):
            d.rod(
                f"sausage_{k}",
                0.0045,
                (sy1 - sy0) * 0.8,
                (sx + (k - 0.5) * 0.0085, cy, t_food + 0.0045),
                "organic",
                "red",
                axis="y",
                capsule=True,
            )
    else:
        for k in range(2):
            y = cy + (k - 0.5) * (sy1 - sy0) * 0.45
            d.sphere(f"cherry_tomato_{k}", 0.0065, (sx, y, t_food + 0.0065), "organic", "red")
    # the clip-lock lid, taken off and put under the box, as at a lunch table
    d.box("lid", (hx + 0.005, hy + 0.005, 0.002), (0.004, 0.003, -0.002), "plastic", lid)
    d.frame("lid_rim", (hx + 0.005, hy + 0.005), 0.003, -0.009, 0.005, "plastic", lid)
    d.frame("seal", (hx - t, hy - t), 0.002, h, 0.001, "silicone", "gray")
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"clip_side_{k}",
            (0.0025, 0.014, 0.009),
            (sign * (hx + 0.0025), 0, h - 0.011),
            "plastic",
            clip,
        )
        d.box(
            f"clip_{k}",
            (0.015, 0.0025, 0.009),
            (sign * hx * 0.5, hy + 0.0025, h - 0.011),
            "plastic",
            clip,
        )
    # the free pocket: the side pocket at -y
    d.interior(
        (pw / 2 - 0.003, (hy - t - t / 2) / 2 - 0.003),
        floor_z=t,
        rim_z=h,
        center=((px0 + px1) / 2, -(hy - t + t / 2) / 2),
    )
    return Traits(tuple(dict.fromkeys((color, lid))), "plastic", "cuboid")


@generator(
    "bucket", size=(0.16, 0.27), synonyms=("bucket", "pail"), graspable=False, container=True
)
def bucket(d: Design) -> Traits:
    material, color = _metal_or_plastic(d, ["red", "blue", "yellow", "green", "orange", "white"])
    r, h = d.uniform(0.065, 0.085), d.uniform(0.13, 0.19)
    t = 0.0015 if material == "aluminium" else 0.003
    top = _vessel(d, r, h, t, 0.005, material, color, flare=d.uniform(0.1, 0.18), segments=18)
    _rim_ring(d, top, t, 0.012, h, material, color, 18)
    bail = top + 0.008
    z = h - 0.02
    for k, sign in enumerate((-1, 1)):
        d.rod(f"ear_{k}", 0.008, 0.012, (sign * (top + 0.002), 0, z), material, color)
    fold = d.uniform(1.2, 1.35)  # the bail handle leans back over the rim
    tilt = axis_angle_quat((1, 0, 0), fold)
    n = 7
    for k in range(n):
        a0, a1 = math.pi * k / n, math.pi * (k + 1) / n
        mid, chord = (a0 + a1) / 2, 2 * bail * math.sin(math.pi / (2 * n))
        x, up = bail * math.cos(mid), bail * math.sin(mid)
        quat = quat_mul(tilt, axis_angle_quat((0, 1, 0), -(mid + math.pi / 2)))
        pos = (x, -up * math.sin(fold), z + up * math.cos(fold))
        d.add(
            f"bail_{k}", "cylinder", (0.0022, chord / 2 + 0.001), pos, "metal", "silver", quat=quat
        )
    _round_interior(d, r, 0.005, h)
    return Traits((color,), material, "cylinder")


@generator(
    "colander",
    size=(0.2, 0.32),
    synonyms=("colander", "strainer"),
    graspable=False,
    container=True,
)
def colander(d: Design) -> Traits:
    material, color = _metal_or_plastic(d, ["red", "green", "blue", "white", "yellow"])
    holes = "black" if color in ("silver", "white", "yellow") else "white"
    r, h, t = d.uniform(0.045, 0.055), d.uniform(0.065, 0.085), 0.0025
    flare, foot = d.uniform(0.55, 0.7), 0.012
    d.wall("foot", r * 0.75, 0.004, foot, 0.0, material, color, segments=14)
    top = _vessel(d, r, h, t, 0.004, material, color, flare=flare, z0=foot, segments=20)
    for ring, frac in enumerate((0.3, 0.55, 0.8)):
        z = foot + 0.004 + frac * (h - 0.004)
        rho = r + t / 2 + math.tan(flare) * (z - foot - 0.004)
        count = int(2 * math.pi * rho / 0.016)
        for k in range(count):
            a = 2 * math.pi * (k + 0.5 * ring) / count
            d.sphere(
                f"hole_{ring}_{k}",
                0.0025,
                (rho * math.cos(a), rho * math.sin(a), z),
                material,
                holes,
                visual_only=True,
            )
    for k in range(7):
        a, rho = 2 * math.pi * k / 6, r * 0.55 if k < 6 else 0.0
        d.sphere(
            f"drain_{k}",
            0.0025,
            (rho * math.cos(a), rho * math.sin(a), foot + 0.004),
            material,
            holes,
            visual_only=True,
        )
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"handle_{k}",
            (0.015, 0.022, 0.003),
            (sign * (top + 0.012), 0, foot + h - 0.003),
            material,
            color,
        )
    _round_interior(d, r, foot + 0.004, foot + h)
    return Traits((color,), material, "hemisphere")


@generator(
    "placemat",
    size=(0.22, 0.32),
    synonyms=("placemat", "place mat", "table mat"),
    graspable=False,
    container=True,
    revision=3,
)
def placemat_3(d: Design) -> Traits:
    """Revision 3: a table placemat printed with a place setting: a thin wipe-clean vinyl
    (or woven cotton) rectangle with rounded corners, long across the diner's view, printed
    in one ink with a plate (two rings) between a fork and a knife (a woven, fringed mat
    read as a rug, a mat with the setting as stacked discs as an induction cooktop). The
    interior is the printed plate."""
    material = d.choice(["plastic", "plastic", "fabric"])
    color = d.choice(["red", "blue", "green", "orange", "white", "beige", "pink", "yellow"])
    light = color in ("white", "beige", "yellow")
    ink = d.choice(["blue", "red", "green", "brown"]) if light else "white"
    hx, hy = d.uniform(0.09, 0.105), d.uniform(0.13, 0.15)
    thick, r = d.uniform(0.002, 0.003), 0.018
    d.box("slab", (hx - r, hy, thick / 2), (0, 0, thick / 2), material, color)
    d.box("slab_ends", (hx, hy - r, thick / 2), (0, 0, thick / 2), material, color)
    for k, (sx, sy) in enumerate(((-1, -1), (-1, 1), (1, -1), (1, 1))):
        d.upright(f"corner_{k}", r, thick, 0.0, material, color, xy=(sx * (hx - r), sy * (hy - r)))
    # the print over the top (its square corners inside the rounded ones): the diner sits
    # at +x, the fork on their left (-y), the knife on their right
    inset = 0.35 * r
    pattern = "place_setting_woven" if material == "fabric" else "place_setting"
    d.box(
        "place_setting",
        (hx - inset, hy - inset, 0.0001),
        (0, 0, thick - 0.00007),  # sunk into the mat but for its top, so no edge shows
        material,
        color,
        visual_only=True,
        texture=Texture(pattern, (ink,)),
    )
    d.interior((hx - 0.025, hx - 0.025), floor_z=thick, rim_z=thick + 0.003)
    return Traits((color,), material, "flat")
