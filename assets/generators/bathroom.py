"""Personal care and bath products."""

from __future__ import annotations

import math
from itertools import pairwise

from ..design import Design, Traits
from ..parts import X_TO_Z, axis_angle_quat, quat_mul
from ..textures import FRONT, Texture
from ..vocab import COLORS
from .desktop import BRIGHT
from .registry import generator

PASTEL = ["white", "white", "pink", "blue", "green", "beige", "purple", "yellow"]


def _flip_cap(d: Design, radius: float, z0: float, color: str) -> None:
    """A flip-top cap on a bottle neck."""
    h = d.uniform(0.016, 0.024)
    d.upright("cap", radius, h, z0, "plastic", color)
    d.upright(
        "cap_seam", radius + 0.0006, 0.0015, z0 + h * 0.65, "plastic", color, visual_only=True
    )
    d.box("cap_tab", (0.003, 0.005, 0.002), (radius, 0, z0 + h * 0.65), "plastic", color)


#: A quarter turn about z: a box's x along +y, its y along -x (a top face's image then reads
#: along +y with its top away from a viewer at +x).
QUARTER = axis_angle_quat((0, 0, 1), math.pi / 2)


def _top_print(d: Design, name: str, half: tuple[float, float], z: float, color: str, texture):
    """A printed label lying flat on z, ``half`` = (along y, along x): the words read along
    +y, their top towards -x."""
    d.add(
        name,
        "box",
        (half[0], half[1], 0.0004),
        (0.0, 0.0, z + 0.0004),
        "paper",
        color,
        quat=QUARTER,
        visual_only=True,
        texture=texture,
    )


@generator(
    "toothpaste",
    size=(0.13, 0.22),
    synonyms=("toothpaste", "toothpaste tube", "tube of toothpaste"),
    revision=3,
)
def toothpaste_3(d: Design) -> Traits:
    """Revision 3: a flat white squeeze tube lying along y (flat on top, round at the
    sides), crimped flat at one end and with a wide flip-top cap at the other, printed
    TOOTHPASTE in big letters with a coloured band (the first, a round ellipsoid with a
    small cap, read as a tube of paint)."""
    color = d.choice(["white", "white", "white", "blue", "red"])
    stripe = d.choice([c for c in ("red", "blue", "green", "red") if c != color])
    cap = d.choice(["white", "white", stripe])
    a = d.uniform(0.05, 0.07)  # half length of the tube's body
    w, hz = d.uniform(0.02, 0.025), d.uniform(0.01, 0.013)  # half width, half thickness
    core = w - hz
    d.box("tube", (core, a, hz), (0, 0, hz), "plastic", color, solid_fraction=0.9)
    for k, s in enumerate((-1, 1)):
        d.rod(f"tube_side_{k}", hz, 2 * a, (s * core, 0, hz), "plastic", color, axis="y")
    # the crimped end at -y: the tube flattens to a wide serrated seal
    reach, seal_w = d.uniform(0.014, 0.02), w * 1.08
    for k, z in enumerate((2 * hz - 0.001, 0.001)):
        d.segment(
            f"taper_{k}",
            "box",
            (0, -a, z),
            (0, -a - reach, hz),
            (w * 0.98, 0.001),
            "plastic",
            color,
        )
    d.box("seal", (seal_w, 0.005, 0.0012), (0, -a - reach - 0.004, hz), "plastic", color)
    for k in range(4):
        y = -a - reach - 0.0075 + k * 0.0022
        d.box(
            f"seal_rib_{k}",
            (seal_w, 0.0004, 0.0014),
            (0, y, hz),
            "plastic",
            stripe,
            visual_only=True,
        )
    # the shoulder, neck and a wide flip-top cap at +y
    d.rod("shoulder", hz * 0.95, 0.008, (0, a + 0.004, hz), "plastic", color)
    cap_len = d.uniform(0.014, 0.02)
    cap_y, cap_r = a + 0.008 + cap_len / 2, hz * 1.1
    d.box("cap_flip", (w * 0.5, cap_len / 2, cap_r), (0, cap_y, cap_r), "plastic", cap)
    for k, s in enumerate((-1, 1)):
        d.rod(
            f"cap_side_{k}", cap_r, cap_len, (s * w * 0.5, cap_y, cap_r), "plastic", cap, axis="y"
        )
    d.box(
        "cap_hinge_line",
        (w * 0.5, 0.0006, 0.0006),
        (0, a + 0.008 + cap_len * 0.35, 2 * cap_r + 0.0002),
        "plastic",
        stripe if cap != stripe else "white",
        visual_only=True,
    )
    # the print: a coloured band by the cap, the word across the flat top
    d.add(
        "band",
        "box",
        (core * 1.02, a * 0.14, hz * 1.02),
        (0, a * 0.82, hz),
        "plastic",
        stripe,
        visual_only=True,
    )
    for k, s in enumerate((-1, 1)):
        d.rod(
            f"band_side_{k}",
            hz * 1.02,
            a * 0.28,
            (s * core, a * 0.82, hz),
            "plastic",
            stripe,
            axis="y",
            visual_only=True,
        )
    word = Texture("print_toothpaste", (stripe if color == "white" else "white",))
    _top_print(d, "label", (a * 0.62, core * 0.98 + hz * 0.3), 2 * hz, color, word)
    return Traits((color, stripe), "plastic", "elongated")


