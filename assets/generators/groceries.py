"""Fruits, vegetables, breads, drinks and snacks of the grocery shelf."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import IDENTITY as IDENTITY_Q
from ..parts import X_TO_Z, axis_angle_quat, quat_mul
from ..textures import Texture
from .registry import generator
from .reprints import reprint

WRAPPERS = ["red", "blue", "green", "yellow", "orange", "purple", "pink", "black", "white"]
PRINTS = ["white", "yellow", "red", "silver", "blue"]


def _yaw(angle: float) -> tuple[float, ...]:
    return axis_angle_quat((0, 0, 1), angle)


def _dots(d: Design, name: str, center, radii, count: int, size: float, color: str) -> None:
    """Small decorative dots (seeds, eyes, chips) on the upper half of an ellipsoid."""
    for k in range(count):
        theta, phi = d.uniform(0.25, 1.25), d.uniform(0.0, 2 * math.pi)
        pos = (
            center[0] + radii[0] * math.sin(theta) * math.cos(phi),
            center[1] + radii[1] * math.sin(theta) * math.sin(phi),
            center[2] + radii[2] * math.cos(theta),
        )
        d.sphere(f"{name}_{k}", size, pos, "organic", color, visual_only=True)


def _stalk(d: Design, top: float, length: float, tilt: float) -> None:
    """A thin stalk leaning ``tilt`` radians from upright, rooted at height ``top``."""
    quat = quat_mul(axis_angle_quat((0, 1, 0), tilt), X_TO_Z)
    center = (math.sin(tilt) * length / 2, 0.0, top - 0.003 + math.cos(tilt) * length / 2)
    d.add("stalk", "cylinder", (0.0022, length / 2), center, "organic", "brown", quat=quat)


def _leaf(d: Design, pos, length: float, yaw: float) -> None:
    d.box("leaf", (length / 2, length / 4, 0.0012), pos, "organic", "green", yaw=yaw)


def _crimps(d: Design, half_x: float, width: float, z: float, color: str, reach: float) -> None:
    """The flat sealed (or twisted) ends of a wrapper, at x = +-half_x."""
    for k, sign in enumerate((-1, 1)):
        center = (sign * (half_x + reach / 2), 0.0, z)
        d.box(f"crimp_{k}", (reach / 2, width / 2, 0.0012), center, "plastic", color)


def _print(
    d: Design, name: str, radius: float, depth: float, z: float, color: str, texture=None
) -> None:
    """A round printed picture on the front and back faces of a body ``depth`` deep in y."""
    d.add(
        name,
        "cylinder",
        (radius, depth / 2 + 0.001),
        (0, 0, z),
        "paper",
        color,
        quat=_yaw(math.pi / 2),
        visual_only=True,
        texture=texture,
    )


def _band(d: Design, name: str, half, z: float, color: str, x: float = 0.0, texture=None) -> None:
    """A printed label wrapped around a box-shaped body (decoration)."""
    d.box(name, half, (x, 0.0, z), "paper", color, visual_only=True, texture=texture)


# fruits ----------------------------------------------------------------------------------
@generator("pear", size=(0.07, 0.14))
def pear(d: Design) -> Traits:
    color = d.choice(["green", "green", "yellow", "brown", "red"])
    r = d.uniform(0.03, 0.035)
    low = r * d.uniform(0.85, 0.95)
    d.upright("base", r * 0.35, 0.004, 0.0, "organic", color)
    d.ellipsoid("body", (r, r, low), (0, 0, low), "organic", color)
    neck_r, neck_h = r * d.uniform(0.55, 0.65), r * d.uniform(0.75, 0.95)
    neck_z = low * 1.7
    d.ellipsoid("neck", (neck_r, neck_r, neck_h), (0, 0, neck_z), "organic", color)
    _dots(d, "speck", (0, 0, low), (r, r, low), 10, 0.0012, "brown")
    top = neck_z + neck_h
    _stalk(d, top, d.uniform(0.012, 0.02), d.uniform(0.1, 0.4))
    if d.rng.random() < 0.4:
        _leaf(d, (0.012, 0.0, top + 0.002), 0.026, d.uniform(0, math.pi))
    return Traits((color,), "organic", "irregular")


@generator("strawberry", size=(0.03, 0.07))
def strawberry(d: Design) -> Traits:
    r = d.uniform(0.012, 0.018)
    length = r * d.uniform(2.4, 2.9)
    # lying on its side: the wide shoulder at +x, the tip at -x
    pieces = ((0.3, 1.0, 0.22), (0.28, 0.78, -0.08), (0.2, 0.45, -0.3))
    for k, (ax, rad, x) in enumerate(pieces):
        h = r * rad * 0.92
        d.ellipsoid(f"body_{k}", (length * ax, r * rad, h), (length * x, 0, h), "organic", "red")
    z = r * 0.92
    _dots(d, "seed", (length * 0.22, 0, z), (length * 0.3, r, z), 16, 0.0008, "yellow")
    cap_x = length * 0.52 - 0.002
    d.rod("calyx", r * 0.3, 0.003, (cap_x, 0, z), "organic", "green")
    for k in range(6):
        a = 2 * math.pi * k / 6 + 0.3
        pos = (cap_x - 0.002, r * 0.5 * math.cos(a), z + r * 0.5 * math.sin(a))
        quat = quat_mul(axis_angle_quat((1, 0, 0), a), axis_angle_quat((0, 0, 1), -0.5))
        d.add(
            f"sepal_{k}", "ellipsoid", (0.001, r * 0.4, 0.0022), pos, "organic", "green", quat=quat
        )
    d.rod("stem", 0.0013, 0.01, (cap_x + 0.005, 0, z), "organic", "green")
    return Traits(("red",), "organic", "cone")


# ingredients -----------------------------------------------------------------------------
@generator(
    "garlic", size=(0.04, 0.09), synonyms=("garlic", "garlic bulb", "head of garlic"), revision=3
)
def garlic_3(d: Design) -> Traits:
    """Revision 3: a papery white head of garlic shaped like a teardrop: plump cloves
    leaning in to a pointed top with a dry stem, purple streaks running up it, a fringe of
    roots at the base, and a loose clove lying beside it (the first, a squat ribbed ball,
    read as a white pumpkin)."""
    skin = d.choice(["white", "white", "white", "beige"])
    streak = d.choice(["purple", "purple", skin])
    r = d.uniform(0.019, 0.024)
    h = r * d.uniform(0.72, 0.8)
    d.upright("root_plate", r * 0.4, 0.003, 0.0, "organic", "beige")
    d.ellipsoid("bulb", (r, r, h), (0, 0, h + 0.002), "organic", skin)
    count = int(d.rng.integers(6, 9))
    for k in range(count):
        a = 2 * math.pi * k / count
        pos = (r * 0.45 * math.cos(a), r * 0.45 * math.sin(a), h * 1.25 + 0.002)
        quat = quat_mul(_yaw(a), axis_angle_quat((0, 1, 0), -0.42))
        radii = (r * 0.44, r * 0.36, h * 1.1)
        d.add(f"clove_{k}", "ellipsoid", radii, pos, "organic", skin, quat=quat)
        if streak != skin:
            d.add(
                f"streak_{k}",
                "ellipsoid",
                (r * 0.48, r * 0.09, h * 1.02),
                pos,
                "organic",
                streak,
                quat=quat,
                visual_only=True,
            )
    d.ellipsoid("neck", (r * 0.28, r * 0.28, h * 0.6), (0, 0, 2.25 * h), "organic", skin)
    d.upright("stem", r * 0.1, h * 0.55, 2.6 * h, "organic", "beige")
    for k in range(14):
        a = 2 * math.pi * (k + d.uniform(-0.3, 0.3)) / 14
        reach = r * d.uniform(0.6, 0.8)
        p0 = (r * 0.25 * math.cos(a), r * 0.25 * math.sin(a), 0.0015)
        p1 = (reach * math.cos(a), reach * math.sin(a), 0.0008)
        d.segment(f"root_{k}", "capsule", p0, p1, 0.0008, "organic", "beige", visual_only=True)
    # a loose clove beside the head, lying on its curved back, its pointed tip towards +x
    cx, cy, cl, cw = r * 1.45, -r * 1.05, r * 0.55, r * 0.36
    d.ellipsoid("loose_clove", (cl, cw, cw * 0.85), (cx, cy, cw * 0.85), "organic", skin)
    tip = (cx + cl * 1.25, cy, cw * 1.0)
    d.segment(
        "loose_clove_tip",
        "ellipsoid",
        (cx + cl * 0.5, cy, cw * 0.85),
        tip,
        (cw * 0.35, cw * 0.3),
        "organic",
        skin,
    )
    d.ellipsoid(
        "loose_clove_base",
        (cw * 0.2, cw * 0.6, cw * 0.55),
        (cx - cl * 0.92, cy, cw * 0.85),
        "organic",
        "beige",
        visual_only=True,
    )
    if streak != skin:
        d.ellipsoid(
            "loose_streak",
            (cl * 0.8, cw * 0.08, cw * 0.9),
            (cx, cy, cw * 0.85),
            "organic",
            streak,
            visual_only=True,
        )
    return Traits(tuple(dict.fromkeys((skin, streak))), "organic", "irregular")


def _lying_taper(d: Design, name: str, r0: float, length: float, color: str, bend: float):
    """A tapering body lying along an arc in the xy plane, thick end first; its thick end."""
    n = 5
    arc = length / max(bend, 1e-3)
    seg = length / n
    a0 = -bend / 2
    for k in range(n):
        a = a0 + bend * (k + 0.5) / n
        r = r0 * (1.0 - 0.72 * k / (n - 1))
        center = (arc * math.sin(a), arc * (1 - math.cos(a)), r)
        d.add(f"{name}_{k}", "capsule", (r, seg / 2), center, "organic", color, quat=_yaw(a))
    end = (arc * math.sin(a0), arc * (1 - math.cos(a0)))
    return end, (math.cos(a0), math.sin(a0))


@generator("carrot", size=(0.1, 0.3))
def carrot(d: Design) -> Traits:
    color = d.choice(["orange", "orange", "orange", "purple"])
    r0 = d.uniform(0.012, 0.019)
    length = d.uniform(0.12, 0.19)
    (x, y), (tx, ty) = _lying_taper(d, "root", r0, length, color, d.uniform(0.0, 0.15))
    top = (x - tx * (r0 + 0.003), y - ty * (r0 + 0.003), r0)
    d.add(
        "crown",
        "cylinder",
        (r0 * 0.55, 0.004),
        top,
        "organic",
        "green",
        quat=_yaw(math.atan2(ty, tx)),
    )
    leafy = d.rng.random() < 0.6
    fronds = int(d.rng.integers(3, 6)) if leafy else 0
    for k in range(fronds):  # drooping onto the table
        frond = d.uniform(0.045, 0.09)
        yaw = math.atan2(-ty, -tx) + d.uniform(-0.45, 0.45)
        pitch = math.asin((r0 - 0.0012) / frond)
        quat = quat_mul(_yaw(yaw), axis_angle_quat((0, 1, 0), pitch))
        reach = (frond / 2) * math.cos(pitch) + 0.004
        pos = (top[0] + math.cos(yaw) * reach, top[1] + math.sin(yaw) * reach, (r0 + 0.0012) / 2)
        d.add(f"frond_{k}", "box", (frond / 2, 0.004, 0.0012), pos, "organic", "green", quat=quat)
    colors = (color, "green") if leafy else (color,)
    return Traits(colors, "organic", "cone")


@generator("chili", size=(0.06, 0.16), synonyms=("chili", "chili pepper", "hot pepper"))
def chili(d: Design) -> Traits:
    color = d.choice(["red", "red", "green", "orange"])
    length = d.uniform(0.07, 0.12)
    r0 = length * d.uniform(0.09, 0.12)
    (x, y), (tx, ty) = _lying_taper(d, "pod", r0, length, color, d.uniform(0.5, 1.1))
    yaw = _yaw(math.atan2(ty, tx))
    cap = (x - tx * r0 * 0.6, y - ty * r0 * 0.6, r0)
    d.add("calyx", "cylinder", (r0 * 0.95, 0.003), cap, "organic", "green", quat=yaw)
    stem = d.uniform(0.012, 0.022)
    pos = (cap[0] - tx * stem / 2, cap[1] - ty * stem / 2, r0)
    d.add("stem", "cylinder", (0.0018, stem / 2), pos, "organic", "green", quat=yaw)
    return Traits(tuple(dict.fromkeys((color, "green"))), "organic", "elongated")


# beverages -------------------------------------------------------------------------------
JUICE_FRUITS = ["orange", "yellow", "red", "purple", "green"]


@generator("juice", size=(0.09, 0.18), synonyms=("juice", "fruit juice"), revision=3)
@reprint("juice")
def juice_2(d: Design) -> Traits:
    """Revision 2: the bottle is a tall clear bottle showing the juice, with a slim neck,
    a small cap and the fruit label (the first, squat with a wide cap, read as a pill
    bottle); the carton is unchanged."""
    fruit = d.choice(JUICE_FRUITS)
    if d.rng.random() < 0.5:
        return _juice_box(d, fruit)
    cap = d.choice(["white", "green", "orange", "blue", "black"])
    r, hz = d.uniform(0.025, 0.03), d.uniform(0.125, 0.15)
    body = hz * 0.62
    d.upright("bottle", r, body, 0.0, "plastic", fruit, solid_fraction=0.95)
    d.upright(
        "label",
        r + 0.0012,
        body * 0.55,
        body * 0.25,
        "paper",
        d.choice(PRINTS[:3]),
        visual_only=True,
        texture=Texture("sticker", (fruit, fruit), "fruit"),
    )
    shoulder = hz * 0.16
    d.ellipsoid("shoulder", (r, r, shoulder), (0, 0, body), "plastic", fruit, solid_fraction=0.95)
    neck_z = body + shoulder * 0.8
    d.upright("neck", r * 0.42, hz - neck_z - 0.014, neck_z, "plastic", "transparent")
    d.upright("cap", r * 0.5, 0.014, hz - 0.014, "plastic", cap)
    return Traits((fruit, cap), "plastic", "cylinder")


def _juice_box(d: Design, fruit: str) -> Traits:
    """A carton with its fruit and a straw."""
    box = d.choice(WRAPPERS)
    lx, ly, hz = d.uniform(0.04, 0.055), d.uniform(0.028, 0.038), d.uniform(0.075, 0.105)
    band = Texture("label", ("white",))
    d.box(
        "carton",
        (lx / 2, ly / 2, hz / 2),
        (0, 0, hz / 2),
        "paper",
        box,
        solid_fraction=1.4,
        texture=band,
    )
    badge = Texture("badge", ("white", fruit), "fruit")
    _print(d, "fruit_print", lx * 0.3, ly, hz * 0.45, fruit, texture=badge)
    straw_color = d.choice(["white", "yellow", "pink", "blue"])
    straw = d.uniform(0.035, 0.05)
    d.upright("straw", 0.0025, straw, hz - 0.004, "plastic", straw_color, xy=(lx * 0.25, ly * 0.2))
    tip = quat_mul(axis_angle_quat((0, 1, 0), 0.7), X_TO_Z)
    top = (lx * 0.25 + 0.0032, ly * 0.2, hz - 0.004 + straw + 0.0038)
    d.add("straw_tip", "cylinder", (0.0025, 0.007), top, "plastic", straw_color, quat=tip)
    return Traits((box, fruit) if box != fruit else (box,), "paper", "cuboid")


@generator(
    "milk_carton", size=(0.1, 0.26), synonyms=("milk carton", "carton of milk", "milk"), revision=3
)
@reprint("milk")
def milk_carton(d: Design) -> Traits:
    body = d.choice(["white", "white", "white", "yellow", "beige"])
    band = d.choice(["blue", "blue", "red", "green", "pink"])
    w = d.uniform(0.055, 0.072)
    hz = d.uniform(0.08, 0.19)
    d.box("carton", (w / 2, w / 2, hz / 2), (0, 0, hz / 2), "paper", body, solid_fraction=1.4)
    s = w / (2 * math.sqrt(2))
    gable = axis_angle_quat((1, 0, 0), math.pi / 4)
    d.add("gable", "box", (w / 2, s, s), (0, 0, hz), "paper", body, quat=gable)
    fin = d.uniform(0.008, 0.014)
    d.box("fin", (w / 2, 0.0015, fin / 2), (0, 0, hz + w / 2 + fin / 2 - 0.003), "paper", body)
    mark = Texture("sticker", (body,), "drop")
    _band(d, "print", (w / 2 + 0.0008, w / 2 + 0.0008, hz * 0.22), hz * 0.45, band, texture=mark)
    if d.rng.random() < 0.5:
        spout = quat_mul(axis_angle_quat((1, 0, 0), -math.pi / 4), X_TO_Z)
        pos = (0, w / 4 + 0.004, hz + w / 4 + 0.004)
        d.add(
            "spout_cap", "cylinder", (min(w * 0.18, 0.011), 0.005), pos, "plastic", band, quat=spout
        )
    return Traits((body, band), "paper", "cuboid")


# snacks ----------------------------------------------------------------------------------
@generator(
    "chewing_gum", size=(0.06, 0.1), synonyms=("chewing gum", "gum", "pack of gum"), revision=3
)
@reprint("gum")
def chewing_gum_2(d: Design) -> Traits:
    """Revision 2: every pack is a sleeve of sticks, opened at one end with three foil
    sticks pulled out to different lengths (the flat box of the first read as a mat)."""
    color, label = _gum_colors(d)
    lx, ly, hz = d.uniform(0.06, 0.075), d.uniform(0.02, 0.026), d.uniform(0.011, 0.014)
    d.box("sleeve", (lx / 2, ly / 2, hz / 2), (0, 0, hz / 2), "paper", color, solid_fraction=0.8)
    stick_t = (hz - 0.002) / 3
    for k, out in enumerate(sorted((d.uniform(0.006, 0.012), d.uniform(0.016, 0.026)))[::-1]):
        z = 0.001 + stick_t * (k + 0.5)
        d.box(
            f"stick_{k}",
            (out / 2, ly / 2 - 0.0012, stick_t / 2 - 0.0002),
            (lx / 2 + out / 2, 0, z),
            "paper",
            "silver",
        )
    _gum_label(d, color, label, lx, ly, hz)
    return Traits((color, label), "paper", "cuboid")


def _gum_colors(d: Design) -> tuple[str, str]:
    color = d.choice(WRAPPERS[:-1])
    return color, d.choice([c for c in PRINTS if c != color])


def _gum_label(d: Design, color: str, label: str, lx: float, ly: float, hz: float) -> None:
    """The band round the pack with its mint leaf."""
    mint = Texture("sticker", (color, "white" if label == "green" else "green"), "leaf")
    _band(
        d,
        "label",
        (lx * 0.18, ly / 2 + 0.0006, hz / 2 + 0.0006),
        hz / 2,
        label,
        x=-lx * 0.1,
        texture=mint,
    )


def _chip_cookie(
    d: Design, name: str, r: float, t: float, z0: float, color: str, chip: str, xy=(0.0, 0.0)
) -> float:
    """A round baked cookie on z0: a low slab under a domed, cracked top studded with
    chocolate chips; returns the height of its dome's crown."""
    dome = t * 0.5
    d.upright(name, r, t - dome * 0.4, z0, "organic", color, xy=xy, solid_fraction=0.6)
    top = z0 + t - dome * 0.4
    d.ellipsoid(f"{name}_dome", (r * 0.97, r * 0.97, dome), (xy[0], xy[1], top), "organic", color)
    crack = "beige" if color == "golden" else "golden"  # paler dough in the cracks
    for k in range(3):  # pale cracks across the crown
        a = d.uniform(0, math.pi) + k * math.pi / 3
        rho = r * d.uniform(0.15, 0.45)
        x, y = rho * math.cos(a + 1.3), rho * math.sin(a + 1.3)
        zz = top + dome * math.sqrt(max(0.0, 1 - (rho / r) ** 2)) - 0.0002
        d.box(
            f"{name}_crack_{k}",
            (r * d.uniform(0.3, 0.45), 0.0009, 0.0005),
            (xy[0] + x, xy[1] + y, zz),
            "organic",
            crack,
            yaw=a,
            visual_only=True,
        )
    n = int(d.rng.integers(11, 15))
    turn = d.uniform(0, 2 * math.pi)
    for k in range(n):  # scattered evenly over the top (a sunflower spiral)
        a = turn + k * 2.39996 + d.uniform(-0.2, 0.2)
        rho = r * 0.84 * math.sqrt((k + 0.5) / n)
        zz = top + dome * math.sqrt(max(0.0, 1 - (rho / r) ** 2))
        d.ellipsoid(
            f"{name}_chip_{k}",
            (0.0034, 0.003, 0.0022),
            (xy[0] + rho * math.cos(a), xy[1] + rho * math.sin(a), zz),
            "organic",
            chip,
            visual_only=True,
        )
    return top + dome


