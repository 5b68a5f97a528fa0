"""Kitchen cutting tools, tableware, ware and utensils."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import axis_angle_quat
from ..textures import Texture
from .kitchen import CERAMIC_COLORS
from .registry import generator, revised

GRIPS = ["black", "red", "green", "blue", "yellow", "orange", "white", "brown"]


def _grip(d: Design, length: float, half_w: float, thick: float, x1: float) -> tuple[str, str]:
    """A flat handle along x ending at ``x1``, resting on z = 0; returns (material, colour)."""
    color = d.choice(GRIPS)
    material = "wood" if color == "brown" else "plastic"
    d.box(
        "handle", (length / 2, half_w, thick / 2), (x1 - length / 2, 0, thick / 2), material, color
    )
    return material, color


@generator("fruit_knife", size=(0.15, 0.25), synonyms=("fruit knife", "paring knife"))
def fruit_knife(d: Design) -> Traits:
    handle, blade = d.uniform(0.08, 0.1), d.uniform(0.07, 0.11)
    thick, w = d.uniform(0.012, 0.016), d.uniform(0.016, 0.022)
    x0 = -(handle + blade) / 2
    material, color = _grip(d, handle, d.uniform(0.008, 0.01), thick, x0 + handle)
    for k in range(2 if material == "wood" else 0):
        d.upright(
            f"rivet_{k}",
            0.0022,
            0.0006,
            thick,
            "metal",
            "silver",
            xy=(x0 + handle * (0.3 + 0.4 * k), 0),
            visual_only=True,
        )
    xb = x0 + handle
    d.box(
        "bolster", (0.004, 0.0075, thick * 0.35), (xb + 0.004, 0, thick * 0.35), "metal", "silver"
    )
    body = blade - w
    d.box("blade", (body / 2, w / 2, 0.0008), (xb + body / 2, 0, 0.0008), "metal", "silver")
    d.ellipsoid("tip", (w * 1.1, w / 2, 0.0008), (xb + body, 0, 0.0008), "metal", "silver")
    return Traits((color, "silver"), material, "elongated")


@generator("peeler", size=(0.13, 0.21), synonyms=("peeler", "vegetable peeler", "potato peeler"))
def peeler(d: Design) -> Traits:
    handle, thick = d.uniform(0.09, 0.12), d.uniform(0.012, 0.016)
    material, color = _grip(d, handle, d.uniform(0.009, 0.012), thick, 0.0)
    d.upright(
        "hang_hole",
        0.004,
        0.0006,
        thick,
        "plastic",
        "black",
        xy=(-handle + 0.012, 0),
        visual_only=True,
    )
    if d.rng.random() < 0.5:  # a Y peeler: two arms and a blade across their tips
        reach, half = d.uniform(0.035, 0.045), d.uniform(0.025, 0.032)
        for k, sign in enumerate((-1, 1)):
            d.segment(
                f"arm_{k}",
                "box",
                (0, 0, thick / 2),
                (reach, sign * half, thick / 2),
                (0.0035, thick / 2),
                material,
                color,
            )
        d.box("blade", (0.006, half, 0.0012), (reach, 0, 0.0012), "metal", "silver")
        return Traits((color, "silver"), material, "T-shape")
    frame, half = d.uniform(0.05, 0.065), d.uniform(0.009, 0.012)
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"rail_{k}",
            (frame / 2, 0.0025, thick / 3),
            (frame / 2, sign * half, thick / 3),
            "metal",
            "silver",
        )
    d.box("end_cap", (0.003, half + 0.0025, thick / 3), (frame, 0, thick / 3), "metal", "silver")
    d.box(
        "blade", (frame / 2 - 0.004, half - 0.0045, 0.001), (frame / 2, 0, 0.001), "metal", "silver"
    )
    return Traits((color, "silver"), material, "elongated")


@revised("peeler", 3)
def peeler_3(d: Design) -> Traits:
    """Revision 3: lying flat, a Y peeler (a broad handle, a yoke spreading wider than it and
    a slotted blade across the yoke's tips) or a swivel peeler (a slotted blade between two
    rails, a pointed eye-remover at the tip); the first, arms and blade at odd heights,
    was not named at all."""
    color = d.choice(GRIPS)
    material = "wood" if color == "brown" else "plastic"
    thick = d.uniform(0.009, 0.012)
    z = thick / 2
    if d.rng.random() < 0.6:  # a Y peeler, the yoke at +x
        handle, hw = d.uniform(0.085, 0.105), d.uniform(0.011, 0.014)
        _pill(d, "handle", handle, 2 * hw, thick, material, color, x=-handle / 2)
        d.upright(
            "hang_hole",
            0.0045,
            0.0006,
            thick,
            "plastic",
            "black",
            xy=(-handle + 0.013, 0),
            visual_only=True,
        )
        reach, half = d.uniform(0.04, 0.048), d.uniform(0.03, 0.036)
        yoke = "silver" if d.rng.random() < 0.4 else color
        yoke_mat = "metal" if yoke == "silver" else material
        for k, sign in enumerate((-1, 1)):
            knee = (reach * 0.45, sign * half * 0.85, z)
            d.segment(
                f"yoke_{k}",
                "box",
                (-0.004, sign * hw * 0.4, z),
                knee,
                (0.0035, z * 0.8),
                yoke_mat,
                yoke,
            )
            d.segment(
                f"yoke_tip_{k}",
                "box",
                knee,
                (reach, sign * half, z),
                (0.0035, z * 0.8),
                yoke_mat,
                yoke,
            )
            d.upright(
                f"rivet_{k}", 0.0032, thick * 0.9, 0.0, "metal", "silver", xy=(reach, sign * half)
            )
        d.box("blade", (0.0055, half - 0.002, 0.0009), (reach, 0, z), "metal", "silver")
        d.box(
            "slot",
            (0.0009, half * 0.8, 0.0002),
            (reach, 0, z + 0.001),
            "metal",
            "black",
            visual_only=True,
        )
        for k, sign in enumerate((-1, 1)):
            d.box(
                f"edge_{k}",
                (0.0004, half * 0.85, 0.0002),
                (reach + sign * 0.004, 0, z + 0.0009),
                "metal",
                "gray",
                visual_only=True,
            )
        return Traits((color, "silver"), material, "T-shape")
    handle, hw = d.uniform(0.09, 0.11), d.uniform(0.01, 0.012)
    _pill(d, "handle", handle, 2 * hw, thick, material, color, x=-handle / 2)
    d.upright(
        "hang_hole",
        0.004,
        0.0006,
        thick,
        "plastic",
        "black",
        xy=(-handle + 0.012, 0),
        visual_only=True,
    )
    frame, half = d.uniform(0.055, 0.065), d.uniform(0.009, 0.011)
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"rail_{k}",
            (frame / 2, 0.002, z * 0.7),
            (frame / 2, sign * half, z * 0.7),
            "metal",
            "silver",
        )
    d.segment(
        "eye_tip",
        "box",
        (frame, 0, z * 0.7),
        (frame + 0.014, 0, z * 0.7),
        (half + 0.002, z * 0.7),
        "metal",
        "silver",
    )
    d.ellipsoid(
        "tip", (0.008, half + 0.002, z * 0.7), (frame + 0.014, 0, z * 0.7), "metal", "silver"
    )
    d.box(
        "blade",
        (frame / 2 - 0.005, half - 0.002, 0.0009),
        (frame / 2, 0, z * 0.7),
        "metal",
        "silver",
    )
    d.box(
        "slot",
        (frame / 2 - 0.009, 0.0009, 0.0002),
        (frame / 2, 0, z * 0.7 + 0.001),
        "metal",
        "black",
        visual_only=True,
    )
    return Traits((color, "silver"), material, "elongated")


def _pill(d: Design, name: str, length, width, height, material, color, x=0.0) -> None:
    """A flat handle of rounded ends along x, centred at x, resting on z = 0."""
    core = max(length - width, 1e-4) / 2
    d.stadium(
        name,
        core,
        width / 2,
        0.0,
        height,
        material,
        color,
        xy=(x, 0.0),
        solid_fraction=1.0,
        end_fill=0.5,
    )


@generator("garlic_press", size=(0.15, 0.23), synonyms=("garlic press", "garlic crusher"))
def garlic_press(d: Design) -> Traits:
    metal = d.choice(["silver", "silver", "gray"])
    grip = d.choice(["black", "red", "green", metal])
    rc, cup_h = d.uniform(0.015, 0.019), d.uniform(0.02, 0.026)
    d.upright("cup_floor", rc + 0.003, 0.003, 0.0, "aluminium", metal)
    d.wall("cup", rc, 0.003, cup_h - 0.003, 0.003, "aluminium", metal, segments=14)
    for k in range(7):
        a, rr = k * math.pi / 3, 0.0 if k == 6 else rc * 0.55
        d.upright(
            f"hole_{k}",
            0.0022,
            0.0004,
            0.003,
            "aluminium",
            "black",
            xy=(rr * math.cos(a), rr * math.sin(a)),
            visual_only=True,
        )
    thick = d.uniform(0.01, 0.013)
    xh, length = rc + 0.018, d.uniform(0.16, 0.2)
    z = thick / 2
    for k, sign in enumerate((-1, 1)):
        side = (0.0, sign * (rc + 0.009), z)
        end = (xh - length, sign * d.uniform(0.02, 0.03), z)
        d.segment(f"fork_{k}", "box", (xh, sign * 0.004, z), side, (0.006, z), "aluminium", metal)
        d.segment(f"arm_{k}", "box", side, end, (0.006, z - 0.0015), "aluminium", metal)
        grip_start = tuple(a + 0.4 * (b - a) for a, b in zip(side, end, strict=True))
        d.segment(f"grip_{k}", "capsule", grip_start, end, z, "rubber", grip)
    d.upright("hinge", 0.006, thick + 0.004, 0.0, "aluminium", metal, xy=(xh, 0))
    colors = (metal,) if grip == metal else (metal, grip)
    return Traits(colors, "aluminium", "irregular")


@generator(
    "wire_cutters", size=(0.11, 0.2), synonyms=("wire cutters", "side cutters", "wire snips")
)
def wire_cutters(d: Design) -> Traits:
    grip = d.choice(["red", "red", "yellow", "blue", "black", "orange"])
    length, spread = d.uniform(0.12, 0.16), d.uniform(0.035, 0.055)
    jaw, thick = d.uniform(0.025, 0.032), d.uniform(0.011, 0.014)
    z = thick / 2
    pivot = length / 2 - jaw
    for k, sign in enumerate((-1, 1)):
        end = (-length / 2, sign * spread / 2, z)
        d.segment(
            f"arm_{k}", "box", (pivot, 0, z), end, (0.0045, thick / 2 - 0.002), "metal", "silver"
        )
        start = (pivot - 0.02, sign * 0.006, z)
        d.segment(f"grip_{k}", "capsule", start, end, thick / 2, "rubber", grip)
        d.segment(
            f"jaw_{k}",
            "box",
            (pivot, sign * 0.006, z),
            (length / 2, 0, z),
            (0.005, thick / 2 - 0.002),
            "metal",
            "silver",
        )
    d.upright("pivot", 0.0065, thick, 0.0, "metal", "silver", xy=(pivot, 0))
    return Traits((grip, "silver"), "metal", "irregular")


@revised("wire_cutters", 3)
def wire_cutters_3(d: Design) -> Traits:
    """Revision 3: diagonal side cutters lying across the view, jaws shut: a short, black,
    pointed head (two almond jaws meeting at the tip) with a bright ground bevel running
    down each jaw to the straight cutting edge between them, so that the bevels close in a
    V at the point; a round boss with a bright rivet; two plain dipped grips, a little
    open (the first, long straight jaws, read as pliers or a
    can opener; jaws opened like a beak with a spring and two-tone grips as pliers or wire
    strippers; a wire held in the jaws as wire strippers)."""
    grip = d.choice(["red", "red", "yellow", "red", "orange", "blue"])
    metal, shine = "black", "white"  # a dark oxide head, so that the ground bevels shine
    jaw_len, half_w = d.uniform(0.032, 0.035), d.uniform(0.0135, 0.0145)
    handle_len, closed = d.uniform(0.095, 0.1), d.uniform(0.008, 0.01)
    open_a = math.radians(d.uniform(6.0, 8.0))  # each handle turned a little open
    thick = d.uniform(0.011, 0.012)
    z = thick / 2
    r = d.uniform(0.0064, 0.0068)  # the dipped grips' radius

    def p(u: float, v: float, h: float) -> tuple[float, float, float]:
        """The tool's frame (u from the handles to the tip) laid along +y, across the view."""
        return (-v, u, h)

    def turn(u: float, v: float, s: int, h: float) -> tuple[float, float, float]:
        """A point of the half on side ``s``, turned open about the rivet."""
        c, sn = math.cos(s * open_a), math.sin(s * open_a)
        return p(u * c - v * sn, u * sn + v * c, h)

    d.upright("boss", half_w * 0.9, thick, 0.0, "metal", metal)
    d.upright("rivet", 0.0045, thick + 0.001, 0.0, "metal", shine)
    # the jaws: two almonds from beside the rivet to the shared point
    jaws = [((-0.004, s * half_w * 0.55), (jaw_len, 0.0)) for s in (-1, 1)]
    semi = half_w * 0.55  # the almonds' half width
    for k, (a0, a1) in enumerate(jaws):
        d.segment(f"jaw_{k}", "ellipsoid", p(*a0, z), p(*a1, z), (semi, z), "metal", metal)

    def top(u: float, v: float) -> float:
        """The height of the jaws' top at (u, v)."""
        high = 0.0
        for a0, a1 in jaws:
            half = math.dist(a0, a1) / 2
            du, dv = ((b - a) / (2 * half) for a, b in zip(a0, a1, strict=True))
            x = (u - (a0[0] + a1[0]) / 2) * du + (v - (a0[1] + a1[1]) / 2) * dv
            y = -(u - (a0[0] + a1[0]) / 2) * dv + (v - (a0[1] + a1[1]) / 2) * du
            high = max(high, z + z * math.sqrt(max(1 - (x / half) ** 2 - (y / semi) ** 2, 0.0)))
        return high

    for k, s in enumerate((-1, 1)):
        # the ground bevel down this jaw to the cutting edge, following the jaw's top
        edge = [
            (0.005 + (jaw_len * 0.9 - 0.005) * f, s * (0.0036 - 0.003 * f))
            for f in (0, 0.33, 0.66, 1)
        ]
        for j, (b0, b1) in enumerate(zip(edge, edge[1:], strict=False)):
            d.segment(
                f"bevel_{k}_{j}", "box", p(*b0, top(*b0) + 0.0006), p(*b1, top(*b1) + 0.0006),
                (0.0016, 0.0003), "metal", shine, visual_only=True,
            )  # fmt: skip
        # the handle of this half lies on the other side of the rivet
        knee, end = (-0.02, -s * 0.0075), (-handle_len, -s * closed)
        d.segment(
            f"shank_{k}", "box", turn(-0.004, -s * 0.0045, s, z), turn(*knee, s, z * 0.9),
            (0.0042, z * 0.6), "metal", metal,
        )  # fmt: skip
        d.segment(f"grip_{k}", "capsule", turn(*knee, s, r), turn(*end, s, r), r, "rubber", grip)
    return Traits((grip, metal), "metal", "irregular")