def _panelled_wall(
    d: Design,
    name: str,
    radius: float,
    t: float,
    height: float,
    z0: float,
    color: str,
    panels: int,
    flare: float,
    turn: float,
) -> None:
    """``Design.wall`` in plastic, of ``panels`` flat panels ``{name}_{k}``, panel k facing
    the azimuth ``turn`` + 2 pi k / ``panels`` (so that one can face the front)."""
    slant = height / math.cos(flare)
    outer = radius + t + math.sin(flare) * slant  # widest ring: close it there
    chord = 2 * outer * math.tan(math.pi / panels) * 1.02
    r = radius + t / 2 + math.sin(flare) * slant / 2
    for k in range(panels):
        a = turn + 2 * math.pi * k / panels
        d.add(
            f"{name}_{k}",
            "box",
            (t / 2, chord / 2, slant / 2),
            (r * math.cos(a), r * math.sin(a), z0 + height / 2),
            "plastic",
            color,
            quat=quat_mul(axis_angle_quat((0, 0, 1), a), axis_angle_quat((0, 1, 0), flare)),
        )


def _facet_print(
    d: Design,
    name: str,
    angle: float,
    face: tuple[float, float, float],
    span: tuple[float, float],
    width: float,
    color: str,
    texture: Texture,
) -> None:
    """A print on one flat panel of a wall (``_panelled_wall``): the panel facing azimuth
    ``angle``, ``face`` = (the distance of its outer face from the axis at the wall's foot,
    the z of the foot, the flare), printed from z = ``span[0]`` to ``span[1]`` up its slant,
    ``width`` wide (no mass)."""
    apothem, z_foot, flare = face
    z0, z1 = span
    zc = (z0 + z1) / 2
    inset = 0.00035  # the box's centre under the face: its front a hair proud of it
    out = apothem + math.tan(flare) * (zc - z_foot) - inset * math.cos(flare)
    slant = (z1 - z0) / math.cos(flare)
    d.add(
        name,
        "box",
        (0.0004, width / 2, slant / 2),
        (out * math.cos(angle), out * math.sin(angle), zc + inset * math.sin(flare)),
        "plastic",
        color,
        quat=quat_mul(axis_angle_quat((0, 0, 1), angle), axis_angle_quat((0, 1, 0), flare)),
        visual_only=True,
        texture=texture,
    )


@generator(
    "mouthwash_cup",
    size=(0.08, 0.12),
    synonyms=("mouthwash cup", "rinse cup", "bathroom tumbler"),
    container=True,
    revision=3,
)
def mouthwash_cup_3(d: Design) -> Traits:
    """Revision 3: a sturdy plastic toothbrush tumbler: eight thick flat panels flaring a
    little from a recessed foot round a heavy floor, the front panel printed with a tooth
    and its sparkles, the panels either side with a standing toothbrush, and the same on
    the back (the first, a plain cup with a coloured band round the rim, read as a cup, a
    glass or a paper cup)."""
    color = d.choice(PASTEL)
    accent = d.choice(["blue", "blue", "green", "purple"])
    if color in ("white", "beige", "yellow"):  # printed in one colour
        tooth = shine = handle = accent
        bristle = "blue" if accent != "blue" else d.choice(["green", "pink"])
    else:  # a white tooth, white or yellow sparkles, a toothbrush that stands out
        tooth, shine = "white", "white" if color == "pink" else "yellow"
        handle, bristle = ("white", "blue") if color in ("pink", "green") else ("yellow", "white")
    segments = 8
    r, t = d.uniform(0.028, 0.032), 0.005
    h, flare = d.uniform(0.095, 0.11), d.uniform(0.04, 0.07)
    foot, base = 0.004, d.uniform(0.012, 0.016)
    d.upright("foot", r + t - 0.003, foot, 0.0, "plastic", color)
    d.upright("base", r + t * 0.5, base, foot, "plastic", color)  # the heavy floor
    turn = FRONT - 2 * math.pi / segments  # panel 1 faces the front
    _panelled_wall(d, "wall", r, t, h - foot, foot, color, segments, flare, turn)
    face = (r + t, foot, flare)  # the outer face of a panel at its foot
    # the prints run up the whole panel, their top edge tucked under the rim's
    span = (foot + 0.001, h - 0.0008)
    width = 2 * (r + t) * math.tan(math.pi / segments) * 0.92
    shine_print = Texture("tooth_shine", (tooth, shine))
    brush_print = Texture("toothbrush", (handle, bristle))
    for side, k0 in (("front", 1), ("back", 5)):
        prints = ((k0 - 1, "brush_l", brush_print), (k0, "tooth", shine_print))
        prints += ((k0 + 1, "brush_r", brush_print),)
        for k, what, texture in prints:
            angle = turn + 2 * math.pi * k / segments
            _facet_print(d, f"{what}_print_{side}", angle, face, span, width, color, texture)
    d.interior((r * 0.7, r * 0.7), floor_z=foot + base, rim_z=h)
    return Traits((color,), "plastic", "cylinder")


