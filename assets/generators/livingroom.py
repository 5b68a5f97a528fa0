"""Living-room ornaments."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import X_TO_Z, axis_angle_quat
from .registry import generator


def _cactus(d: Design, z: float) -> None:
    r, h = d.uniform(0.018, 0.026), d.uniform(0.1, 0.16)
    d.upright("trunk", r, h - r, z - 0.01, "organic", "green")
    d.sphere("crown", r, (0, 0, z - 0.01 + h - r), "organic", "green")
    for k, sign in enumerate((-1, 1)[: d.choice([1, 2])]):
        zk = z + h * d.uniform(0.3, 0.45)
        reach = r + d.uniform(0.012, 0.018)
        d.rod(f"arm_{k}", r * 0.55, reach, (0, sign * reach / 2, zk), "organic", "green", axis="y")
        d.add(
            f"arm_tip_{k}",
            "capsule",
            (r * 0.55, h * 0.12),
            (0, sign * reach, zk + h * 0.12),
            "organic",
            "green",
            quat=X_TO_Z,
        )
    d.sphere("flower", r * 0.45, (0, 0, z - 0.01 + h), "organic", "pink", visual_only=True)


def _leaves(d: Design, z: float, radius: float, blades: bool) -> None:
    """Broad leaves fanning out, or the tall upright blades of a snake plant."""
    n = d.choice([5, 6, 7] if blades else [6, 7, 8, 9])
    for k in range(n):
        a = 2 * math.pi * k / n + d.uniform(-0.3, 0.3)
        if blades:
            length, lean = d.uniform(0.15, 0.25), d.uniform(0.05, 0.25)
            cross = (d.uniform(0.009, 0.013), 0.002)
        else:
            length, lean = d.uniform(0.08, 0.13), d.uniform(0.5, 1.0)
            cross = (d.uniform(0.018, 0.026), 0.0025)
        reach = length * math.sin(lean)
        base = (radius * 0.3 * math.cos(a), radius * 0.3 * math.sin(a), z)
        tip = (reach * math.cos(a), reach * math.sin(a), z + length * math.cos(lean))
        shape = "box" if blades else "ellipsoid"
        d.segment(f"leaf_{k}", shape, base, tip, cross, "organic", "green")


@generator(
    "houseplant",
    size=(0.15, 0.4),
    synonyms=("houseplant", "potted plant", "plant"),
    graspable=False,
)
def houseplant(d: Design) -> Traits:
    material, pot = d.choice(
        [
            ("ceramic", "orange"),
            ("ceramic", "brown"),
            ("ceramic", "white"),
            ("ceramic", "gray"),
            ("ceramic", "blue"),
            ("plastic", "black"),
            ("plastic", "white"),
        ]
    )
    r, h = d.uniform(0.04, 0.055), d.uniform(0.07, 0.11)
    spread = d.uniform(0.008, 0.015)
    flare = math.atan2(spread, h)
    d.upright("pot_floor", r + 0.006, 0.008, 0.0, material, pot)
    d.wall("pot", r, 0.006, h - 0.008, 0.008, material, pot, segments=16, flare=flare)
    d.wall("pot_rim", r + spread - 0.002, 0.01, 0.016, h - 0.016, material, pot, segments=16)
    soil = h - 0.012
    d.upright("soil", r, soil - 0.008, 0.008, "organic", "brown", solid_fraction=0.7)
    d.upright("soil_top", r + spread * 0.85, 0.003, soil - 0.003, "organic", "brown")
    kind = d.choice(["leafy", "leafy", "snake", "cactus"])
    if kind == "cactus":
        _cactus(d, soil)
    else:
        _leaves(d, soil, r, blades=kind == "snake")
    return Traits(("green", pot), material, "irregular")


@generator(
    "watering_can",
    size=(0.2, 0.42),
    synonyms=("watering can", "watering pot"),
)
def watering_can(d: Design) -> Traits:
    material, color = d.choice(
        [
            ("plastic", "green"),
            ("plastic", "blue"),
            ("plastic", "red"),
            ("plastic", "yellow"),
            ("plastic", "white"),
            ("metal", "silver"),
            ("metal", "gray"),
        ]
    )
    fill = 0.1 if material == "plastic" else 0.02
    w, core, h = d.uniform(0.06, 0.074), d.uniform(0.03, 0.06), d.uniform(0.1, 0.15)
    d.stadium("body", core, w / 2, 0.0, h, material, color, solid_fraction=fill)
    d.upright("opening", w * 0.3, 0.004, h, material, "black", xy=(-core * 0.6, 0))
    front = core + w / 2
    elev, length = d.uniform(0.6, 0.9), d.uniform(0.12, 0.18)
    root = (front - 0.01, 0, h * 0.2)
    tip = (root[0] + length * math.cos(elev), 0, root[2] + length * math.sin(elev))
    d.segment("spout", "cylinder", root, tip, d.uniform(0.007, 0.009), material, color)
    rose = (tip[0] + 0.02 * math.cos(elev), 0, tip[2] + 0.02 * math.sin(elev))
    rose_color = d.choice([color, "black", "silver"])
    d.segment("rose", "cylinder", tip, rose, 0.016, material, rose_color)
    top = h + d.uniform(0.035, 0.05)
    bar = (core * 0.5, 0, top)
    back = (-front - 0.02, 0, top - 0.01)
    d.segment("handle", "capsule", bar, back, 0.007, material, color)
    d.segment("handle_post", "capsule", (core * 0.5, 0, h - 0.005), bar, 0.007, material, color)
    d.segment("handle_back", "capsule", back, (-front + 0.005, 0, h * 0.45), 0.007, material, color)
    colors = (color,) if rose_color == color else (color, rose_color)
    return Traits(colors, material, "irregular")


@generator(
    "diffuser_bottle",
    size=(0.2, 0.38),
    synonyms=("diffuser bottle", "reed diffuser"),
)
def diffuser_bottle(d: Design) -> Traits:
    glass = d.choice(["transparent", "transparent", "brown", "white", "black"])
    oil = d.choice(["yellow", "orange", "pink", "purple"])
    collar = d.choice(["golden", "silver", "black"])
    reed = d.choice([c for c in ("beige", "brown", "black", "white") if c != glass])
    r, h = d.uniform(0.024, 0.033), d.uniform(0.07, 0.1)
    if d.rng.random() < 0.5:
        d.upright("body", r, h, 0.0, "glass", glass, solid_fraction=0.4)
        d.upright("oil", r - 0.003, h * 0.6, 0.004, "organic", oil, visual_only=True)
        shape = "cylinder"
    else:
        d.box("body", (r, r, h / 2), (0, 0, h / 2), "glass", glass, solid_fraction=0.4)
        d.box(
            "oil",
            (r - 0.003, r - 0.003, h * 0.3),
            (0, 0, 0.004 + h * 0.3),
            "organic",
            oil,
            visual_only=True,
        )
        shape = "cuboid"
    d.upright("neck", 0.009, 0.012, h, "glass", glass)
    d.upright("collar", 0.012, 0.012, h + 0.008, "metal", collar, solid_fraction=0.3)
    n = d.choice([5, 6, 7, 8])
    for k in range(n):
        length = d.uniform(0.19, 0.24)
        lean = d.uniform(0.08, 0.4) * (1 if k % 2 else -1)
        side = d.uniform(-0.025, 0.025)
        base = (0.0, 0.0, h - 0.03)
        tip = (length * math.sin(lean), side, h - 0.03 + length * math.cos(lean))
        d.segment(f"reed_{k}", "cylinder", base, tip, 0.0018, "wood", reed)
    return Traits((glass, reed), "glass", shape)


def _tilted(d: Design, name, half, local, tilt, material, color, **kw) -> None:
    """A box in the frame of a plate leaning back (towards -x) by ``tilt``."""
    x, y, z = local
    pos = (x * math.cos(tilt) - z * math.sin(tilt), y, x * math.sin(tilt) + z * math.cos(tilt))
    d.add(name, "box", half, pos, material, color, quat=axis_angle_quat((0, 1, 0), -tilt), **kw)


@generator(
    "photo_frame",
    size=(0.12, 0.21),
    synonyms=("photo frame", "picture frame"),
)
def photo_frame(d: Design) -> Traits:
    material, color = d.choice(
        [
            ("wood", "brown"),
            ("wood", "black"),
            ("wood", "white"),
            ("wood", "beige"),
            ("aluminium", "silver"),
            ("aluminium", "golden"),
            ("plastic", "pink"),
        ]
    )
    kw = dict(solid_fraction=0.4 if material == "aluminium" else 1.0)
    long, short = d.uniform(0.15, 0.2), d.uniform(0.11, 0.15)
    hw, hh = (short / 2, long / 2) if d.rng.random() < 0.5 else (long / 2, short / 2)
    b, ft, tilt = d.uniform(0.012, 0.02), d.uniform(0.01, 0.016), d.uniform(0.15, 0.22)
    for k, sign in enumerate((-1, 1)):
        _tilted(
            d,
            f"rail_{k}",
            (ft / 2, hw, b / 2),
            (0, 0, sign * (hh - b / 2)),
            tilt,
            material,
            color,
            **kw,
        )
        _tilted(
            d,
            f"stile_{k}",
            (ft / 2, b / 2, hh - b),
            (0, sign * (hw - b / 2), 0),
            tilt,
            material,
            color,
            **kw,
        )
    _tilted(
        d, "backing", (0.0015, hw - b, hh - b), (-ft / 2 + 0.0015, 0, 0), tilt, "paper", "black"
    )
    sky, ground = d.choice([("blue", "green"), ("blue", "beige"), ("white", "gray")])
    split = d.uniform(-0.3, 0.1) * hh
    top = (hh - b - split) / 2
    _tilted(
        d,
        "photo_sky",
        (0.0003, hw - b, top),
        (0, 0, split + top),
        tilt,
        "paper",
        sky,
        visual_only=True,
    )
    bottom = (hh - b + split) / 2
    _tilted(
        d,
        "photo_ground",
        (0.0003, hw - b, bottom),
        (0, 0, split - bottom),
        tilt,
        "paper",
        ground,
        visual_only=True,
    )
    floor = -(ft / 2 * math.sin(tilt) + hh * math.cos(tilt))
    attach = (-ft / 2 * math.cos(tilt), 0.0, -ft / 2 * math.sin(tilt))
    foot_x = attach[0] - hh * 0.25 - 0.01
    pitch = math.atan2(attach[2] - floor, attach[0] - foot_x)
    foot = (foot_x, 0.0, floor + 0.0015 * math.cos(pitch))
    d.segment("leg", "box", attach, foot, (d.uniform(0.008, 0.012), 0.0015), "paper", "black")
    return Traits((color,), material, "flat")


@generator(
    "candle_holder",
    size=(0.06, 0.15),
    synonyms=("candle holder", "votive holder", "tealight holder"),
    container=True,
    revision=3,
)
def candle_holder_3(d: Design) -> Traits:
    """Revision 3: the holder, not the candle: a brass or silver candlestick (a wide drip
    tray for a foot, a turned stem with knops, a drip pan and a socket) or an enamel
    chamberstick (a dish with a raised rim, a socket and a finger loop), each holding a
    short unlit stub with a blackened wick (a lit candle in it read as a candle). The free
    place is the drip tray (the dish) beside the stem."""
    wax = d.choice(["white", "white", "beige", "red"])
    stub = d.uniform(0.012, 0.02)
    if d.rng.random() < 0.55:  # a candlestick
        metal = d.choice(["golden", "golden", "silver"])
        fill = dict(solid_fraction=0.2)
        tray_r, tray_t = d.uniform(0.042, 0.048), 0.005
        d.upright("tray", tray_r, tray_t, 0.0, "metal", metal, **fill)
        d.wall("tray_rim", tray_r - 0.003, 0.003, 0.008, tray_t, "metal", metal, segments=16)
        stem = d.uniform(0.06, 0.075)
        d.upright("stem", 0.006, stem, tray_t, "metal", metal, **fill)
        d.upright("stem_base", 0.012, 0.008, tray_t, "metal", metal, **fill)
        for k, (frac, rad) in enumerate(((0.3, 0.011), (0.62, 0.013), (0.85, 0.009))):
            d.ellipsoid(
                f"knop_{k}",
                (rad, rad, 0.0055),
                (0, 0, tray_t + frac * stem),
                "metal",
                metal,
                **fill,
            )
        z = tray_t + stem
        d.upright("drip_pan", d.uniform(0.022, 0.026), 0.003, z, "metal", metal, **fill)
        d.upright("socket", 0.012, 0.016, z + 0.003, "metal", metal, **fill)
        d.upright("socket_lip", 0.0135, 0.002, z + 0.017, "metal", metal, **fill)
        candle_r, candle_z = 0.0095, z + 0.015
        free_r, rim_z = tray_r - 0.003, tray_t + 0.008
        floor = tray_t
        colors, material, shape = (metal,), "metal", "irregular"
    else:  # an enamel chamberstick
        enamel = d.choice(["white", "white", "red", "blue", "green"])
        edge = d.choice(["blue", "black"]) if enamel == "white" else "white"
        dish_r, dish_t = d.uniform(0.044, 0.05), 0.004
        d.upright("dish", dish_r, dish_t, 0.0, "metal", enamel, solid_fraction=0.25)
        d.wall("dish_rim", dish_r - 0.003, 0.003, 0.012, dish_t, "metal", enamel, segments=16)
        d.flat_ring(
            "dish_edge", dish_r - 0.0015, 0.004, 0.002, dish_t + 0.012, "metal", edge, segments=12
        )
        socket = 0.022
        d.upright("socket", 0.014, socket, dish_t, "metal", enamel, solid_fraction=0.25)
        d.upright("socket_lip", 0.0155, 0.0025, dish_t + socket, "metal", edge)
        # the finger loop standing up out of the rim, towards the front left
        loop_r, out = 0.013, dish_r + 0.008
        u = (math.cos(2.1), math.sin(2.1))
        z0 = dish_t + 0.012

        def on_loop(r: float, z: float) -> tuple[float, float, float]:
            return (u[0] * r, u[1] * r, z)

        for k in range(7):
            a0, a1 = math.pi * (k / 7 - 0.5), math.pi * ((k + 1) / 7 - 0.5)
            p0 = on_loop(out + loop_r * math.cos(a0), z0 + loop_r * (1 + math.sin(a0)))
            p1 = on_loop(out + loop_r * math.cos(a1), z0 + loop_r * (1 + math.sin(a1)))
            d.segment(f"loop_{k}", "box", p0, p1, (0.0045, 0.002), "metal", enamel)
        d.segment(
            "loop_foot",
            "box",
            on_loop(dish_r - 0.004, dish_t + 0.006),
            on_loop(out, z0),
            (0.0045, 0.002),
            "metal",
            enamel,
        )
        candle_r, candle_z = 0.0105, dish_t + socket - 0.002
        free_r, rim_z, floor = dish_r - 0.003, dish_t + 0.012, dish_t
        colors, material, shape = (enamel,), "metal", "disk"
    # a short unlit stub, its wick blackened, a run of wax down its side
    d.upright("stub", candle_r, stub, candle_z, "organic", wax)
    d.upright("wick", 0.0008, 0.004, candle_z + stub, "fabric", "black", visual_only=True)
    d.upright(
        "wick_well", candle_r * 0.6, 0.0008, candle_z + stub, "organic", wax, visual_only=True
    )
    drip_a = d.uniform(0, 2 * math.pi)
    d.ellipsoid(
        "wax_drip",
        (0.0022, 0.0022, stub * 0.35),
        (candle_r * math.cos(drip_a), candle_r * math.sin(drip_a), candle_z + stub * 0.7),
        "organic",
        wax,
        visual_only=True,
    )
    # the free place: the dish or drip tray round the socket, on the side away from the loop
    half = (free_r - 0.016) / 2 - 0.006
    center = (-(free_r + 0.016) / 2 * 0.8, -(free_r + 0.016) / 2 * 0.6)
    d.interior((half, half), floor_z=floor, rim_z=rim_z, center=center)
    return Traits(colors, material, shape)