@generator("chopsticks", size=(0.2, 0.28), synonyms=("chopsticks", "pair of chopsticks"))
def chopsticks(d: Design) -> Traits:
    color = d.choice(["brown", "brown", "beige", "black", "red", "silver"])
    material = "metal" if color == "silver" else d.choice(["wood", "wood", "plastic"])
    band = d.choice(["golden", "red", "white", "black"])
    length, side = d.uniform(0.21, 0.26), d.uniform(0.0085, 0.0095)
    back = length * 0.45
    for k, sign in enumerate((-1, 1)):
        y = sign * d.uniform(0.0085, 0.011)
        x0 = -length / 2
        d.box(
            f"back_{k}",
            (back / 2, side / 2, side / 2),
            (x0 + back / 2, y, side / 2),
            material,
            color,
        )
        d.box(
            f"band_{k}",
            (0.012, side / 2 + 0.0004, side / 2 + 0.0004),
            (x0 + 0.02, y, side / 2),
            material,
            band,
            visual_only=True,
        )
        for j, frac in enumerate((0.75, 0.55)):
            r = side / 2 * frac
            seg = (length - back) / 2
            d.rod(f"tip_{k}_{j}", r, seg, (x0 + back + seg * (j + 0.5), y, r), material, color)
    return Traits((color,), material, "elongated")