@generator("comb", size=(0.11, 0.2), synonyms=("comb", "hair comb"))
def comb(d: Design) -> Traits:
    color = d.choice(["black", "black", "brown", "pink", "blue", "purple", "white"])
    material = "wood" if color == "brown" else "plastic"
    length, width = d.uniform(0.12, 0.19), d.uniform(0.03, 0.042)
    t = d.uniform(0.0082, 0.0095)
    handle = d.choice([0.0, length * d.uniform(0.35, 0.45)])
    spine = width * d.uniform(0.25, 0.35)
    x0 = -length / 2
    d.box(
        "spine",
        ((length - handle) / 2, spine / 2, t / 2),
        (x0 + (length + handle) / 2, (width - spine) / 2, t / 2),
        material,
        color,
    )
    if handle:
        d.box(
            "handle",
            (handle / 2, width * 0.3, t / 2),
            (x0 + handle / 2, width * 0.15, t / 2),
            material,
            color,
        )
    tooth = width - spine
    x, k = x0 + handle + 0.002, 0
    while x < length / 2 - 0.002:
        pitch = 0.0055 if handle or x < 0 else 0.0032
        d.box(
            f"tooth_{k}",
            (pitch * 0.22, tooth / 2, 0.00175),
            (x + pitch * 0.22, -spine / 2, 0.00175),
            material,
            color,
        )
        x, k = x + pitch, k + 1
    return Traits((color,), material, "flat")


@generator("razor", size=(0.11, 0.16), synonyms=("razor", "shaving razor", "disposable razor"))
def razor(d: Design) -> Traits:
    color = d.choice(BRIGHT + ["white", "gray"])
    grip = d.choice(["black", "gray", "white", color])
    length, r = d.uniform(0.1, 0.13), d.uniform(0.0055, 0.007)
    d.rod("handle", r, length, (-length / 2, 0, r), "plastic", color, capsule=True)
    d.ellipsoid(
        "grip",
        (length * 0.25, r * 1.08, r * 1.08),
        (-length * 0.45, 0, r),
        "rubber",
        grip,
        visual_only=True,
    )
    head_w, head_t = d.uniform(0.018, 0.022), d.uniform(0.01, 0.013)
    d.box("neck", (0.008, r * 0.8, r * 0.8), (0.006, 0, r), "plastic", color)
    d.box("head", (0.007, head_w, head_t / 2), (0.018, 0, head_t / 2), "plastic", color)
    for k in range(d.choice([2, 3, 4, 5])):
        d.box(
            f"blade_{k}",
            (0.0006, head_w * 0.9, 0.0005),
            (0.014 + k * 0.0022, 0, head_t),
            "metal",
            "silver",
            visual_only=True,
        )
    strip = d.choice(["green", "blue", "white"])
    d.box(
        "lube_strip",
        (0.0015, head_w * 0.9, 0.0006),
        (0.023, 0, head_t),
        "plastic",
        strip,
        visual_only=True,
    )
    return Traits((color,), "plastic", "T-shape")