@generator("biscuit", size=(0.045, 0.21), synonyms=("biscuit", "cookie"), revision=3)
def biscuit_3(d: Design) -> Traits:
    """Revision 3: a biscuit people call a cookie at a glance: a round chocolate-chip
    cookie (a domed, cracked top studded with dark chips), a
    rectangular butter biscuit with a scalloped edge and docking holes, or a packet printed
    COOKIES with a cookie pictured (the first's smooth sandwich discs read as macarons)."""
    kind = d.choice(["cookie", "cookie", "cookie", "butter", "pack"])
    if kind == "pack":
        wrapper = d.choice(["red", "blue", "yellow", "orange", "brown", "purple"])
        ink = "white" if wrapper in ("red", "blue", "brown", "purple") else "brown"
        ly, lx, hz = d.uniform(0.13, 0.16), d.uniform(0.055, 0.065), d.uniform(0.032, 0.04)
        d.box("pack", (lx / 2, ly / 2, hz / 2), (0, 0, hz / 2), "paper", wrapper)
        for k, sign in enumerate((-1, 1)):  # the sealed crimped ends
            d.box(
                f"crimp_{k}",
                (lx / 2 - 0.003, 0.005, 0.0012),
                (0, sign * (ly / 2 + 0.005), hz / 2),
                "plastic",
                wrapper,
            )
        d.add(
            "pack_print",
            "box",
            (ly * 0.42, lx * 0.44, 0.0004),
            (0.0, 0.0, hz + 0.0004),
            "paper",
            wrapper,
            quat=axis_angle_quat((0, 0, 1), math.pi / 2),
            visual_only=True,
            texture=Texture("print_cookies", (ink, "golden"), "cookie"),
        )
        return Traits((wrapper,), "paper", "cuboid")
    if kind == "butter":
        color = d.choice(["golden", "golden", "beige"])
        lx, ly, t = d.uniform(0.04, 0.046), d.uniform(0.058, 0.066), d.uniform(0.0085, 0.0095)
        s = 0.0035  # the scallops' radius
        d.slab("biscuit", (lx / 2 - s / 2, ly / 2 - s / 2, t / 2), 0.0, "organic", color)
        k = 0
        for along, half, other, axis in ((ly, ly / 2, lx / 2, "y"), (lx, lx / 2, ly / 2, "x")):
            n = int(round(along / (2.2 * s)))
            for j in range(n):
                u = -half + s + (along - 2 * s) * j / (n - 1)
                for sign in (-1, 1):
                    xy = (sign * (other - s), u) if axis == "y" else (u, sign * (other - s))
                    d.upright(f"scallop_{k}", s, t, 0.0, "organic", color, xy=xy, visual_only=True)
                    k += 1
        for i in range(3):  # docking holes in a grid
            for j in range(4):
                x, y = (i - 1) * lx * 0.26, (j - 1.5) * ly * 0.22
                d.upright(
                    f"dock_{i}{j}",
                    0.0013,
                    0.0004,
                    t,
                    "organic",
                    "brown",
                    xy=(x, y),
                    visual_only=True,
                )
        return Traits((color,), "organic", "cuboid")
    color = d.choice(["golden", "golden", "beige", "brown"])
    chip = "white" if color == "brown" else d.choice(["brown", "black"])
    r = d.uniform(0.03, 0.036)
    _chip_cookie(d, "cookie", r, d.uniform(0.0075, 0.009), 0.0, color, chip)
    return Traits((color,), "organic", "disk")