@generator("coaster", size=(0.08, 0.12), synonyms=("coaster", "drink coaster"), graspable=False)
def coaster(d: Design) -> Traits:
    material, color = d.choice(
        [
            ("wood", "beige"),
            ("wood", "brown"),
            ("ceramic", "white"),
            ("stone", "black"),
            ("stone", "gray"),
            ("silicone", "blue"),
            ("silicone", "green"),
        ]
    )
    pattern = d.choice(
        [c for c in ("red", "blue", "white", "black", "green", "golden") if c != color]
    )
    size, thick = d.uniform(0.04, 0.05), d.uniform(0.006, 0.009)
    kw = dict(solid_fraction=0.5 if material == "stone" else 1.0)
    if d.rng.random() < 0.5:
        d.upright("disk", size, thick, 0.0, material, color, **kw)
        d.wall("ring", size * 0.72, 0.003, 0.0004, thick, "paper", pattern, segments=20)
        shape = "disk"
    else:
        d.box("slab", (size, size, thick / 2), (0, 0, thick / 2), material, color, **kw)
        d.box(
            "print",
            (size * 0.7, size * 0.7, 0.0002),
            (0, 0, thick + 0.0002),
            "paper",
            pattern,
            yaw=math.pi / 4,
            visual_only=True,
        )
        shape = "flat"
    return Traits((color, pattern), material, shape)


