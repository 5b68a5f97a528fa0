"""Hand tools for repairs."""

from __future__ import annotations

import math

from ..design import Design, Traits
from .registry import generator


@generator(
    "hex_key", size=(0.08, 0.16), synonyms=("hex key", "allen key", "allen wrench"), revision=3
)
def hex_key_3(d: Design) -> Traits:
    """Revision 3: mostly a set of L-shaped hex keys of falling sizes nested in a plastic
    clip, else one key with a rounded bend and a ball end (the single straight key read as a
    razor)."""
    color = d.choice(["black", "black", "silver", "golden"])
    if d.rng.random() < 0.65:
        clip = d.choice(["red", "black", "blue", "yellow", "green"])
        if clip == color:
            clip = "red"
        n = d.choice([4, 5, 6])
        big = d.uniform(0.0035, 0.0042)
        long0 = d.uniform(0.1, 0.125)
        y = 0.0
        x0, prev = -long0 / 2, big
        for k in range(n):
            a = big * (1 - 0.55 * k / (n - 1))
            length = long0 * (1 - 0.35 * k / (n - 1))
            short = max(0.022, a * 8)
            if k:
                y += a + prev + 0.0015
            prev = a
            _hex_l(d, f"key_{k}", a, length, short, (x0, y), color)
        hy = y / 2 + big + 0.003
        d.box(
            "clip",
            (0.009, hy, big + 0.0015),
            (x0 + 0.014, y / 2, big + 0.0015 - 0.0005),
            "plastic",
            clip,
        )
        d.box(
            "clip_label",
            (0.006, hy * 0.7, 0.0002),
            (x0 + 0.014, y / 2, 2 * big + 0.0012),
            "plastic",
            "white",
            visual_only=True,
        )
        return Traits((color, clip), "metal", "L-shape")
    a = d.uniform(0.0041, 0.005)
    long_arm, short_arm = d.uniform(0.09, 0.13), a * d.uniform(7, 9)
    _hex_l(d, "key", a, long_arm, short_arm, (-long_arm / 2, 0.0), color)
    d.sphere("ball_end", a * 0.98, (-long_arm / 2 - a * 0.4, 0, a), "metal", color)
    return Traits((color,), "metal", "L-shape")


def _hex_l(d: Design, name: str, a: float, length: float, short: float, start, color: str):
    """An L-shaped hex key lying flat: its long arm along +x from ``start`` (x, y), a rounded
    bend, and its short arm along +y."""
    x0, y0 = start
    bend = 2.2 * a
    d.hex_rod(f"{name}_long", a, length - bend, (x0 + (length - bend) / 2, y0, a), "metal", color)
    corner = (x0 + length - bend, y0 + bend)
    for j in range(3):  # the bend, a quarter turn in three steps
        t0, t1 = j * math.pi / 6, (j + 1) * math.pi / 6
        p0 = (corner[0] + bend * math.sin(t0), corner[1] - bend * math.cos(t0), a)
        p1 = (corner[0] + bend * math.sin(t1), corner[1] - bend * math.cos(t1), a)
        d.segment(f"{name}_bend_{j}", "cylinder", p0, p1, a * 1.05, "metal", color)
    d.hex_rod(
        f"{name}_short",
        a,
        short - bend,
        (corner[0] + bend, corner[1] + (short - bend) / 2, a),
        "metal",
        color,
        yaw=math.pi / 2,
    )


@generator("measuring_tape", size=(0.05, 0.1), synonyms=("measuring tape", "tape measure"))
def measuring_tape(d: Design) -> Traits:
    color = d.choice(["yellow", "yellow", "black", "red", "silver", "orange", "blue"])
    trim = d.choice(["black", "gray"]) if color != "black" else d.choice(["yellow", "gray"])
    h = d.uniform(0.05, 0.072)
    length, w, r = h * d.uniform(1.05, 1.2), d.uniform(0.028, 0.04), h / 2
    back = -length / 2
    d.rod("spool_case", r, w, (back + r, 0, r), "plastic", color, axis="y")
    d.box(
        "front_case",
        ((length - r) / 2, w / 2, r),
        ((back + r + length / 2) / 2, 0, r),
        "plastic",
        color,
    )
    for k, s in enumerate((-1, 1)):
        d.rod(
            f"grip_{k}",
            r * 0.75,
            0.001,
            (back + r, s * (w / 2 + 0.0005), r),
            "rubber",
            trim,
            axis="y",
            visual_only=True,
        )
    d.box("lock", (0.008, w * 0.22, 0.003), (length / 2 - 0.015, 0, h + 0.003), "plastic", trim)
    d.box("clip", (length * 0.3, 0.001, h * 0.3), (0, -w / 2 - 0.0015, h * 0.55), "metal", "silver")
    d.box("blade", (0.006, w * 0.32, 0.0006), (length / 2 + 0.006, 0, 0.004), "metal", "yellow")
    d.box("hook", (0.0007, w * 0.34, 0.0045), (length / 2 + 0.0127, 0, 0.0045), "metal", "silver")
    return Traits((color, trim), "plastic", "cube")