@generator(
    "potato_chips", size=(0.15, 0.26), synonyms=("potato chips", "chips", "crisps"), revision=3
)
@reprint("chips")
def potato_chips(d: Design) -> Traits:
    color = d.choice(WRAPPERS[:-1])
    label = d.choice([c for c in ("yellow", "white", "red", "golden") if c != color])
    if d.rng.random() < 0.5:  # a stand-up bag
        w, t, hz = d.uniform(0.13, 0.18), d.uniform(0.05, 0.068), d.uniform(0.17, 0.23)
        d.box(
            "gusset",
            (w * 0.45, t * 0.35, 0.006),
            (0, 0, 0.006),
            "plastic",
            color,
            solid_fraction=0.05,
        )
        d.box(
            "core",
            (w / 2, t * 0.12, hz / 2 - 0.01),
            (0, 0, hz / 2),
            "plastic",
            color,
            solid_fraction=0.2,
        )
        d.ellipsoid(
            "puff",
            (w / 2, t / 2, hz * 0.5 - 0.004),
            (0, 0, hz / 2),
            "plastic",
            color,
            solid_fraction=0.05,
        )
        d.box("seal", (w / 2, 0.003, 0.01), (0, 0, hz - 0.01), "plastic", color)
        for k in range(int(w / 0.008)):
            x = -w / 2 + 0.004 + k * 0.008
            d.add(
                f"serration_{k}",
                "box",
                (0.0028, 0.0031, 0.0028),
                (x, 0, hz - 0.0005),
                "plastic",
                "silver",
                quat=axis_angle_quat((0, 1, 0), math.pi / 4),
                visual_only=True,
            )
        chip = Texture(
            "badge", (color, "orange" if label in ("yellow", "golden") else "golden"), "chip"
        )
        _print(d, "chip_picture", w * 0.27, t, hz * 0.45, label, texture=chip)
        return Traits((color, label), "plastic", "irregular")
    r, hz = d.uniform(0.033, 0.035), d.uniform(0.17, 0.24)
    d.upright("rim", r * 0.97, 0.005, 0.0, "aluminium", "silver")
    d.upright("tube", r, hz - 0.02, 0.005, "paper", color, solid_fraction=0.33)
    d.upright("lid", r + 0.0012, 0.015, hz - 0.015, "plastic", d.choice(["transparent", color]))
    chip = Texture(
        "sticker", (color, "orange" if label in ("yellow", "golden") else "golden"), "chip"
    )
    d.upright(
        "label", r + 0.0008, hz * 0.3, hz * 0.3, "paper", label, visual_only=True, texture=chip
    )
    return Traits((color, label), "paper", "cylinder")