@generator(
    "nail_clipper",
    size=(0.05, 0.1),
    synonyms=("nail clipper", "nail clippers", "nail cutter"),
    revision=3,
)
def nail_clipper_3(d: Design) -> Traits:
    """Revision 3: lying along y, seen from the side: two springy jaws joined at a rounded
    rear with a key-ring hole, the upper one rising and bending down to a curved cutting
    beak at the front, a pin through them and a lever on the pin arching back and up to a
    wide thumb pad (the first, flat parallel slabs with square ends, read as a stapler)."""
    color = d.choice(["silver", "silver", "golden", "gray"])
    lever = d.choice([color, color, "black", "red", "blue", "pink"])
    length, w = d.uniform(0.058, 0.08), d.uniform(0.012, 0.015)
    yb, yf = -length / 2 + w / 2, length / 2 - w / 2
    t = 0.0012  # the thickness of a jaw
    d.box("lower_jaw", (w / 2, (yf - yb) / 2, t / 2), (0, 0, t / 2), "metal", color)
    d.upright("lower_jaw_end", w / 2, t, 0.0, "metal", color, xy=(0.0, yf))
    d.upright("rear_joint", w / 2, 0.0045, 0.0, "metal", color, xy=(0.0, yb))
    d.upright(
        "ring_hole", w * 0.2, 0.0003, 0.0045, "metal", "black", xy=(0.0, yb), visual_only=True
    )
    bend, tip = yf - 0.004, yf + w * 0.42
    d.segment(
        "upper_jaw",
        "box",
        (0, yb, 0.0045 - t / 2),
        (0, bend, 0.007),
        (w / 2, t / 2),
        "metal",
        color,
    )
    d.segment(
        "upper_beak", "box", (0, bend, 0.007), (0, tip, 0.0033), (w * 0.46, t / 2), "metal", color
    )
    d.segment(
        "lower_beak", "box", (0, bend, t / 2), (0, tip, 0.0025), (w * 0.46, t / 2), "metal", color
    )
    d.rod("edge", 0.0005, w * 0.9, (0, tip, 0.0029), "metal", "silver")
    pin = bend - 0.004
    top = 0.011
    d.upright("pin", 0.0016, top, 0.0, "metal", "silver", xy=(0, pin))
    d.rod("lever_cam", 0.0024, w * 0.75, (0, pin, top), "metal", lever)
    pad, lift = yb + 0.003, d.uniform(0.007, 0.009)
    d.segment(
        "lever",
        "box",
        (0, pin - 0.001, top + 0.0015),
        (0, pad, top + lift),
        (w * 0.32, 0.0008),
        "metal",
        lever,
    )
    d.ellipsoid("thumb_pad", (w * 0.55, w * 0.65, 0.0013), (0, pad, top + lift), "metal", lever)
    return Traits((color,) if lever == color else (color, lever), "metal", "elongated")


@generator(
    "hair_clip", size=(0.05, 0.1), synonyms=("hair clip", "claw clip", "hair claw"), revision=3
)
def hair_clip_3(d: Design) -> Traits:
    """Revision 3: a plastic claw clip standing on its teeth, its hinge across the view:
    each half curves out and down from the hinge, a smooth shell and then a comb of a few
    long, flat teeth curling in to interlock with the other half's at the bottom; above
    the hinge two squeeze tabs a side, the bright spring showing between them; printed
    tortoiseshell or one glossy colour (many thin round teeth seen along the hinge read as
    an engine block, slat teeth as a sled or a wine rack)."""
    color = d.choice(["brown", "brown", "brown", "black", "black", "pink", "purple", "beige"])
    kw: dict = {"texture": Texture("tortoise")} if color == "brown" else {}
    length, rz = d.uniform(0.064, 0.074), d.uniform(0.017, 0.019)
    rx, teeth = d.uniform(0.018, 0.02), d.choice([4, 5])
    zh = 2 * rz
    d.rod("hinge", 0.0032, length, (0, 0, zh), "plastic", color, axis="y")
    d.rod("spring", 0.0048, length * 0.26, (0, 0, zh), "metal", "silver", axis="y")
    pitch = length / teeth
    t = 0.0017  # half the thickness of a shell
    tab = length * 0.3  # a squeeze tab's length; the spring shows between the two

    def stroke(name: str, a, b, y: float, half_w: float, **extra) -> None:
        d.segment(
            name, "box", (a[0], y, a[1]), (b[0], y, b[1]), (half_w, t), "plastic", color, **extra
        )

    for k, s in enumerate((-1, 1)):

        def arc(deg: float, s: int = s) -> tuple[float, float]:
            a = math.radians(deg)
            return (s * rx * math.cos(a), rz + rz * math.sin(a))

        grip = [(s * 0.0025, zh), (s * 0.005, zh + 0.006), (s * 0.009, zh + 0.01)]
        for m, y in enumerate((-1, 1)):
            yc = y * (length / 2 - tab / 2)
            for j, (a, b) in enumerate(pairwise(grip)):
                stroke(f"grip_{k}_{m}_{j}", a, b, yc, tab / 2)
            d.rod(f"claw_lip_{k}_{m}", t, tab, (*grip[-1][:1], yc, grip[-1][1]), "plastic", color,
                  axis="y")  # fmt: skip
        shell = [(s * 0.0025, zh), arc(66), arc(38)]
        for j, (a, b) in enumerate(pairwise(shell)):
            stroke(f"shell_{k}_{j}", a, b, 0.0, length / 2, **kw)
        for j in range(teeth):
            y = -length / 2 + pitch * (j + 0.25 + 0.5 * k)
            tooth = [arc(38), arc(-6), arc(-55), arc(-105)]
            for i, (a, b) in enumerate(pairwise(tooth)):
                stroke(f"tooth_{k}_{j}_{i}", a, b, y, pitch * 0.22)
    return Traits((color,), "plastic", "irregular")