CORK = Texture("pores")


def _cork_stain(d: Design, radius: float, z: float, center: tuple[float, float]) -> None:
    """The ring a wet glass left on cork: a darker, uneven, broken circle printed at ``z``."""
    pieces = 18
    chord = 2 * radius * math.tan(math.pi / pieces) * 1.05
    gap = int(d.rng.integers(pieces))
    for k in range(pieces):
        if k == gap:  # where the ring dried out
            continue
        a = 2 * math.pi * k / pieces
        pos = (center[0] + radius * math.cos(a), center[1] + radius * math.sin(a), z + 0.00015)
        width = d.uniform(0.0022, 0.0042)
        d.box(
            f"stain_{k}",
            (width / 2, chord / 2, 0.00015),
            pos,
            "paper",
            "brown",
            yaw=a,
            visual_only=True,
        )


@revised("coaster", 3)
def coaster_3(d: Design) -> Traits:
    """Revision 3: a set of round cork coasters, each one thin and palm sized: a stack of
    them fanned out so every edge shows, the top one ringed brown where a wet glass stood;
    or a neat stack standing in a wire caddy with posts round it (one cork disc, or a slate
    square, read as a mouse pad or a wireless charger)."""
    cork = "beige"
    size = d.uniform(0.045, 0.049)
    thick = d.uniform(0.0045, 0.006)
    if d.rng.random() < 0.4:  # fanned out, each a step further along
        layers = d.choice([4, 5])
        step = d.uniform(0.0045, 0.0055)
        a = d.uniform(2.9, 4.6)  # away from the front, so the lower edges show
        for k in range(layers):
            xy = (k * step * math.cos(a), k * step * math.sin(a))
            d.upright(f"disk_{k}", size, thick, k * thick, "wood", cork, xy=xy, texture=CORK)
        top = layers * thick
        center = ((layers - 1) * step * math.cos(a), (layers - 1) * step * math.sin(a))
        colors = (cork,)
    else:  # a neat stack in a caddy: a round base and four posts
        caddy = d.choice(["black", "silver", "brown"])
        material = "wood" if caddy == "brown" else "metal"
        fill = {} if material == "wood" else dict(solid_fraction=0.3)
        base = 0.004
        d.upright("caddy_base", size + 0.004, base, 0.0, material, caddy, **fill)
        layers = d.choice([5, 6])
        for k in range(layers):
            xy = (d.uniform(-0.0012, 0.0012), d.uniform(-0.0012, 0.0012))
            z = base + k * thick
            d.upright(f"disk_{k}", size, thick, z, "wood", cork, xy=xy, texture=CORK)
        top = base + layers * thick
        spin = d.uniform(0, math.pi / 2)
        for k in range(4):
            b = spin + k * math.pi / 2
            xy = ((size + 0.0025) * math.cos(b), (size + 0.0025) * math.sin(b))
            d.upright(f"post_{k}", 0.0018, top + 0.008 - base, base, material, caddy, xy=xy, **fill)
            d.sphere(f"post_knob_{k}", 0.0028, (xy[0], xy[1], top + 0.008), material, caddy, **fill)
        center = (0.0, 0.0)
        colors = (cork, caddy)
    _cork_stain(d, d.uniform(0.028, 0.032), top, center)
    return Traits(colors, "wood", "cylinder")