@generator("chocolate", size=(0.08, 0.17), synonyms=("chocolate", "chocolate bar"), revision=3)
@reprint("chocolate")
def chocolate(d: Design) -> Traits:
    wrapper = d.choice(WRAPPERS[:-2] + ["golden"])
    if d.rng.random() < 0.5:  # a tablet, half unwrapped
        nx, ny = int(d.rng.integers(4, 7)), int(d.rng.integers(2, 4))
        cell = d.uniform(0.0205, 0.0225)
        lx, ly, t = nx * cell, ny * cell, d.uniform(0.004, 0.006)
        d.box("slab", (lx / 2, ly / 2, t / 2), (0, 0, t / 2), "organic", "brown")
        for i in range(nx):
            for j in range(ny):
                pos = ((i - (nx - 1) / 2) * cell, (j - (ny - 1) / 2) * cell, t + 0.002)
                d.box(
                    f"piece_{i}_{j}",
                    (cell / 2 - 0.0015, cell / 2 - 0.0015, 0.002),
                    pos,
                    "organic",
                    "brown",
                )
        cover = lx * d.uniform(0.35, 0.55)
        d.box(
            "wrapper",
            (cover / 2, ly / 2 + 0.001, t / 2 + 0.003),
            (-lx / 2 + cover / 2, 0, t / 2 + 0.002),
            "paper",
            wrapper,
            solid_fraction=0.1,
        )
        d.box(
            "foil",
            (0.0015, ly / 2 + 0.0012, t / 2 + 0.0032),
            (-lx / 2 + cover, 0, t / 2 + 0.002),
            "aluminium",
            "silver",
            visual_only=True,
        )
        return Traits(("brown", wrapper), "organic", "flat")
    label = d.choice([c for c in PRINTS if c != wrapper])
    lx, ly, hz = d.uniform(0.08, 0.12), d.uniform(0.028, 0.04), d.uniform(0.012, 0.018)
    d.box("bar", (lx / 2, ly / 2, hz / 2), (0, 0, hz / 2), "plastic", wrapper)
    _crimps(d, lx / 2, ly * 0.9, hz / 2, wrapper, 0.008)
    mark = Texture("sticker", (wrapper,))
    _band(d, "brand", (lx * 0.25, ly / 2 + 0.0006, hz / 2 + 0.0006), hz / 2, label, texture=mark)
    return Traits((wrapper, label), "plastic", "cuboid")