@generator(
    "pliers",
    size=(0.13, 0.22),
    synonyms=("pliers", "pair of pliers", "needle-nose pliers"),
    revision=3,
)
def pliers_3(d: Design) -> Traits:
    """Revision 3: ordinary combination pliers lying flat across the view, jaws closed: a
    chunky head tapering from a big round pivot with a polished rivet to a broad, flat,
    square nose whose two jaws meet on a dark serrated seam, the rounded pipe-grip opening
    between nose and pivot, and two long, straight handles in plain single-colour
    rubber sleeves (the first, thin arms, read as a clothespin; pointed jaws on wide V
    handles read as pruning shears; a toothed, ticked nose and two-tone banded sleeves read
    as wire strippers or a crimper)."""
    grip = d.choice(["red", "red", "blue", "yellow", "orange", "red"])
    steel = d.choice(["gray", "silver", "black", "gray"])
    polish = "silver" if steel == "black" else steel
    jaw_len, head_w = d.uniform(0.043, 0.048), d.uniform(0.0125, 0.0135)
    nose_w = head_w * d.uniform(0.68, 0.74)  # the flat nose's half width
    handle_len, spread = d.uniform(0.118, 0.13), d.uniform(0.016, 0.019)
    t = d.uniform(0.011, 0.013)
    z = t / 2
    r = d.uniform(0.0068, 0.0074)

    def p(x: float, y: float, h: float) -> tuple[float, float, float]:
        """The tool's frame (x from the handles to the nose) laid along +y, across the view."""
        return (-y, x, h)

    d.upright("pivot", head_w * 1.2, t, 0.0, "metal", steel)
    d.upright("rivet", head_w * 0.6, t + 0.0008, 0.0, "metal", polish)
    d.upright("rivet_pin", head_w * 0.22, t + 0.0012, 0.0, "metal", "gray")
    nose = jaw_len * 0.44
    x0 = jaw_len - nose
    for k, s in enumerate((-1, 1)):
        d.segment(
            f"cheek_{k}",
            "box",
            p(0.0, s * head_w * 0.5, z),
            p(x0 + 0.002, s * nose_w * 0.5, z),
            (head_w * 0.5, z),
            "metal",
            steel,
        )
        d.box(
            f"jaw_{k}",
            (nose_w / 2, nose / 2, z),
            p(jaw_len - nose / 2, s * nose_w / 2, z),
            "metal",
            polish,
        )
        # the handle: a steel arm from the pivot, then a plain straight sleeve
        knee = (-0.019, -s * 0.0075)
        end = (-handle_len, -s * spread)
        d.segment(
            f"arm_{k}",
            "box",
            p(-0.004, -s * 0.0045, z),
            p(*knee, z * 0.9),
            (0.005, z * 0.62),
            "metal",
            steel,
        )
        d.segment(f"sleeve_{k}", "capsule", p(*knee, r), p(*end, r), r, "rubber", grip)
    # the seam where the serrated jaws meet, with fine cross teeth, and the pipe grip
    d.box(
        "seam",
        (0.0005, nose / 2, 0.0003),
        p(x0 + nose / 2, 0, t),
        "metal",
        "black",
        visual_only=True,
    )
    for j in range(6):
        x = x0 + nose * (0.1 + 0.16 * j)
        d.box(
            f"serration_{j}",
            (nose_w * 0.3, 0.0003, 0.0002),
            p(x, 0, t),
            "metal",
            "gray" if polish == "silver" else "silver",
            visual_only=True,
        )
    d.add(
        "pipe_grip",
        "ellipsoid",
        (0.0036, 0.0062, 0.0006),
        p(x0 - 0.0055, 0, t + 0.0001),
        "metal",
        "black",
        visual_only=True,
    )
    return Traits((grip, steel), "metal", "elongated")