@generator(
    "tray", size=(0.3, 0.48), synonyms=("serving tray", "tray"), graspable=False, container=True
)
def tray(d: Design) -> Traits:
    material, color = d.choice(
        [
            ("wood", "brown"),
            ("wood", "beige"),
            ("plastic", "black"),
            ("plastic", "white"),
            ("plastic", "red"),
            ("metal", "silver"),
            ("metal", "golden"),
        ]
    )
    hx, hy = d.uniform(0.15, 0.22), d.uniform(0.1, 0.15)
    rim = d.uniform(0.02, 0.035)
    kw = dict(solid_fraction=0.2 if material == "metal" else 1.0)
    floor = d.open_box("tray", (hx, hy), rim, 0.006, material, color, full="y", **kw)
    handle = d.choice(["black", color])
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"handle_{k}",
            (0.009, hy * 0.35, 0.006),
            (sign * (hx + 0.009), 0, rim - 0.006),
            material,
            handle,
            **kw,
        )
    colors = (color,) if handle == color else (color, handle)
    d.interior((hx - 0.02, hy - 0.02), floor_z=floor, rim_z=rim)
    return Traits(colors, material, "flat")


@generator("wine_glass", size=(0.14, 0.25), synonyms=("wine glass", "goblet"), container=True)
def wine_glass(d: Design) -> Traits:
    r, bowl_h = d.uniform(0.036, 0.044), d.uniform(0.07, 0.1)
    stem = d.uniform(0.06, 0.09)
    d.upright("foot", d.uniform(0.032, 0.038), 0.004, 0.0, "glass", "transparent")
    d.upright("stem", 0.0045, stem, 0.004, "glass", "transparent")
    floor = 0.008 + stem
    r0, low = r * 0.4, bowl_h * d.uniform(0.35, 0.5)
    d.upright("bowl_floor", r0 + 0.002, 0.004, floor - 0.004, "glass", "transparent")
    d.wall(
        "bowl",
        r0,
        0.003,
        low,
        floor,
        "glass",
        "transparent",
        segments=18,
        flare=math.atan2(r - r0, low),
    )
    d.wall(
        "rim",
        r,
        0.003,
        bowl_h - low,
        floor + low,
        "glass",
        "transparent",
        segments=18,
        flare=-math.atan2(r * 0.1, bowl_h - low),
    )
    d.interior((r0, r0), floor_z=floor, rim_z=floor + bowl_h)
    return Traits(("transparent",), "glass", "irregular")