@generator(
    "cheese_sticks",
    size=(0.08, 0.15),
    synonyms=("cheese sticks", "string cheese", "cheese stick"),
    revision=3,
)
def cheese_sticks_3(d: Design) -> Traits:
    """Revision 3: string cheese: two sticks still in their clear wrappers (sealed flat at
    both ends), held by a coloured paper band printed STRING CHEESE, lying behind a pale stick
    unwrapped and peeled at one end into strings that splay over the table (plain peeled
    sticks read as nothing in particular; wrapped ones with a pictogram as glue sticks)."""
    cheese = d.choice(["white", "white", "white", "beige"])
    wrap = d.choice(["red", "blue", "green", "yellow", "orange", "purple"])
    ink = "white" if wrap != "yellow" else "red"
    r, length = d.uniform(0.0085, 0.0095), d.uniform(0.095, 0.11)
    # the wrapped sticks at the back (-x), lying along y
    for k in range(2):
        x = -(2 * r + 0.007) - k * (2 * r + 0.001)  # room for a finger by the front one
        y = d.uniform(-0.003, 0.003)
        d.rod(f"stick_{k}", r, length, (x, y, r), "organic", cheese, axis="y", capsule=True)
        d.rod(
            f"sleeve_{k}",
            r + 0.0007,
            length + 0.002,
            (x, y, r),
            "plastic",
            "transparent",
            axis="y",
            visual_only=True,
        )
        for j, sign in enumerate((-1, 1)):
            d.box(
                f"crimp_{k}{j}",
                (r * 0.9, 0.005, 0.0008),
                (x, y + sign * (length / 2 + 0.005), r),
                "plastic",
                "transparent",
                visual_only=True,
            )
    # a paper band round the two, printed STRING CHEESE on top
    band = d.uniform(0.021, 0.025)
    bx = -(3 * r + 0.0075)
    d.add(
        "pack_band",
        "box",
        (band, 2 * r + 0.0016, r + 0.0011),
        (bx, 0.0, r),
        "paper",
        wrap,
        quat=_yaw(math.pi / 2),  # the words along +y, their top towards -x
        visual_only=True,
        texture=Texture("print_cheese", (ink,)),
    )
    # the front stick, unwrapped, peeled at its +y end into strings
    x = 0.0
    peel = length * d.uniform(0.32, 0.38)
    body = length - peel
    y0 = -length / 2 + body  # where the strings leave the stick
    d.rod("stick_peeled", r, body, (x, y0 - body / 2, r), "organic", cheese, axis="y")
    strands = d.choice([7, 8, 9])
    for k in range(strands):
        f = (k + 0.5) / strands - 0.5  # from -0.5 (one side) to 0.5 (the other)
        sx, sz = r * 1.4 * f, r + r * 0.5 * math.cos(math.pi * f) * (1 if k % 2 else -0.6)
        thick = r * d.uniform(0.17, 0.22)
        mid = (x + r * 1.6 * f, y0 + peel * 0.5, max(sz * 0.6, thick))
        end = (x + r * 2.4 * f + r * 0.3, y0 + peel - thick, thick)
        d.segment(
            f"peel_string_{k}",
            "capsule",
            (x + sx, y0 - 0.004, sz),
            mid,
            thick,
            "organic",
            cheese,
            visual_only=True,
        )
        d.segment(
            f"peel_string_end_{k}",
            "capsule",
            mid,
            end,
            thick,
            "organic",
            cheese,
            visual_only=True,
        )
    fibre = "beige" if cheese == "white" else "white"
    for k, a in enumerate((-0.9, -0.3, 0.35, 0.95)):
        d.rod(
            f"fibre_{k}",
            0.00035,
            body * 0.7,
            (x + r * math.sin(a), y0 - body * 0.45, r + r * math.cos(a)),
            "organic",
            fibre,
            axis="y",
            visual_only=True,
        )
    return Traits((cheese, wrap), "organic", "elongated")