@generator("mini_hammer", size=(0.14, 0.26), synonyms=("hammer", "mini hammer", "small hammer"))
def mini_hammer(d: Design) -> Traits:
    steel = d.choice(["silver", "silver", "gray", "black"])
    handle_color = d.choice(["brown", "beige", "black", "red", "yellow", "orange", "blue"])
    handle_mat = "wood" if handle_color in ("brown", "beige") else "rubber"
    hh, hx = d.uniform(0.008, 0.011), d.uniform(0.008, 0.011)
    head, handle = d.uniform(0.055, 0.072), d.uniform(0.14, 0.2)
    body = head * 0.22
    d.box("head", (hx, body, hh), (0, 0, hh), "metal", steel)
    d.rod("face", hh, head * 0.5 - body, (0, (head * 0.5 + body) / 2, hh), "metal", steel, axis="y")
    if d.choice([True, False]):
        for k, s in enumerate((-1, 1)):
            z = hh + s * hh * 0.45
            d.segment(
                f"claw_{k}",
                "box",
                (0, -body + 0.002, z),
                (-0.016, -head * 0.5 + 0.004, z),
                (0.0045, hh * 0.3),
                "metal",
                steel,
            )
    else:
        ball = head / 2 - hh * 0.95
        d.rod(
            "peen_neck",
            hh * 0.6,
            ball - body,
            (0, -(ball + body) / 2, hh),
            "metal",
            steel,
            axis="y",
        )
        d.sphere("peen", hh * 0.95, (0, -ball, hh), "metal", steel)
    d.rod("shaft", hh * 0.6, handle * 0.6, (-hx - handle * 0.3, 0, hh), handle_mat, handle_color)
    d.rod(
        "grip",
        hh,
        handle * 0.45,
        (-hx - handle * 0.775, 0, hh),
        handle_mat,
        handle_color,
        capsule=True,
    )
    return Traits((steel, handle_color), "metal", "T-shape")


GLUE_GUN_COLORS = ["blue", "black", "gray", "green", "pink", "orange", "yellow"]


@generator("glue_gun", size=(0.15, 0.28), synonyms=("glue gun", "hot glue gun"), revision=2)
def glue_gun_2(d: Design) -> Traits:
    """Revision 2: a round barrel tapering to a long metal nozzle, the white glue stick
    fed in at the back, a rounded grip with its cord, the trigger in front of the grip in
    a colour of its own (the first, square, read as a power drill)."""
    color = d.choice(GLUE_GUN_COLORS)
    trigger = d.choice(["black", "gray", "yellow" if color != "yellow" else "black"])
    body, r = d.uniform(0.1, 0.13), d.uniform(0.018, 0.023)
    grip_h, rake = d.uniform(0.06, 0.075), d.uniform(0.25, 0.4)
    zc = grip_h + r
    d.rod("barrel", r, body, (0, 0, zc), "plastic", color, capsule=True, solid_fraction=0.4)
    d.rod("nose", r * 0.55, 0.022, (body / 2 + 0.006, 0, zc), "plastic", color)
    d.rod("nozzle", 0.0055, 0.016, (body / 2 + 0.025, 0, zc), "metal", "silver")
    d.segment(
        "tip",
        "cylinder",
        (body / 2 + 0.033, 0, zc),
        (body / 2 + 0.046, 0, zc - 0.005),
        0.002,
        "metal",
        "silver",
    )
    stick = d.uniform(0.04, 0.08)
    d.rod("glue_stick", 0.0056, stick, (-body / 2 - stick / 2 + 0.004, 0, zc), "plastic", "white")
    x_top = -body * 0.18
    x_butt = x_top - grip_h * math.tan(rake)
    d.segment(
        "grip", "capsule", (x_top, 0, zc - r * 0.5), (x_butt, 0, 0.012), 0.012, "plastic", color
    )
    d.box("butt", (0.016, 0.014, 0.006), (x_butt, 0, 0.006), "plastic", color)
    d.rod("cord", 0.003, 0.03, (x_butt - 0.028, 0, 0.004), "rubber", "black")
    d.segment(
        "trigger",
        "capsule",
        (x_top + 0.032, 0, zc - r * 0.6),
        (x_top + 0.024, 0, zc - r - 0.032),
        0.0065,
        "plastic",
        trigger,
    )
    _glue_gun_stand(d, body / 2 - 0.018, 2 * r * 0.8, zc - r * 0.9)
    return Traits((color,), "plastic", "L-shape")


def _glue_gun_stand(d: Design, x_stand: float, w: float, zb: float) -> None:
    """The folding wire stand under the nose, its foot across at the front."""
    for k, s in enumerate((-1, 1)):
        d.segment(
            f"stand_{k}",
            "cylinder",
            (x_stand, s * w * 0.35, zb),
            (x_stand + 0.018, s * w * 0.6, 0.002),
            0.002,
            "metal",
            "silver",
        )
    d.rod("stand_foot", 0.002, w * 1.3, (x_stand + 0.018, 0, 0.002), "metal", "silver", axis="y")