def _luma(color: str) -> float:
    """How light ``color`` looks (Rec. 709 luma of its base sRGB)."""
    r, g, b = COLORS[color]
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


@generator(
    "shampoo_bottle",
    size=(0.16, 0.26),
    synonyms=("shampoo bottle", "shampoo", "bottle of shampoo"),
    revision=3,
)
def shampoo_bottle_3(d: Design) -> Traits:
    """Revision 3: a tall flattened oval bottle, its broad face towards the reader with a
    big label printed SHAMPOO, under a wide oval flip-top cap (or, on some, a pump) (the
    first, its label blank and on the narrow side, read as just a bottle)."""
    color = d.choice(BRIGHT + ["white", "white", "silver"])
    cap = d.choice(["white", "black", "silver", color])
    if color in ("white", "silver"):  # a coloured label, the word in white
        label = d.choice(["blue", "green", "purple", "black", "red"])
        ink = "white"
    else:  # a white label, the word in the bottle's colour (or black on a light one)
        label = "white"
        ink = color if _luma(color) < 0.55 else d.choice(["black", "blue", "purple"])
    h, r = d.uniform(0.14, 0.18), d.uniform(0.012, 0.015)
    half_len = d.uniform(0.021, 0.027)  # the flat of the broad face, either side of the middle
    _stadium_y(d, "body", half_len, r, 0.0, h, color, solid_fraction=0.6)
    sh = d.uniform(0.012, 0.018)
    d.ellipsoid("shoulder", (r, half_len + r, sh), (0, 0, h), "plastic", color, solid_fraction=0.6)
    d.box(
        "front_label",
        (0.0004, half_len + r * 0.5, h * 0.15),
        (r + 0.0004, 0, h * 0.55),
        "paper",
        label,
        visual_only=True,
        texture=Texture("print_shampoo", (ink,)),
    )
    if d.rng.random() < 0.75:  # a wide oval flip-top cap on the shoulder
        cap_r = r * 0.8
        cap_half = max(0.6 * (half_len + r) - cap_r, 0.002)
        z0, cap_h = h + sh * 0.55, d.uniform(0.018, 0.024)
        _stadium_y(d, "cap", cap_half, cap_r, z0, cap_h, cap)
        seam = "gray" if cap != "gray" else "white"
        _stadium_y(
            d,
            "cap_seam",
            cap_half,
            cap_r + 0.0004,
            z0 + cap_h * 0.62,
            0.0008,
            seam,
            visual_only=True,
        )
        d.box(
            "cap_tab",
            (0.002, 0.006, 0.0025),
            (cap_r + 0.0015, 0, z0 + cap_h * 0.62),
            "plastic",
            cap,
        )
    else:  # a pump on a big bottle
        d.upright("collar_ring", 0.014, 0.006, h + sh * 0.7, "plastic", cap)
        _pump_y(d, h + sh * 0.7 + 0.006, cap, nozzle=d.uniform(0.018, 0.026))
    return Traits((color,) if cap == color else (color, cap), "plastic", "cuboid")


def _flat_tube(d: Design, name: str, t: float, w: float, z0: float, h: float, color, **kw):
    """An upright flattened tube section from z0 up ``h``: a box ``2 t`` deep (x) and two
    round sides of radius ``t`` at y = +-(w - t), ``2 w`` wide in all."""
    core = w - t
    d.box(name, (t, core, h / 2), (0, 0, z0 + h / 2), "plastic", color, **kw)
    for k, s in enumerate((-1, 1)):
        d.upright(f"{name}_side_{k}", t, h, z0, "plastic", color, xy=(0, s * core))