@generator("bread", size=(0.07, 0.24), revision=3)
def bread_3(d: Design) -> Traits:
    """Revision 3: a golden-brown sandwich loaf, its domed top overhanging the tin-baked
    sides, cut at the front to show a porous crumb, two slices cut off standing a little
    apart; or a long baguette with pale diagonal slashes (the oval loaves read as potatoes
    and kiwis; a cut slice lying flat before the loaf read as a slipper's sole)."""
    top = d.choice(["brown", "brown", "golden"])
    crumb = d.choice(["beige", "beige", "white"])
    pores = Texture("pores")
    if d.rng.random() < 0.65:
        side = "golden"
        lx, ly, hz = d.uniform(0.1, 0.12), d.uniform(0.06, 0.064), d.uniform(0.042, 0.048)
        a = ly / 2 * 1.06  # the domed top: an arc of a circle, overhanging the sides
        dome = ly / 2 * d.uniform(0.62, 0.72)
        zc = hz + dome - a
        t, gap = d.uniform(0.011, 0.013), d.uniform(0.0025, 0.0045)
        x0, x1 = -lx / 2, lx / 2 - 2 * (t + gap)  # the loaf from x0 to its cut end x1

        def piece(name: str, lo: float, hi: float, **kw) -> None:
            mid, half = (lo + hi) / 2, (hi - lo) / 2
            d.box(name, (half, ly / 2, hz / 2), (mid, 0, hz / 2), "organic", side, **kw)
            d.add(
                f"{name}_top",
                "cylinder",
                (a, half),
                (mid, 0, zc),
                "organic",
                top,
                solid_fraction=0.3,
            )
            face = hi + 0.0005  # the cut face: a porous crumb inside a rim of crust
            d.box(
                f"{name}_crumb",
                (0.0005, ly / 2 - 0.0035, hz / 2 - 0.002),
                (face, 0, hz / 2 + 0.001),
                "organic",
                crumb,
                visual_only=True,
                texture=pores,
            )
            d.add(
                f"{name}_crumb_top",
                "cylinder",
                (a - 0.004, 0.0005),
                (face - 0.0002, 0, zc),
                "organic",
                crumb,
                visual_only=True,
                texture=pores,
            )

        piece("loaf", x0, x1, solid_fraction=0.3)
        for k in range(2):
            lo = x1 + gap + k * (t + gap)
            piece(f"slice_{k}", lo, lo + t, solid_fraction=0.3)
        return Traits((top, side) if top != side else (top,), "organic", "cuboid")
    crumb = "beige"
    a, b = d.uniform(0.1, 0.115), d.uniform(0.022, 0.027)
    c = b
    d.rod("baguette", b, 2 * a, (0, 0, c), "organic", top, capsule=True, solid_fraction=0.3)
    slashes = int(d.rng.integers(4, 6))
    for k in range(slashes):
        x = (k - (slashes - 1) / 2) * a * 1.55 / slashes
        radii = (a * 1.05 / slashes, b * 0.26, 0.0035)
        d.add(
            f"slash_{k}",
            "ellipsoid",
            radii,
            (x, 0, 2 * c - 0.0016),
            "organic",
            crumb,
            quat=_yaw(0.35),
            visual_only=True,
        )
    return Traits((top,), "organic", "elongated")


