"""Electronic accessories and desk decorations."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import X_TO_Z, axis_angle_quat, quat_mul
from ..textures import Texture
from .registry import generator


def _pill(d: Design, name: str, length, width, height, z0, material, color, **kw) -> None:
    """A slab with round ends in plan view (a pill) along x, standing on z = z0; half of each
    end cylinder lies inside the core box, so the ends get half its fill."""
    fill = kw.pop("solid_fraction", 1.0)
    kw.update(ends=("end-1", "end1"), end_fill=fill / 2, solid_fraction=fill)
    d.stadium(name, max(length - width, 1e-4) / 2, width / 2, z0, height, material, color, **kw)


def dot(d: Design, name: str, radius: float, x: float, y: float, z: float, color: str) -> None:
    """A flat round button printed on a surface at height z."""
    d.upright(name, radius, 0.001, z, "rubber", color, xy=(x, y), visual_only=True)


def beam(d: Design, name: str, p1, p2, half_w: float, half_t: float, material: str, color: str):
    """A plate from p1 to p2 in the xz plane (a tilted backrest, a strut)."""
    dx, dz = p2[0] - p1[0], p2[1] - p1[1]
    center = ((p1[0] + p2[0]) / 2, 0.0, (p1[1] + p2[1]) / 2)
    half = (half_t, half_w, math.hypot(dx, dz) / 2)
    quat = axis_angle_quat((0, 1, 0), math.atan2(dx, dz))
    d.add(name, "box", half, center, material, color, quat=quat)


MOUSE_COLORS = ["black", "gray", "white", "silver", "blue", "red"]


@generator("mouse", size=(0.09, 0.13), synonyms=("computer mouse", "mouse"), revision=2)
def mouse_2(d: Design) -> Traits:
    """Revision 2: the two buttons show (a seam between them up to the wheel, and one
    across behind them) and the wheel stands proud in the gap."""
    shell = d.choice(MOUSE_COLORS)
    skirt = d.choice(["black", "gray", shell])
    lx, w, h = d.uniform(0.095, 0.125), d.uniform(0.055, 0.068), d.uniform(0.032, 0.042)
    _mouse_body(d, shell, skirt, lx, w, h)
    seam = "gray" if shell in ("black", "blue", "red") else "black"

    def top(x: float) -> float:  # the shell's top along its middle
        return h / 2 + h / 2 * math.sqrt(max(0.0, 1 - (2 * x / lx) ** 2))

    back, front = -lx * 0.04, lx * 0.47
    xs = [back + (front - back) * k / 4 for k in range(5)]
    for k, (x0, x1) in enumerate(zip(xs[:-1], xs[1:], strict=True)):
        d.segment(
            f"seam_{k}",
            "box",
            (x0, 0, top(x0) + 0.0004),
            (x1, 0, top(x1) + 0.0004),
            (0.0007, 0.0005),
            "plastic",
            seam,
            visual_only=True,
        )
    scale = math.sqrt(1 - (2 * back / lx) ** 2)
    d.add(
        "seam_across",
        "ellipsoid",
        (0.0007, w / 2 * scale + 0.0004, h / 2 * scale + 0.0004),
        (back, 0, h / 2),
        "plastic",
        seam,
        visual_only=True,
    )
    x = lx * 0.24
    d.rod("wheel", 0.0072, 0.0055, (x, 0, top(x) - 0.0012), "rubber", "black", axis="y")
    return Traits((shell, skirt), "plastic", "ellipsoid")


def _mouse_body(d: Design, shell: str, skirt: str, lx: float, w: float, h: float) -> None:
    _pill(d, "skirt", lx, w, h / 2, 0.0, "plastic", skirt, solid_fraction=0.3)
    d.ellipsoid(
        "shell", (lx / 2, w / 2, h / 2), (0, 0, h / 2), "plastic", shell, solid_fraction=0.3
    )


#: The lit segments of a seven-segment digit (a top, b top right, c bottom right, d bottom,
#: e bottom left, f top left, g middle), and the ends of each in a cell one wide, two high.
LCD_LIT = {
    "1": "bc",
    "2": "abged",
    "4": "fgbc",
    "5": "afgcd",
    "6": "afgedc",
    "8": "abcdefg",
    "C": "afed",
}
LCD_SEGMENTS = {
    "a": (0, 0, 1, 0),
    "b": (1, 0, 1, 1),
    "c": (1, 1, 1, 2),
    "d": (0, 2, 1, 2),
    "e": (0, 1, 0, 2),
    "f": (0, 0, 0, 1),
    "g": (0, 1, 1, 1),
}


def lcd_glyph(d: Design, name: str, glyph: str, top_left, cell: float, z: float, ink: str):
    """A seven-segment glyph printed flat at height z, read with its top towards -x (its
    left at -y): ``cell`` wide, twice that high, from the top-left corner (x, y)."""
    x0, y0 = top_left
    for seg in LCD_LIT[glyph]:
        a, b, c, e = LCD_SEGMENTS[seg]
        p0 = (x0 + b * cell, y0 + a * cell, z)
        p1 = (x0 + e * cell, y0 + c * cell, z)
        d.segment(
            f"{name}_{seg}", "box", p0, p1, (cell * 0.13, 0.0003), "plastic", ink, visual_only=True
        )


@generator(
    "ac_remote",
    size=(0.12, 0.18),
    synonyms=("ac remote", "air conditioner remote", "aircon remote"),
    revision=3,
)
def ac_remote_3(d: Design) -> Traits:
    """Revision 3: a white air-conditioner remote whose top third is a large display (its
    top towards -x): a snowflake, a fan and COOL over the set temperature in big digits
    with degrees C; under it a few large keys: a big red power key, MODE, the temperature
    down/up keys either side of TEMP, FAN and SWING (the first, a small display over a grid
    of keys, read as any remote control)."""
    color = d.choice(["white", "white", "white", "beige"])
    keys = "silver"
    lx, w, t = d.uniform(0.15, 0.17), d.uniform(0.052, 0.058), d.uniform(0.017, 0.02)
    core = lx - t
    d.box("body", (core / 2, w / 2, t / 2), (0, 0, t / 2), "plastic", color, solid_fraction=0.6)
    for sign in (-1, 1):
        d.rod(
            f"end_{sign}",
            t / 2,
            w,
            (sign * core / 2, 0, t / 2),
            "plastic",
            color,
            axis="y",
            solid_fraction=0.3,
        )
    d.rod(
        "ir_window",
        t * 0.32,
        w * 0.5,
        (-lx / 2 + 0.0015, 0, t / 2),
        "plastic",
        "black",
        axis="y",
        visual_only=True,
    )
    # the display: the top third of the face
    span = lx * 0.36
    sx0, sx1 = -core / 2 + 0.002, -core / 2 + 0.002 + span
    z = t + 0.0004
    zt = z + 0.0004
    d.box(
        "display_bezel",
        (span / 2 + 0.002, w * 0.45, 0.0003),
        ((sx0 + sx1) / 2, 0, t),
        "plastic",
        "black",
        visual_only=True,
    )
    d.box(
        "lcd", (span / 2, w * 0.41, 0.0004), ((sx0 + sx1) / 2, 0, z), "plastic", keys,
        visual_only=True,
    )  # fmt: skip
    # the icon row: a snowflake, a fan and the mode word
    row = sx0 + span * 0.17
    icon = span * 0.13
    for k in range(3):
        d.box(
            f"snowflake_{k}", (icon, icon * 0.14, 0.0003), (row, -w * 0.28, zt), "plastic",
            "blue", yaw=k * math.pi / 3, visual_only=True,
        )  # fmt: skip
    fan = (row, -w * 0.08)
    d.upright("fan_hub", icon * 0.22, 0.0004, zt, "plastic", "black", xy=fan, visual_only=True)
    for k in range(3):
        a = k * 2 * math.pi / 3 + 0.4
        d.ellipsoid(
            f"fan_blade_{k}",
            (icon * 0.5, icon * 0.22, 0.0003),
            (fan[0] + icon * 0.5 * math.cos(a), fan[1] + icon * 0.5 * math.sin(a), zt),
            "plastic",
            "black",
            quat=axis_angle_quat((0, 0, 1), a),
            visual_only=True,
        )
    d.box(
        "mode_word", (w * 0.15, icon * 0.75, 0.0003), (row, w * 0.2, zt), "plastic", keys,
        yaw=math.pi / 2, visual_only=True, texture=Texture("print_cool", ("black",)),
    )  # fmt: skip
    # the set temperature, big, and degrees C
    temp = d.choice(["24", "25", "26", "22", "18", "16"])
    cell = min(w * 0.2, span * 0.29)
    top, y0 = sx0 + span * 0.33, -cell * 3.55 / 2
    for k, glyph in enumerate(temp):
        lcd_glyph(d, f"temp_digit_{k}", glyph, (top, y0 + k * cell * 1.45), cell, zt, "black")
    deg = y0 + 2.45 * cell + 0.2 * cell
    d.flat_ring(
        "degree",
        cell * 0.14,
        cell * 0.08,
        0.0003,
        z,
        "plastic",
        "black",
        center=(top + 0.15 * cell, deg),
        segments=6,
        visual_only=True,
    )
    lcd_glyph(d, "unit", "C", (top, deg + 0.35 * cell), cell * 0.6, zt, "black")

    def key(name: str, word: str, x: float, y: float) -> None:
        """A wide key printed with its word, read from the front (its top towards -x)."""
        d.box(
            name, (w * 0.17, 0.0048, 0.0006), (x, y, t + 0.0006), "rubber", keys,
            yaw=math.pi / 2, visual_only=True, texture=Texture(f"print_{word}", ("black",)),
        )  # fmt: skip

    # the keys: a big power key and MODE, the temperature down/up keys, FAN and SWING
    x = sx1 + 0.013
    dot(d, "power", 0.0085, x, w * 0.24, t, "red")
    key("mode_key", "mode", x, -w * 0.2)
    x += 0.019
    for k, sign in enumerate((-1, 1)):  # temperature down (-y) and up (+y)
        c = (x, sign * w * 0.3)
        dot(d, f"temp_key_{k}", 0.0078, *c, t, "blue")
        d.box(
            f"temp_sign_{k}", (0.0009, 0.004, 0.0003), (*c, t + 0.0013), "plastic", "white",
            visual_only=True,
        )  # fmt: skip
        if sign > 0:
            d.box(
                "temp_plus", (0.004, 0.0009, 0.0003), (*c, t + 0.0013), "plastic", "white",
                visual_only=True,
            )  # fmt: skip
    d.box(
        "temp_word", (w * 0.13, 0.004, 0.0003), (x, 0, t + 0.0003), "plastic", color,
        yaw=math.pi / 2, visual_only=True, texture=Texture("print_temp", ("black",)),
    )  # fmt: skip
    x += 0.018
    key("fan_key", "fan", x, -w * 0.2)
    key("swing_key", "swing", x, w * 0.2)
    d.box(
        "cover_seam", (0.0004, w * 0.46, 0.0002), (x + 0.014, 0, t + 0.0002), "plastic", "gray",
        visual_only=True,
    )  # fmt: skip
    return Traits((color,), "plastic", "cuboid")


def _arrowhead(
    d: Design, name: str, x: float, y: float, z: float, size: float, point: int, ink: str
) -> None:
    """A filled triangle printed at height z, pointing to +y (``point`` 1) or -y (-1): four
    strips across, shorter towards the tip."""
    for j in range(4):
        d.box(
            f"{name}_{j}",
            (size * (1 - j / 4), size / 8 + 0.0001, 0.0002),
            (x, y + point * (j - 1.5) * size / 4, z),
            "plastic",
            ink,
            visual_only=True,
        )


@generator(
    "presenter_clicker",
    size=(0.085, 0.14),
    synonyms=("presentation clicker", "slide clicker", "presentation remote", "presenter"),
    revision=3,
)
def presenter_clicker_3(d: Design) -> Traits:
    """Revision 3: a short, slim presenter stick lying across the view: only three keys in a
    row on top, a red laser key by the nose and two big page keys marked with white forward
    and back arrowheads; a glossy black laser nose with a silver ring and red lens at the
    tip, and a lanyard loop through the back end (a short remote with round keys read as a
    car key fob; a long one with a keypad of page keys read as a TV remote)."""
    color = d.choice(["black", "silver", "black", "gray", "silver", "white"])
    keys = "black" if color != "black" else d.choice(["gray", "silver"])
    ink = "white" if keys == "black" else "black"
    loop = d.choice(["black", "gray"] if color != "black" else ["gray", "red", "blue"])
    lx, w, t = d.uniform(0.094, 0.104), d.uniform(0.022, 0.025), d.uniform(0.011, 0.013)
    half = lx / 2 - w / 2  # the straight middle of the body, along y
    d.box("body", (w / 2, half, t / 2), (0.0, 0.0, t / 2), "plastic", color, solid_fraction=0.6)
    tip_color = "black" if color != "black" else "gray"  # the glossy laser end
    d.upright("body_back", w / 2, t, 0.0, "plastic", color, xy=(0, -half), solid_fraction=0.3)
    d.upright("laser_end", w / 2, t, 0.0, "plastic", tip_color, xy=(0, half), solid_fraction=0.3)
    d.segment(
        "nose",
        "ellipsoid",
        (0, half - 0.002, t / 2),
        (0, half + w / 2 + 0.007, t / 2),
        (w * 0.34, t * 0.4),
        "plastic",
        tip_color,
        solid_fraction=0.6,
    )
    tip = half + w / 2 + 0.0062
    d.rod(
        "laser_ring",
        0.0032,
        0.0014,
        (0, tip - 0.0008, t / 2),
        "metal",
        "silver",
        axis="y",
        visual_only=True,
    )
    d.rod(
        "laser", 0.0024, 0.001, (0, tip + 0.0003, t / 2), "glass", "red", axis="y", visual_only=True
    )
    d.upright("laser_key", w * 0.2, 0.0012, t, "rubber", "red", xy=(0, half - 0.006))
    for k, (y, point) in enumerate(((half * 0.22, 1), (-half * 0.42, -1))):
        d.ellipsoid(f"page_key_{k}", (w * 0.36, 0.011, 0.0016), (0, y, t), "rubber", keys)
        _arrowhead(d, f"arrow_{k}", 0, y - point * 0.001, t + 0.0016, 0.0058, point, ink)
    # the lanyard loop through a slot at the back end
    d.flat_ring(
        "lanyard",
        0.0058,
        0.0016,
        0.0022,
        0.0,
        "fabric",
        loop,
        center=(0.0, -lx / 2 - 0.0035),
        segments=10,
    )
    return Traits((color,), "plastic", "elongated")


@generator("gamepad", size=(0.12, 0.17), synonyms=("gamepad", "game controller", "joypad"))
def gamepad(d: Design) -> Traits:
    color = d.choice(["black", "white", "gray", "blue", "red", "purple"])
    accent = "gray" if color == "black" else "black"
    w, depth, h = d.uniform(0.13, 0.16), d.uniform(0.034, 0.039), d.uniform(0.022, 0.028)
    _pill(d, "body", w, depth, h, 0.0, "plastic", color, solid_fraction=0.5)
    for sign in (-1, 1):
        d.add(
            f"grip_{sign}",
            "ellipsoid",
            (0.018, 0.028, h / 2),
            (sign * w * 0.3, -depth / 2, h / 2),
            "plastic",
            color,
            quat=axis_angle_quat((0, 0, 1), sign * 0.35),
            solid_fraction=0.5,
        )
        bumper = (0.014, 0.0025, h * 0.25)
        d.box(
            f"bumper_{sign}",
            bumper,
            (sign * w * 0.3, depth / 2 + 0.0025, h * 0.6),
            "plastic",
            accent,
        )
        d.upright(
            f"stick_{sign}", 0.0035, 0.005, h, "plastic", accent, xy=(sign * w * 0.12, -depth * 0.2)
        )
        d.upright(
            f"stick_cap_{sign}",
            0.0085,
            0.003,
            h + 0.005,
            "rubber",
            accent,
            xy=(sign * w * 0.12, -depth * 0.2),
        )
        d.box(
            f"menu_{sign}",
            (0.003, 0.0012, 0.0004),
            (sign * 0.008, depth * 0.18, h + 0.0004),
            "rubber",
            accent,
            visual_only=True,
        )
    pad = (-w * 0.3, depth * 0.08, h + 0.0008)
    for k, half in enumerate(((0.008, 0.0025, 0.0008), (0.0025, 0.008, 0.0008))):
        d.box(f"dpad_{k}", half, pad, "rubber", accent, visual_only=True)
    for name, dx, dy in (("yellow", 0, 1), ("green", 0, -1), ("blue", -1, 0), ("red", 1, 0)):
        dot(d, f"button_{name}", 0.0035, w * 0.3 + dx * 0.0075, depth * 0.08 + dy * 0.0075, h, name)
    return Traits((color,), "plastic", "irregular")


@generator(
    "earbud_case",
    size=(0.045, 0.075),
    synonyms=("earbud case", "earbuds case", "earphone case"),
    revision=3,
)
def earbud_case_3(d: Design) -> Traits:
    """Revision 3: the case stands with its lid flipped open, the two earbuds seated in it
    showing their heads and speaker grilles (the closed first case read as a round box or a
    hat box)."""
    color = d.choice(["white", "white", "white", "black", "gray", "blue", "pink"])
    buds = color if color in ("white", "black") else d.choice(["white", "black"])
    lx, depth = d.uniform(0.045, 0.055), d.uniform(0.021, 0.025)
    hb, hl = d.uniform(0.032, 0.04), d.uniform(0.011, 0.014)
    _pill(d, "base", lx, depth, hb, 0.0, "plastic", color, solid_fraction=0.5)
    d.box(
        "tray",
        ((lx - depth) / 2 + depth * 0.3, depth / 2 - 0.0025, 0.0003),
        (0, 0, hb + 0.0003),
        "plastic",
        "gray" if color == "white" else "black",
        visual_only=True,
    )
    for k, sign in enumerate((-1, 1)):
        c = (sign * lx * 0.2, 0.0005, hb + 0.004)
        d.ellipsoid(f"bud_{k}", (0.0085, 0.0075, 0.0065), c, "plastic", buds)
        d.ellipsoid(
            f"grille_{k}",
            (0.004, 0.0035, 0.0015),
            (c[0] - sign * 0.002, c[1] + 0.001, c[2] + 0.0055),
            "fabric",
            "black" if buds == "white" else "gray",
            visual_only=True,
        )
    # the lid flipped open on its hinge along the back edge (-y), leaning back a little
    tilt = d.uniform(1.75, 1.95)
    turn = axis_angle_quat((1, 0, 0), tilt)
    hinge = (0.0, -depth / 2, hb)
    core = max(lx - depth, 1e-4) / 2

    def lid_point(x, y, z):  # a point of the closed lid (hinge frame) once opened
        return (
            hinge[0] + x,
            hinge[1] + y * math.cos(tilt) - z * math.sin(tilt),
            hinge[2] + y * math.sin(tilt) + z * math.cos(tilt),
        )

    d.add(
        "lid",
        "box",
        (core, depth / 2, hl / 2),
        lid_point(0, depth / 2, hl / 2),
        "plastic",
        color,
        quat=turn,
        solid_fraction=0.4,
    )
    for k, sign in enumerate((-1, 1)):
        d.add(
            f"lid_end_{k}",
            "cylinder",
            (depth / 2, hl / 2),
            lid_point(sign * core, depth / 2, hl / 2),
            "plastic",
            color,
            quat=quat_mul(turn, X_TO_Z),
            solid_fraction=0.2,
        )
    d.add(
        "lid_inside",
        "box",
        (core, depth / 2 - 0.002, 0.0003),
        lid_point(0, depth / 2, -0.0003),
        "plastic",
        "gray" if color == "white" else "black",
        quat=turn,
        visual_only=True,
    )
    d.rod(
        "led",
        0.0012,
        0.0006,
        (0, depth / 2 + 0.0003, hb * 0.55),
        "plastic",
        d.choice(["green", "white", "orange"]),
        axis="y",
        visual_only=True,
    )
    return Traits((color,), "plastic", "cuboid")


@generator(
    "charging_head",
    size=(0.04, 0.075),
    synonyms=("wall charger", "charging head", "power adapter", "charger plug"),
)
def charging_head(d: Design) -> Traits:
    color = d.choice(["white", "white", "black", "gray"])
    lx, w = d.uniform(0.026, 0.045), d.uniform(0.026, 0.045)
    round_pins = d.rng.random() < 0.5
    h = d.uniform(0.027, 0.034) if round_pins else d.uniform(0.022, 0.03)
    d.slab("body", (lx / 2, w / 2, h / 2), 0.0, "plastic", color)
    if round_pins:
        d.rod("plug_face", 0.013, 0.006, (lx / 2 + 0.003, 0, h / 2), "plastic", color)
        for sign in (-1, 1):
            pin = (lx / 2 + 0.006 + 0.0095, sign * 0.0095, h / 2)
            d.rod(f"pin_{sign}", 0.002, 0.019, pin, "metal", "silver")
    else:
        for sign in (-1, 1):
            prong = (lx / 2 + 0.008, sign * 0.0063, h / 2)
            d.box(f"prong_{sign}", (0.008, 0.0008, 0.003), prong, "metal", "silver")
    d.box(
        "port",
        (0.0004, 0.006, 0.0022),
        (-lx / 2 - 0.0004, 0, h / 2),
        "plastic",
        "black",
        visual_only=True,
    )
    dot(d, "logo", min(lx, w) * 0.18, 0, 0, h, "gray" if color != "gray" else "white")
    return Traits((color,), "plastic", "cube" if abs(lx - w) < 0.006 else "cuboid")


def _plug(d: Design, name: str, x: float, sign: int, housing, tip, color: str, tip_color: str):
    """A cable plug lying on the table at x, pointing away along sign * x."""
    d.box(f"{name}_housing", housing, (x + sign * housing[0], 0, housing[2]), "plastic", color)
    tip_x = x + sign * (2 * housing[0] + tip[0])
    d.box(f"{name}_tip", tip, (tip_x, 0, housing[2]), "metal", tip_color)


@generator(
    "charging_cable",
    size=(0.1, 0.19),
    synonyms=("charging cable", "usb cable", "charger cable", "phone cable"),
)
def charging_cable(d: Design) -> Traits:
    color = d.choice(["white", "white", "black", "gray", "red", "blue"])
    cr, radius, loops, n = d.uniform(0.0017, 0.0022), d.uniform(0.022, 0.031), d.choice([2, 3]), 12
    for j in range(loops):
        rj, cx = radius - j * cr * 1.2, j * 0.0015
        for k in range(n):
            a = 2 * math.pi * k / n
            pos = (cx + rj * math.cos(a), rj * math.sin(a), cr + j * 1.6 * cr)
            d.add(
                f"loop_{j}_{k}",
                "capsule",
                (cr, rj * math.pi / n),
                pos,
                "plastic",
                color,
                quat=axis_angle_quat((0, 0, 1), a + math.pi / 2),
            )
    tie = d.choice(["black", "green", "blue", "red"])
    bundle = (0.005, loops * cr * 1.3, (loops * 1.6 + 0.4) * cr / 2 + 0.0004)
    d.box(
        "tie",
        bundle,
        (0, radius - cr * 0.6 * loops, bundle[2] - 0.0003),
        "fabric",
        tie,
        visual_only=True,
    )
    for sign in (1, -1):
        tail = d.uniform(0.008, 0.025)
        start = sign * (radius + (0.0015 * (loops - 1) if sign > 0 else 0.0))
        d.rod(f"tail_{sign}", cr, tail, (start + sign * tail / 2, 0, cr), "plastic", color)
        if sign > 0:  # USB-A
            _plug(
                d,
                "usb_a",
                start + tail,
                1,
                (0.009, 0.0065, 0.0038),
                (0.006, 0.006, 0.0022),
                color,
                "silver",
            )
        else:  # USB-C or Lightning
            tip = d.choice(["silver", "silver", "white"]) if color == "white" else "silver"
            _plug(
                d,
                "phone_end",
                start - tail,
                -1,
                (0.0075, 0.0042, 0.0031),
                (0.0042, 0.0042, 0.0012),
                color,
                tip,
            )
    return Traits((color,), "plastic", "ring")


@generator(
    "mini_sculpture",
    size=(0.06, 0.16),
    synonyms=("figurine", "statuette", "mini sculpture", "small sculpture"),
    revision=3,
)
def mini_sculpture_3(d: Design) -> Traits:
    """Revision 3: always a statue of a person, a marble or bronze bust on a round socle or
    a classical statue of a woman in a long draped gown (the abstract kinds read as a cairn
    or a ring, the ellipsoid figure with a knob head as a joystick, and a standing figure
    with jointed limbs as an artist's mannequin)."""
    return _sculpture_3(d)


def _sculpture_3(d: Design) -> Traits:
    """A small statue of a person on a plinth: a marble or bronze bust (chest, shoulders,
    neck, a head with hair, ears and a nose) on a round socle, or a draped woman (a flared
    gown with folds, a sash, smooth arms, a head with the hair in a bun)."""
    bust = d.rng.random() < 0.5
    material, color = d.choice(
        [
            ("stone", "white"),
            ("stone", "white"),
            ("ceramic", "white"),
            ("stone", "gray"),
            ("metal", "golden"),
            ("metal", "brown"),
            ("stone", "black"),
            ("stone", "white"),
        ][: 4 if bust else 8]
    )
    if (material, color) == ("metal", "golden"):  # a gilt woman on a black base: a trophy
        material, color = "metal", "brown"
    fill = 0.3 if material == "metal" else 1.0
    plinth_mat, plinth = d.choice(
        [
            m
            for m in (("wood", "black"), ("stone", "black"), ("wood", "brown"), ("stone", "gray"))
            if m[1] != color
        ]
    )
    look = (material, color)
    k = d.uniform(0.95, 1.15)
    yaw = d.uniform(0.4, 0.65)  # facing the viewer in front, to the right
    cos, sin = math.cos(yaw), math.sin(yaw)
    kw = dict(solid_fraction=fill, quat=axis_angle_quat((0, 0, 1), yaw))

    def at(x: float, y: float, z: float) -> tuple[float, float, float]:
        return (x * cos - y * sin, x * sin + y * cos, z)

    if bust:  # a bust on a round plinth and socle
        pr, ph = 0.023 * k, 0.012 * k
        d.upright("plinth", pr, ph, 0.0, plinth_mat, plinth)
        sr, sh = 0.012 * k, 0.009 * k
        d.upright("socle", sr, sh, ph, *look, solid_fraction=fill)
        base = ph + sh
        chest = (0, 0, base + 0.012 * k)
        d.ellipsoid("chest", (0.011 * k, 0.028 * k, 0.017 * k), chest, *look, **kw)
        for j, side in enumerate((-1, 1)):
            d.ellipsoid(
                f"shoulder_{j}",
                (0.0085 * k, 0.0095 * k, 0.0065 * k),
                at(-0.001 * k, side * 0.0185 * k, chest[2] + 0.0085 * k),
                *look,
                **kw,
            )
        top = chest[2] + 0.016 * k
        d.upright("neck", 0.0058 * k, 0.011 * k, top - 0.003 * k, *look, solid_fraction=fill)
        head = at(0.001 * k, 0, top + 0.017 * k)
        d.ellipsoid("head", (0.0115 * k, 0.0094 * k, 0.0132 * k), head, *look, **kw)
        hair = at(-0.0025 * k, 0, head[2] + 0.0035 * k)
        d.ellipsoid("hair", (0.0115 * k, 0.0098 * k, 0.0112 * k), hair, *look, **kw)
        d.ellipsoid(
            "nose",
            (0.003 * k, 0.0018 * k, 0.0038 * k),
            at(0.0118 * k, 0, head[2] - 0.001 * k),
            *look,
            **kw,
        )
        for j, side in enumerate((-1, 1)):
            d.ellipsoid(
                f"ear_{j}",
                (0.0025 * k, 0.0015 * k, 0.0038 * k),
                at(0, side * 0.0092 * k, head[2]),
                *look,
                **kw,
            )
        return Traits((color, plinth), material, "irregular")
    # a classical statue of a woman in a long draped gown, facing +x: a smooth skirt
    # falling in folds to a flared hem, a high waist, bare shoulders, the hair in a bun
    pw, ph = 0.036 * k, 0.011 * k
    if d.rng.random() < 0.5:
        d.slab("plinth", (pw / 2, pw / 2, ph / 2), 0.0, plinth_mat, plinth, yaw=yaw)
    else:
        d.upright("plinth", pw / 2, ph, 0.0, plinth_mat, plinth)
    hem_r = 0.0125 * k
    d.upright("gown_hem", hem_r, 0.008 * k, ph, *look, solid_fraction=fill)
    skirt_z = ph + 0.027 * k
    d.ellipsoid("gown", (0.0092 * k, 0.0108 * k, 0.027 * k), (0, 0, skirt_z), *look, **kw)
    waist = ph + 0.052 * k
    d.ellipsoid(
        "bodice", (0.0062 * k, 0.0082 * k, 0.011 * k), (0, 0, waist + 0.004 * k), *look, **kw
    )
    shoulder_z = waist + 0.014 * k
    d.ellipsoid("shoulders", (0.0055 * k, 0.0105 * k, 0.0042 * k), (0, 0, shoulder_z), *look, **kw)
    # folds of drapery down the front of the skirt, and a sash across the body
    for j, y in enumerate((-0.0055, -0.0018, 0.0018, 0.0055)):
        top = at(0.0058 * k, y * k * 0.7, waist - 0.002 * k)
        low = at(0.0112 * k, y * k * 1.5, ph + 0.007 * k)
        d.segment(f"fold_{j}", "capsule", top, low, 0.0014 * k, *look, visual_only=True)
    d.segment(
        "sash",
        "capsule",
        at(0.0035 * k, 0.008 * k, shoulder_z),
        at(0.0055 * k, -0.0065 * k, waist - 0.004 * k),
        0.0022 * k,
        *look,
        solid_fraction=fill,
    )
    pose = d.choice(["down", "chest"])
    for j, side in enumerate((-1, 1)):
        root = at(0, side * 0.0105 * k, shoulder_z - 0.001 * k)
        if pose == "chest" and j == 1:  # a hand held to the breast
            hand = at(0.0065 * k, side * 0.002 * k, shoulder_z - 0.011 * k)
        else:  # hanging at the side, against the gown
            hand = at(0.0018 * k, side * 0.0118 * k, waist - 0.014 * k)
        d.segment(f"arm_{j}", "capsule", root, hand, 0.0024 * k, *look, solid_fraction=fill)
    d.upright("neck", 0.0026 * k, 0.007 * k, shoulder_z, *look, solid_fraction=fill)
    head = at(0.0006 * k, 0, shoulder_z + 0.0115 * k)
    d.ellipsoid("head", (0.0055 * k, 0.0048 * k, 0.0064 * k), head, *look, **kw)
    bun = at(-0.0052 * k, 0, head[2] + 0.0025 * k)
    d.sphere("hair_bun", 0.0034 * k, bun, *look, solid_fraction=fill)
    return Traits((color, plinth), material, "irregular")


@generator(
    "phone_stand",
    size=(0.07, 0.13),
    synonyms=("phone stand", "phone holder", "phone dock"),
    revision=3,
)
def phone_stand_3(d: Design) -> Traits:
    """Revision 3: an empty folding desk phone stand, seen from the front: a flat base plate,
    a support arm rising from a rear hinge to a second hinge, the phone-sized back plate
    leaning back from it with two silicone pads, and at its foot, held up off the base, the
    hooked lip that holds a phone, split by a cable slot (a stand holding a phone read as a
    phone; the first, a low backrest on a base, read as a book stand or an easel)."""
    material = d.choice(["aluminium", "aluminium", "plastic"])
    color = d.choice(
        {"aluminium": ["silver", "gray", "black"], "plastic": ["white", "black", "pink"]}[material]
    )
    pad = "black" if color != "black" else "gray"
    t = {"aluminium": 0.004, "plastic": 0.005}[material]
    w = d.uniform(0.064, 0.072)
    base_t = t
    lx = d.uniform(0.085, 0.095)
    d.slab("base", (lx / 2, w / 2, base_t / 2), 0.0, material, color)
    lean = d.uniform(0.3, 0.4)  # the back plate from the vertical
    sin, cos = math.sin(lean), math.cos(lean)
    h1 = (-lx / 2 + 0.01, base_t + 0.004)
    h2 = (d.uniform(-0.004, 0.004), d.uniform(0.06, 0.068))
    arm_w = w * 0.55
    beam(d, "arm", h1, h2, arm_w / 2, t / 2, material, color)
    hinge = d.choice(["black", "gray"]) if color != "black" else "gray"
    d.rod("hinge_low", 0.004, arm_w + 0.004, (h1[0], 0, h1[1]), "metal", hinge, axis="y")
    d.rod("hinge_top", 0.0045, arm_w + 0.004, (h2[0], 0, h2[1]), "metal", hinge, axis="y")
    # the back plate: its back face on the top hinge, leaning back
    down, up = d.uniform(0.042, 0.048), d.uniform(0.038, 0.045)
    off = 0.0045 + t / 2  # from the hinge axis to the plate's mid plane, out along its normal
    n = (cos, sin)
    mid = (h2[0] + n[0] * off, h2[1] + n[1] * off)
    foot = (mid[0] + down * sin, mid[1] - down * cos)
    head = (mid[0] - up * sin, mid[1] + up * cos)
    beam(d, "back_plate", foot, head, w / 2, t / 2, material, color)
    for k, frac in enumerate((0.3, 0.75)):  # silicone pads across the plate's face
        p = tuple(a + frac * (b - a) for a, b in zip(foot, head, strict=True))
        q = (p[0] + n[0] * (t / 2 + 0.0005), p[1] + n[1] * (t / 2 + 0.0005))
        d.add(
            f"pad_{k}",
            "box",
            (0.0005, w / 2 - 0.012, 0.002),
            (q[0], 0, q[1]),
            "silicone",
            pad,
            quat=axis_angle_quat((0, 1, 0), -lean),
            visual_only=True,
        )
    # the lip: a ledge out from the plate's foot and an upturned edge, split by a cable slot
    ledge = d.uniform(0.013, 0.016)
    l0 = (foot[0] - sin * t / 2, foot[1] + cos * t / 2 - t / 2)
    l1 = (l0[0] + ledge * cos, l0[1] + ledge * sin)
    gap = 0.014
    half = (w / 2 - gap / 2) / 2
    for k, sign in enumerate((-1, 1)):
        y = sign * (gap / 2 + half)
        centre = ((l0[0] + l1[0]) / 2, y, (l0[1] + l1[1]) / 2)
        d.add(
            f"lip_{k}",
            "box",
            (ledge / 2, half, t / 2),
            centre,
            material,
            color,
            quat=axis_angle_quat((0, 1, 0), -lean),
        )
        tip = (l1[0] - sin * 0.0035 - t / 2 * cos, y, l1[1] + cos * 0.0035)
        d.add(
            f"lip_tip_{k}",
            "box",
            (t / 2, half, 0.0045),
            tip,
            material,
            color,
            quat=axis_angle_quat((0, 1, 0), -lean),
        )
        d.add(
            f"lip_pad_{k}",
            "box",
            (ledge / 2 - 0.002, half - 0.002, 0.0004),
            (centre[0] - sin * (t / 2 + 0.0004), y, centre[2] + cos * (t / 2 + 0.0004)),
            "silicone",
            pad,
            quat=axis_angle_quat((0, 1, 0), -lean),
            visual_only=True,
        )
    return Traits((color,), material, "irregular")


@generator("vase", size=(0.12, 0.27), synonyms=("vase", "flower vase"), container=True, revision=3)
def vase_3(d: Design) -> Traits:
    """Revision 3: a vase with a belly and a narrower neck under a flared lip, in glazed
    ceramic or glass, empty: a bud vase (a little round belly, a long slim neck), a
    baluster (a tall egg on a foot, a trumpet neck), an amphora (an egg tapering to a small
    foot, two handles from the neck to the shoulders) or an urn (a wide round belly on a
    pedestal, a short wide neck). The place for things is down the neck (the first, plain
    cylinders, cones and square columns, read as cups and tumblers)."""
    material = d.choice(["ceramic", "ceramic", "glass"])
    if material == "ceramic":
        color = d.choice(["white", "blue", "black", "green", "beige", "red", "pink"])
    else:
        color = d.choice(["transparent", "transparent", "blue", "green"])
    kind = d.choice(["bud", "baluster", "amphora", "urn"])
    t = 0.0035
    hollow = dict(solid_fraction=0.3)  # a thrown or blown body is a shell
    if kind == "bud":
        r = d.uniform(0.026, 0.033)
        hz = r * d.uniform(0.85, 1.0)
        foot = 0.007
        d.upright("foot", r * 0.55, foot, 0.0, material, color)
        zc = foot + hz * 0.92
        bore, height = d.uniform(0.007, 0.009), d.uniform(0.13, 0.16)
        lip_h, flare = d.uniform(0.011, 0.015), d.uniform(0.45, 0.6)
        shape = "sphere"
    elif kind == "baluster":
        r = d.uniform(0.036, 0.043)
        hz = r * d.uniform(1.25, 1.45)
        foot = 0.008
        d.upright("foot", r * 0.6, foot, 0.0, material, color)
        zc = foot + hz * 0.92
        bore, height = d.uniform(0.012, 0.015), (foot + 2 * hz) * d.uniform(1.35, 1.5)
        lip_h, flare = d.uniform(0.016, 0.022), d.uniform(0.55, 0.75)
        shape = "ellipsoid"
    elif kind == "amphora":
        r = d.uniform(0.036, 0.042)
        hz = r * d.uniform(1.3, 1.5)
        foot = 0.01
        d.upright("foot", r * 0.5, foot, 0.0, material, color)
        low = hz * 0.6  # the lower body tapering to the foot
        d.ellipsoid(
            "lower", (r * 0.62, r * 0.62, low), (0, 0, foot + low * 0.92), material, color, **hollow
        )
        zc = foot + hz * 1.12
        bore, height = d.uniform(0.012, 0.015), (foot + 2.2 * hz) * d.uniform(1.28, 1.4)
        lip_h, flare = d.uniform(0.012, 0.016), d.uniform(0.55, 0.75)
        shape = "ellipsoid"
    else:  # an urn on a pedestal
        r = d.uniform(0.042, 0.048)
        hz = r * d.uniform(0.85, 0.95)
        d.upright("foot", r * 0.62, 0.007, 0.0, material, color)
        d.upright("pedestal", r * 0.34, 0.018, 0.007, material, color)
        foot = 0.025
        zc = foot + hz * 0.93
        bore, height = r * d.uniform(0.48, 0.56), 0.0
        lip_h, flare = d.uniform(0.012, 0.016), d.uniform(0.7, 0.85)
        shape = "sphere"
    d.ellipsoid("belly", (r, r, hz), (0, 0, zc), material, color, **hollow)
    floor = zc + hz  # the top of the body, under the neck
    if kind in ("baluster", "amphora"):  # a shoulder narrowing into the neck
        sr = bore + t + 0.006
        d.ellipsoid(
            "shoulder", (sr, sr, hz * 0.3), (0, 0, zc + hz * 0.8), material, color, **hollow
        )
        floor = max(floor, zc + hz * 1.1)
    outer = bore + t
    sunk = zc + hz * math.sqrt(max(1 - (outer / r) ** 2, 0.0)) - 0.002  # into the body
    # the hollow neck up to the lip: to the vase's height, or short on an urn
    neck_top = floor + max(height - floor - lip_h, d.uniform(0.018, 0.026))
    d.wall("neck", bore, t, neck_top - sunk, sunk, material, color, segments=12)
    d.wall("lip", bore, t, lip_h, neck_top, material, color, segments=14, flare=flare)
    rim = neck_top + lip_h
    colors: tuple[str, ...] = (color,)
    if material == "ceramic":
        d.upright("mouth_shadow", bore, 0.001, floor - 0.0005, material, "black", visual_only=True)
        if d.rng.random() < 0.4:  # a glazed band round the belly
            band = d.choice([c for c in ("golden", "white", "blue", "black") if c != color])
            d.ellipsoid(
                "band", (r * 1.02, r * 1.02, hz * 0.5), (0, 0, zc), material, band, visual_only=True
            )
            colors = (color, band)
    if kind == "amphora":  # two handles from under the lip down to the shoulders
        for k, s in enumerate((-1, 1)):
            pts = [
                (0.0, s * (outer - 0.001), neck_top - 0.004),
                (0.0, s * (outer + 0.014), neck_top - 0.008),
                (0.0, s * (outer + 0.017), zc + hz * 0.95),
                (0.0, s * r * 0.7, zc + hz * 0.72),
            ]
            for j in range(3):
                d.segment(f"handle_{k}_{j}", "capsule", pts[j], pts[j + 1], 0.0032, material, color)
    d.interior((bore * 0.68, bore * 0.68), floor_z=floor, rim_z=rim)
    return Traits(colors, material, shape)