@generator(
    "facial_cleanser",
    size=(0.11, 0.2),
    synonyms=("facial cleanser", "face wash", "cleanser tube"),
    revision=3,
)
def facial_cleanser_3(d: Design) -> Traits:
    """Revision 3: a slim flattened squeeze tube standing on its wide flip-top cap, its
    flat front printed FACE WASH (or FACIAL CLEANSER) and crimped flat at the top (the
    first, a plain rounded tube, read as a lotion or a toothpaste tube)."""
    color = d.choice(["white", "white", "blue", "green", "pink", "orange", "purple"])
    cap = d.choice([c for c in ("white", "blue", "silver", "black", "pink") if c != color])
    ink = d.choice([c for c in ("blue", "green", "purple", "pink") if c != color])
    ink = ink if color == "white" else "white"
    t, w = d.uniform(0.01, 0.012), d.uniform(0.025, 0.029)
    cap_h = d.uniform(0.014, 0.018)
    _flat_tube(d, "cap", t * 1.15, w * 0.75, 0.0, cap_h, cap)
    d.box(
        "cap_seam",
        (t * 1.15 + 0.0004, w * 0.75 - t * 1.15, 0.0006),
        (0, 0, cap_h * 0.7),
        "plastic",
        "gray" if cap != "gray" else "white",
        visual_only=True,
    )
    body = d.uniform(0.075, 0.1)
    _flat_tube(d, "tube", t, w, cap_h, body, color)
    d.box(
        "label",
        (0.0003, w - t * 0.7, body * 0.3),
        (t + 0.0003, 0, cap_h + body * 0.5),
        "plastic",
        color,
        visual_only=True,
        texture=Texture("print_face_wash", (ink,)),
    )
    top, reach = cap_h + body, d.uniform(0.028, 0.036)
    steps = 4  # the tube flattens towards the crimp
    for k in range(steps):
        depth = t * (1 - (k + 1) / (steps + 0.6))
        z0 = top + reach * k / steps
        _flat_tube(d, f"flat_{k}", depth, w * (1 + 0.012 * (k + 1)), z0, reach / steps, color)
    d.box("crimp", (0.0013, w * 1.04, 0.0055), (0, 0, top + reach + 0.0045), "plastic", color)
    for k in range(3):
        d.box(
            f"crimp_rib_{k}",
            (0.0016, w * 1.04, 0.0004),
            (0, 0, top + reach + 0.002 + k * 0.0022),
            "plastic",
            cap,
            visual_only=True,
        )
    return Traits((color, cap), "plastic", "cylinder")


def _wrap_label(d: Design, name: str, radius, height, z0, color, texture, xy=(0.0, 0.0)):
    """A printed sleeve round an upright cylinder (no mass): its words face +x and half a
    turn from there (unturned about z: a part's bounds are its turned box, so a turn would
    widen the object's)."""
    quat = X_TO_Z
    center = (xy[0], xy[1], z0 + height / 2)
    d.add(
        name,
        "cylinder",
        (radius, height / 2),
        center,
        "paper",
        color,
        quat=quat,
        visual_only=True,
        texture=texture,
    )


def _stadium_y(d: Design, name: str, half_len: float, r: float, z0: float, h: float, color, **kw):
    """An upright prism of rounded-rectangle section long along y (its flat faces towards
    +-x, where a reader looks): a box and two end cylinders ``{name}_end_{k}``."""
    d.box(name, (r, half_len, h / 2), (0, 0, z0 + h / 2), "plastic", color, **kw)
    for k, s in enumerate((-1, 1)):
        d.upright(f"{name}_end_{k}", r, h, z0, "plastic", color, xy=(0, s * half_len), **kw)


def _pump_y(d: Design, z0: float, color: str, nozzle: float) -> None:
    """A pump dispenser (collar, stem, head) on z0, its nozzle towards +y (seen side on)."""
    collar = d.uniform(0.012, 0.015)
    d.upright("collar", collar, 0.012, z0, "plastic", color)
    stem = d.uniform(0.01, 0.018)
    d.upright("stem", 0.0045, stem, z0 + 0.012, "plastic", color)
    top = z0 + 0.012 + stem
    d.upright("pump_head", collar * 0.9, 0.013, top, "plastic", color)
    d.segment(
        "pump_nozzle",
        "box",
        (0, 0, top + 0.008),
        (0, collar + nozzle, top + 0.006),
        (0.004, 0.0035),
        "plastic",
        color,
    )