@generator("potato", size=(0.06, 0.13), revision=3)
def potato_3(d: Design) -> Traits:
    """Revision 3: an oblong, knobbly tuber, flattened and lumpy, with sunken eyes and
    earthy specks, in earthy skins (a round red one read as an apple or a tomato; a
    lemon-yellow skin is gone)."""
    color = d.choice(["brown", "brown", "brown", "beige", "beige", "red"])
    a = d.uniform(0.038, 0.056)
    b, c = min(a * d.uniform(0.55, 0.66), 0.032), a * d.uniform(0.42, 0.5)
    d.ellipsoid("tuber", (a, b, c), (0, 0, c), "organic", color)
    for k, (fx, fy) in enumerate(((-0.55, 0.25), (0.5, -0.3), (0.1, 0.45))):
        lump = (a * d.uniform(0.38, 0.5), b * d.uniform(0.6, 0.75), c * d.uniform(0.75, 0.9))
        d.ellipsoid(f"knob_{k}", lump, (fx * a, fy * b, lump[2] + 0.001), "organic", color)
    eye = "brown" if color != "brown" else "black"
    speck = "beige" if color in ("red", "brown") else "brown"
    _dots(d, "eye", (0, 0, c), (a * 0.97, b * 0.97, c * 0.97), 7, 0.0022, eye)
    _dots(d, "speck", (0, 0, c), (a, b, c), 14, 0.001, speck)
    return Traits((color,), "organic", "irregular")