@generator("coffee_cup", size=(0.08, 0.16), container=True)
def coffee_cup(d: Design) -> Traits:
    if d.rng.random() < 0.5:  # a takeaway paper cup with a cardboard sleeve
        color = d.choice(["white", "white", "white", "black", "beige"])
        sleeve = d.choice([c for c in ("brown", "beige") if c != color])
        logo = d.choice(["green", "red", "blue", "black"])
        r, h = d.uniform(0.022, 0.026), d.uniform(0.1, 0.13)
        flare = math.atan2(d.uniform(0.008, 0.012), h)
        d.upright("bottom", r + 0.001, 0.006, 0.0, "paper", color)
        d.wall("wall", r, 0.002, h - 0.006, 0.006, "paper", color, segments=16, flare=flare)
        lip = r + math.tan(flare) * (h - 0.006) - 0.001
        d.wall("lip", lip, 0.004, 0.004, h - 0.004, "paper", color, segments=16)
        mid = r + math.tan(flare) * h * 0.45
        d.wall("sleeve", mid, 0.003, h * 0.3, h * 0.35, "paper", sleeve, segments=16, flare=flare)
        d.add(
            "logo",
            "cylinder",
            (0.011, 0.0005),
            (mid + math.tan(flare) * h * 0.15 + 0.0036, 0, h * 0.5),
            "paper",
            logo,
            quat=axis_angle_quat((0, 1, 0), flare),
            visual_only=True,
        )
        d.interior((r * 0.7, r * 0.7), floor_z=0.006, rim_z=h)
        return Traits((color, sleeve), "paper", "cylinder")
    color = d.choice(CERAMIC_COLORS)
    saucer = d.choice([color, "white"])
    rs = d.uniform(0.06, 0.072)
    d.upright("saucer_foot", rs * 0.55, 0.004, 0.0, "ceramic", saucer)
    d.wall(
        "saucer",
        rs * 0.6,
        0.004,
        0.008,
        0.004,
        "ceramic",
        saucer,
        segments=20,
        flare=math.atan2(rs * 0.4, 0.008),
    )
    d.upright("saucer_well", rs * 0.6, 0.004, 0.004, "ceramic", saucer)
    r, h = d.uniform(0.03, 0.036), d.uniform(0.05, 0.065)
    z = 0.008
    d.upright("cup_bottom", r * 0.8, 0.006, z, "ceramic", color)
    d.wall(
        "cup_wall",
        r * 0.8,
        0.004,
        h,
        z + 0.006,
        "ceramic",
        color,
        segments=16,
        flare=math.atan2(r * 0.2, h),
    )
    xs = r + 0.002
    for name, zz in (("handle_top", z + h * 0.8), ("handle_bottom", z + h * 0.4)):
        d.box(name, (0.007, 0.004, 0.003), (xs + 0.004, 0, zz), "ceramic", color)
    d.box(
        "handle_grip",
        (0.003, 0.004, h * 0.2 + 0.003),
        (xs + 0.011, 0, z + h * 0.6),
        "ceramic",
        color,
    )
    d.interior((r * 0.55, r * 0.55), floor_z=z + 0.006, rim_z=z + 0.006 + h)
    colors = (color,) if saucer == color else (color, saucer)
    return Traits(colors, "ceramic", "cylinder")