@generator(
    "hand_sanitizer",
    size=(0.1, 0.2),
    synonyms=("hand sanitizer", "sanitizer", "hand gel"),
    revision=3,
)
def hand_sanitizer_3(d: Design) -> Traits:
    """Revision 3: a flat clear bottle of tinted gel (bubbles in it), its broad face
    towards the reader with a label printed HAND SANITIZER, under a pump or a flip cap
    (the first, with a wordless sticker on its narrow side, read as a soap dispenser)."""
    cap = d.choice(["white", "blue", "green", "black", "purple"])
    gel = d.choice(["transparent", "blue", "green", "transparent"])
    label = d.choice([c for c in ("white", "white", "blue", "green") if c != gel])
    ink = d.choice(["blue", "green", "red"]) if label == "white" else "white"
    h, r = d.uniform(0.085, 0.12), d.uniform(0.014, 0.018)
    half_len, fill = d.uniform(0.018, 0.026), h * d.uniform(0.7, 0.88)
    _stadium_y(d, "gel", half_len, r, 0.0, fill, gel, solid_fraction=0.95)
    _stadium_y(d, "body", half_len, r, fill, h - fill, "transparent", solid_fraction=0.1)
    for k in range(5):  # air bubbles held in the gel
        y, z = d.uniform(-half_len, half_len), d.uniform(0.15, 0.9) * fill
        d.sphere(
            f"bubble_{k}",
            d.uniform(0.0012, 0.0025),
            (r - 0.002, y, z),
            "plastic",
            "white",
            visual_only=True,
        )
    d.box(
        "label",
        (0.0004, half_len + r * 0.45, h * 0.26),
        (r + 0.0004, 0, h * 0.42),
        "paper",
        label,
        visual_only=True,
        texture=Texture("print_sanitizer", (ink,)),
    )
    d.ellipsoid(
        "shoulder", (r, half_len + r, 0.01), (0, 0, h), "plastic", "transparent", solid_fraction=0.3
    )
    if d.choice([True, False]):
        _pump_y(d, h + 0.006, cap, nozzle=d.uniform(0.012, 0.018))
    else:
        d.upright("neck", 0.01, 0.006, h + 0.006, "plastic", "transparent")
        _flip_cap(d, d.uniform(0.012, 0.015), h + 0.012, cap)
    return Traits(("transparent", cap if gel == "transparent" else gel), "plastic", "cuboid")


@generator(
    "lotion", size=(0.15, 0.25), synonyms=("lotion", "lotion bottle", "body lotion"), revision=3
)
def lotion_3(d: Design) -> Traits:
    """Revision 3: a tall creamy bottle with a long pump, printed BODY LOTION (or HAND
    LOTION) front and back (the first, with a plain band, read as a soap
    dispenser; lotion and shampoo bottles were read as each other)."""
    color = d.choice(["white", "white", "beige", "pink", "purple", "blue", "green"])
    pump = d.choice(["white", "black", "silver", "golden"])
    ink = d.choice([c for c in ("blue", "purple", "green") if c != color])
    ink = ink if color in ("white", "beige", "pink") else "white"
    r, h = d.uniform(0.026, 0.032), d.uniform(0.12, 0.16)
    d.upright("body", r, h, 0.0, "plastic", color, solid_fraction=0.85)
    word = Texture(d.choice(["wrap_lotion", "wrap_lotion", "wrap_lotion_hand"]), (ink,))
    _wrap_label(d, "label", r + 0.0008, h * 0.5, h * 0.2, color, word)
    d.ellipsoid("shoulder", (r, r, 0.014), (0, 0, h), "plastic", color, solid_fraction=0.85)
    d.upright("collar_ring", 0.014, 0.006, h + 0.01, "plastic", pump)
    _pump_y(d, h + 0.016, pump, nozzle=d.uniform(0.02, 0.028))
    return Traits((color, pump), "plastic", "cylinder")