@generator("peach", size=(0.055, 0.1), revision=3)
def peach_3(d: Design) -> Traits:
    """Revision 3: a cleft, heart-shaped peach with a red blush over its yellow-orange skin,
    a deep dark crease from the stalk and a slender leaf (a plain orange ball read as an
    orange)."""
    skin = d.choice(["orange", "orange", "yellow"])
    blush = "red"
    r = d.uniform(0.0295, 0.035)
    h = r * d.uniform(0.9, 1.0)
    for k, s in enumerate((-1, 1)):  # two cheeks either side of the crease
        d.ellipsoid(f"cheek_{k}", (r * 0.96, r * 0.6, h), (0, s * r * 0.38, h), "organic", skin)
    for k, s in enumerate((-1, 1)):  # a blush on each cheek, strongest facing the sun
        shift = r * (0.1 if s > 0 else 0.06)
        centre = (shift * 0.8, s * (r * 0.36 + shift * 0.5), h + shift * 0.4)
        radii = (r * 0.9, r * 0.56, h * 0.93)
        d.ellipsoid(f"blush_{k}", radii, centre, "organic", blush, visual_only=True)
    crease = "orange" if skin == "yellow" else "red"
    d.ellipsoid(
        "suture", (r * 0.97, 0.0016, h * 1.005), (0, 0, h), "organic", crease, visual_only=True
    )
    _stalk(d, 2 * h - 0.002, d.uniform(0.006, 0.009), 0.15)
    if d.rng.random() < 0.7:  # a long narrow peach leaf
        yaw = d.uniform(-0.6, 0.6)
        pos = (-0.016 * math.cos(yaw), -0.016 * math.sin(yaw), 2 * h + 0.002)
        d.add(
            "peach_leaf",
            "ellipsoid",
            (0.022, 0.0065, 0.0012),
            pos,
            "organic",
            "green",
            quat=quat_mul(_yaw(yaw), axis_angle_quat((0, 1, 0), 0.25)),
        )
    return Traits((skin, blush), "organic", "sphere")


@generator("candy", size=(0.035, 0.08), synonyms=("candy", "sweet", "wrapped candy"), revision=3)
def candy_3(d: Design) -> Traits:
    """Revision 3: a sweet in a shiny twist wrapper whose pleated ends fan out upright like
    a bow tie, or a red-and-white peppermint swirl in a clear twist wrapper (the first, its
    fans lying flat, read as a vase)."""
    if d.rng.random() < 0.4:  # a peppermint lying flat, its swirl on top
        stripe = d.choice(["red", "red", "green"])
        r, t = d.uniform(0.011, 0.014), d.uniform(0.0095, 0.011)
        d.upright("mint", r, t, 0.0, "organic", "white")
        for k in range(8):
            a = 2 * math.pi * k / 8
            pos = (r * 0.5 * math.cos(a), r * 0.5 * math.sin(a), t + 0.0003)
            half = (r * 0.46, r * 0.15, 0.0003)
            d.box(f"swirl_{k}", half, pos, "organic", stripe, yaw=a + 0.45, visual_only=True)
        _bow_ends(d, r, r, t / 2, "transparent", flat=True)
        return Traits(("white", stripe), "organic", "disk")
    wrapper = d.choice(WRAPPERS[:-2] + ["golden", "silver"])
    stripe = d.choice([c for c in PRINTS if c != wrapper])
    a, b = d.uniform(0.012, 0.016), d.uniform(0.009, 0.011)
    c = b
    d.ellipsoid("sweet", (a, b, c), (0, 0, c), "organic", wrapper, solid_fraction=1.6)
    d.ellipsoid(
        "stripe", (a * 0.28, b * 1.03, c * 1.03), (0, 0, c), "plastic", stripe, visual_only=True
    )
    _bow_ends(d, a, b, c, wrapper)
    return Traits((wrapper, stripe), "organic", "ellipsoid")


def _bow_ends(d: Design, a: float, b: float, c: float, color: str, flat: bool = False) -> None:
    """The twisted ends of a sweet's wrapper at x = +-a, each a pinch and a pleated fan,
    standing across the sweet like a bow tie (or lying ``flat`` on the table)."""
    fan = d.uniform(0.007, 0.009)
    for k, sign in enumerate((-1, 1)):
        d.rod(f"twist_{k}", 0.0022, 0.006, (sign * (a + 0.0015), 0, c), "plastic", color)
        for j, tilt in enumerate((-0.5, -0.25, 0.0, 0.25, 0.5)):  # pleats in a fan
            spread = axis_angle_quat((0, 0, 1), sign * tilt) if flat else IDENTITY_Q
            lean = IDENTITY_Q if flat else axis_angle_quat((1, 0, 0), tilt)
            reach = a + 0.0042 + fan / 2
            pos = (sign * reach, math.tan(tilt) * fan / 2 if flat else 0.0, c)
            half = (fan / 2, b * 0.8, 0.0006) if flat else (fan / 2, 0.0006, c * 0.85)
            d.add(
                f"pleat_{k}_{j}",
                "box",
                half,
                pos,
                "plastic",
                color,
                quat=quat_mul(spread, lean),
            )