@generator("thermos", size=(0.18, 0.33), synonyms=("thermos", "vacuum flask", "thermos flask"))
def thermos(d: Design) -> Traits:
    color = d.choice(["silver", "silver", "black", "blue", "red", "green", "white", "pink"])
    cap = d.choice(["black", "silver", color])
    r, h = d.uniform(0.03, 0.035), d.uniform(0.19, 0.3)
    cap_h = h * d.uniform(0.18, 0.24)
    body = h - cap_h - 0.012
    d.upright("base_ring", r - 0.001, 0.01, 0.0, "rubber", "black")
    d.upright("body", r, body, 0.01, "metal", color, solid_fraction=0.05)
    d.upright("band", r + 0.0006, 0.01, 0.01 + body * 0.8, "metal", "silver", visual_only=True)
    d.upright("neck", r * 0.8, 0.004, 0.01 + body, "metal", "silver")
    d.upright("cap", r + 0.001, cap_h, 0.014 + body, "plastic", cap, solid_fraction=0.2)
    d.upright(
        "cap_grip",
        r + 0.0016,
        cap_h * 0.3,
        0.014 + body + cap_h * 0.6,
        "rubber",
        cap,
        visual_only=True,
    )
    colors = (color,) if cap == color else (color, cap)
    return Traits(colors, "metal", "cylinder")