@generator(
    "dental_floss",
    size=(0.035, 0.06),
    synonyms=("dental floss", "floss", "floss dispenser"),
    revision=3,
)
def dental_floss_3(d: Design) -> Traits:
    """Revision 3: a small flat rounded case with a snap lid printed FLOSS over a tooth,
    and the thread coming out over the metal cutter on its front, hanging down (the
    first, a round plain case, read as a pot or a tin, earlier as a tape measure)."""
    color = d.choice(["white", "white", "white", "blue", "green", "pink"])
    lid = d.choice([color, color, "white", "blue", "green"])
    ink = d.choice(["blue", "green"]) if lid == "white" else "white"
    r, half_len = d.uniform(0.014, 0.017), d.uniform(0.008, 0.012)
    h = d.uniform(0.016, 0.02)
    base_h = h * 0.6
    _stadium_y(d, "case", half_len, r, 0.0, base_h, color, solid_fraction=0.7)
    _stadium_y(d, "lid", half_len, r, base_h, h - base_h, lid, solid_fraction=0.7)
    d.box(
        "lid_seam",
        (r + 0.0003, half_len, 0.0004),
        (0, 0, base_h),
        "plastic",
        "gray",
        visual_only=True,
    )
    word = Texture("print_floss", (ink,), "tooth")
    _top_print(d, "lid_print", (half_len + r * 0.5, r * 0.78), h, lid, word)
    # the cutter on the lid's front edge, and the thread over it, hanging down the front
    d.box("cutter", (0.0006, 0.006, 0.0025), (r + 0.0006, 0, h - 0.0025), "metal", "silver")
    d.rod(
        "thread_out",
        0.0005,
        0.008,
        (r + 0.0013, 0, h - 0.0012),
        "fabric",
        "white",
        axis="y",
        visual_only=True,
    )
    d.segment(
        "thread",
        "cylinder",
        (r + 0.0014, 0.003, h - 0.0012),
        (r + 0.0016, 0.005, base_h * 0.6),
        0.0005,
        "fabric",
        "white",
        visual_only=True,
    )
    return Traits((color,) if lid == color else (color, lid), "plastic", "cuboid")


@generator(
    "soap_dish",
    size=(0.09, 0.15),
    synonyms=("soap dish", "soap holder", "soap tray"),
    container=True,
    revision=3,
)
def soap_dish_3(d: Design) -> Traits:
    """Revision 3: a shallow tray on little feet, its low wall with a lip, and raised
    drain ridges across its floor with the drain slots between them (the first, a deeper
    plain tray or a flared round dish, read as a wooden bowl or a basket)."""
    material = d.choice(["ceramic", "ceramic", "plastic", "wood"])
    color = "brown" if material == "wood" else d.choice(PASTEL)
    lx, ly = d.uniform(0.052, 0.064), d.uniform(0.035, 0.042)  # outer half extents
    t, corner, foot = 0.004, 0.005, 0.003
    floor, rim = foot + 0.004, foot + d.uniform(0.015, 0.019)
    for k, (sx, sy) in enumerate(((-1, -1), (-1, 1), (1, -1), (1, 1))):
        xy = (sx * (lx - corner), sy * (ly - corner))
        d.upright(f"foot_{k}", 0.005, foot, 0.0, material, color, xy=(xy[0] * 0.8, xy[1] * 0.8))
        d.upright(f"corner_{k}", corner, rim - foot, foot, material, color, xy=xy)
    d.box(
        "floor", (lx - corner, ly, (floor - foot) / 2), (0, 0, (floor + foot) / 2), material, color
    )
    d.box(
        "floor_ends",
        (lx, ly - corner, (floor - foot) / 2),
        (0, 0, (floor + foot) / 2),
        material,
        color,
    )
    for k, s in enumerate((-1, 1)):
        d.box(
            f"wall_x{k}",
            (t / 2, ly - corner, (rim - floor) / 2),
            (s * (lx - t / 2), 0, (rim + floor) / 2),
            material,
            color,
        )
        d.box(
            f"wall_y{k}",
            (lx - corner, t / 2, (rim - floor) / 2),
            (0, s * (ly - t / 2), (rim + floor) / 2),
            material,
            color,
        )
        d.box(
            f"lip_x{k}",
            (0.003, ly + 0.004, 0.0015),
            (s * (lx + 0.001), 0, rim - 0.0015),
            material,
            color,
            visual_only=True,
        )
        d.box(
            f"lip_y{k}",
            (lx + 0.004, 0.003, 0.0015),
            (0, s * (ly + 0.001), rim - 0.0015),
            material,
            color,
            visual_only=True,
        )
    rib_h, inner_x, inner_y = 0.0035, lx - t, ly - t
    ribs = 7
    drain = "gray" if color != "gray" else "black"
    for k in range(ribs):
        x = inner_x * 0.85 * (2 * k + 1 - ribs) / ribs
        d.box(
            f"ridge_{k}",
            (0.0018, inner_y * 0.85, rib_h / 2),
            (x, 0, floor + rib_h / 2),
            material,
            color,
        )
        if k:
            d.box(
                f"drain_{k}",
                (0.0012, inner_y * 0.6, 0.0003),
                (x - inner_x * 0.85 / ribs, 0, floor + 0.0003),
                material,
                drain,
                visual_only=True,
            )
    d.interior((inner_x * 0.85, inner_y * 0.8), floor_z=floor + rib_h, rim_z=rim)
    return Traits((color,), material, "cuboid")