@generator("baby_bottle", size=(0.12, 0.22), synonyms=("baby bottle", "feeding bottle"))
def baby_bottle(d: Design) -> Traits:
    ring = d.choice(["blue", "pink", "green", "yellow", "white", "purple"])
    r, h = d.uniform(0.025, 0.032), d.uniform(0.1, 0.15)
    d.upright("body", r, h, 0.0, "plastic", "transparent", solid_fraction=0.08)
    d.upright(
        "milk", r - 0.0015, h * d.uniform(0.3, 0.7), 0.0015, "organic", "white", visual_only=True
    )
    for k in range(4):
        d.box(
            f"mark_{k}",
            (0.0005, 0.005, 0.0006),
            (r + 0.0003, 0, h * (0.25 + 0.15 * k)),
            "plastic",
            ring,
            visual_only=True,
        )
    d.upright("collar", r + 0.002, 0.018, h, "plastic", ring, solid_fraction=0.4)
    teat = d.choice(["beige", "transparent"])
    d.upright("teat_base", r * 0.6, 0.008, h + 0.018, "silicone", teat)
    d.ellipsoid("teat", (r * 0.4, r * 0.4, 0.014), (0, 0, h + 0.026), "silicone", teat)
    d.upright("nipple", 0.004, 0.01, h + 0.036, "silicone", teat)
    return Traits(("transparent", ring), "plastic", "cylinder")


@generator("bottle_opener", size=(0.08, 0.2), synonyms=("bottle opener",))
def bottle_opener(d: Design) -> Traits:
    metal = d.choice(["silver", "silver", "golden", "black"])
    grip = d.choice(["brown", "black", "red", "blue", metal])
    material = "wood" if grip == "brown" else "metal" if grip == metal else "plastic"
    handle, thick = d.uniform(0.06, 0.11), d.uniform(0.01, 0.014)
    hole, ring = d.uniform(0.012, 0.016), d.uniform(0.006, 0.009)
    d.wall("ring", hole, ring, 0.004, 0.0, "metal", metal, segments=12)
    d.box("lip", (0.003, hole * 0.6, 0.002), (hole - 0.003, 0, 0.002), "metal", metal)
    x0 = -(hole + ring)
    d.box("neck", (0.008, 0.006, 0.002), (x0 - 0.004, 0, 0.002), "metal", metal)
    hw = d.uniform(0.009, 0.012)
    d.box(
        "handle",
        (handle / 2, hw, thick / 2),
        (x0 - 0.01 - handle / 2, 0, thick / 2),
        material,
        grip,
    )
    colors = (metal,) if grip == metal else (grip, metal)
    return Traits(colors, "metal", "elongated")


@generator("spatula", size=(0.25, 0.36), synonyms=("spatula", "kitchen spatula", "turner"))
def spatula(d: Design) -> Traits:
    handle, thick = d.uniform(0.13, 0.17), d.uniform(0.012, 0.016)
    _, color = _grip(d, handle, d.uniform(0.01, 0.013), thick, 0.0)
    head = d.choice(["silicone", "plastic", "metal"])
    head_color = "silver" if head == "metal" else d.choice([color, "black", "red", "white"])
    neck, bl, bw = d.uniform(0.04, 0.06), d.uniform(0.08, 0.11), d.uniform(0.028, 0.036)
    t = 0.0015 if head == "metal" else 0.003
    d.box("neck", (neck / 2, 0.006, t), (neck / 2, 0, t), head, head_color)
    d.box("blade", (bl / 2, bw, t / 2), (neck + bl / 2, 0, t / 2), head, head_color)
    for k in range(3):
        d.box(
            f"slot_{k}",
            (bl * 0.3, 0.0025, 0.0002),
            (neck + bl * 0.55, (k - 1) * bw * 0.45, t + 0.0002),
            "plastic",
            "white" if head_color == "black" else "black",
            visual_only=True,
        )
    colors = (color,) if head_color == color else (color, head_color)
    return Traits(colors, head, "flat")
