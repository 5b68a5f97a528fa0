"""Kitchen cutting tools, tableware, ware and utensils."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import axis_angle_quat
from .kitchen import CERAMIC_COLORS
from .registry import generator

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


@generator(
    "peeler",
    size=(0.13, 0.21),
    synonyms=("peeler", "vegetable peeler", "potato peeler"),
    revision=3,
)
def peeler_3(d: Design) -> Traits:
    """Revision 3: lying flat, a Y peeler: a chunky handle, a stem spreading into a yoke
    wider than the handle, and a wide slotted blade across the yoke's tips, its two cutting
    edges bright (a swivel peeler read as a lighter or a penlight)."""
    color = d.choice(GRIPS)
    material = "wood" if color == "brown" else "plastic"
    thick = d.uniform(0.011, 0.014)
    z = thick / 2
    handle, hw = d.uniform(0.08, 0.095), d.uniform(0.013, 0.016)
    _pill(d, "handle", handle, 2 * hw, thick, material, color, x=-handle / 2)
    d.upright(
        "hang_hole",
        0.005,
        0.0006,
        thick,
        "plastic",
        "black",
        xy=(-handle + 0.014, 0),
        visual_only=True,
    )
    reach, half = d.uniform(0.05, 0.056), d.uniform(0.031, 0.034)
    yoke = "silver" if d.rng.random() < 0.4 else color
    yoke_mat = "metal" if yoke == "silver" else material
    arm = (0.0042, z * 0.8)
    stem = reach * 0.3
    d.segment("stem", "box", (-0.006, 0, z), (stem, 0, z), (0.006, z * 0.8), yoke_mat, yoke)
    for k, sign in enumerate((-1, 1)):
        knee = (reach * 0.6, sign * half * 0.92, z)
        d.segment(f"yoke_{k}", "box", (stem - 0.002, 0, z), knee, arm, yoke_mat, yoke)
        d.segment(f"yoke_tip_{k}", "box", knee, (reach, sign * half, z), arm, yoke_mat, yoke)
        d.upright(
            f"rivet_{k}", 0.0038, thick * 0.95, 0.0, "metal", "silver", xy=(reach, sign * half)
        )
    d.box("blade", (0.0075, half - 0.002, 0.0009), (reach, 0, z + 0.0009), "metal", "silver")
    d.box(
        "slot",
        (0.0013, half * 0.78, 0.0002),
        (reach, 0, z + 0.002),
        "metal",
        "black",
        visual_only=True,
    )
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"edge_{k}",
            (0.0006, half * 0.85, 0.0002),
            (reach + sign * 0.0052, 0, z + 0.002),
            "metal",
            "white",
            visual_only=True,
        )
    d.box(  # the potato-eye scoop on one arm
        "eye_scoop",
        (0.004, 0.0025, z * 0.6),
        (reach * 0.75, half * 1.02, z),
        "metal",
        "silver",
    )
    return Traits((color, "silver"), material, "T-shape")


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
    "wire_cutters",
    size=(0.11, 0.2),
    synonyms=("wire cutters", "side cutters", "wire snips"),
    revision=3,
)
def wire_cutters_3(d: Design) -> Traits:
    """Revision 3: diagonal side cutters lying across the view, cutting a wire: a short,
    black, pointed head of two almond jaws opened a little about a round boss with a
    bright rivet, a bright ground bevel down each jaw's cutting edge, and a short piece of
    insulated wire standing in the gap between the edges, bent over the front jaw to a
    bare copper end; two plain dipped grips, spread with the jaws (the first, long
    straight jaws, read as pliers or a can opener; the head shut and empty, as pliers;
    a flat square nose is the pliers')."""
    grip = d.choice(["red", "red", "yellow", "red", "orange", "blue"])
    metal, shine = "black", "white"  # a dark oxide head, so that the ground bevels shine
    cover = d.choice([c for c in ("blue", "green", "yellow", "red") if c != grip])
    jaw_len, half_w = d.uniform(0.032, 0.035), d.uniform(0.0135, 0.0145)
    handle_len, closed = d.uniform(0.095, 0.1), d.uniform(0.004, 0.006)
    open_a = math.radians(d.uniform(9.0, 11.0))  # each half turned open about the rivet
    thick = d.uniform(0.011, 0.012)
    z = thick / 2
    r = d.uniform(0.0064, 0.0068)  # the dipped grips' radius
    wire_r = d.uniform(0.0017, 0.002)

    def turn(u: float, v: float, s: int, h: float) -> tuple[float, float, float]:
        """A point of the half on side ``s`` (the tool's frame: u from the handles to the
        tip), turned open about the rivet and laid along +y, across the view."""
        c, sn = math.cos(s * open_a), math.sin(s * open_a)
        return (-(u * sn + v * c), u * c - v * sn, h)

    d.upright("boss", half_w * 0.9, thick, 0.0, "metal", metal)
    d.upright("rivet", 0.0045, thick + 0.001, 0.0, "metal", shine)
    semi = half_w * 0.55  # the almonds' half width

    def edge(s: int, u: float) -> tuple[float, float]:
        """Where the almond of side ``s`` ends across u (towards the middle), shut, and
        how high its top is a little inside that."""
        (u0, v0), (u1, v1) = (-0.004, s * semi), (jaw_len, 0.0)
        a = math.dist((u0, v0), (u1, v1)) / 2
        eu, ev = (u1 - u0) / (2 * a), (v1 - v0) / (2 * a)
        du = u - (u0 + u1) / 2
        qa = ev * ev / a**2 + eu * eu / semi**2
        qb = 2 * du * eu * ev * (1 / a**2 - 1 / semi**2)
        qc = du * du * (eu * eu / a**2 + ev * ev / semi**2) - 1
        root = math.sqrt(max(qb * qb - 4 * qa * qc, 0.0))
        t = (-qb - s * root) / (2 * qa)  # the end towards -s
        v = (v0 + v1) / 2 + t + s * 0.0016
        x, y = du * eu + (v - (v0 + v1) / 2) * ev, -du * ev + (v - (v0 + v1) / 2) * eu
        return v, z + z * math.sqrt(max(1 - (x / a) ** 2 - (y / semi) ** 2, 0.0)) + 0.0006

    for k, s in enumerate((-1, 1)):
        d.segment(
            f"jaw_{k}", "ellipsoid", turn(-0.004, s * semi, s, z), turn(jaw_len, 0.0, s, z),
            (semi, z), "metal", metal,
        )  # fmt: skip
        # the ground bevel along this jaw's cutting edge, following the jaw's top
        us = [0.006 + (jaw_len * 0.88 - 0.006) * f for f in (0, 0.33, 0.66, 1)]
        for j, (u0, u1) in enumerate(zip(us, us[1:], strict=False)):
            (v0, h0), (v1, h1) = edge(s, u0), edge(s, u1)
            d.segment(
                f"bevel_{k}_{j}", "box", turn(u0, v0, s, h0), turn(u1, v1, s, h1),
                (0.0014, 0.0003), "metal", shine, visual_only=True,
            )  # fmt: skip
        # the handle of this half lies on the other side of the rivet
        knee, end = (-0.02, -s * 0.0075), (-handle_len, -s * closed)
        d.segment(
            f"shank_{k}", "box", turn(-0.004, -s * 0.0045, s, z), turn(*knee, s, z * 0.9),
            (0.0042, z * 0.6), "metal", metal,
        )  # fmt: skip
        d.segment(f"grip_{k}", "capsule", turn(*knee, s, r), turn(*end, s, r), r, "rubber", grip)
    # the wire, standing in the gap where the cutting edges are about to meet, bent over
    # the front jaw (towards +x) down to the table, its cut end bare copper
    uw = jaw_len * 0.5
    inner = [turn(uw, edge(s, uw)[0] - s * 0.0016, s, 0.0) for s in (-1, 1)]
    wx, wy, _ = ((a + b) / 2 for a, b in zip(*inner, strict=True))
    rise = thick + d.uniform(0.008, 0.011)
    reach = half_w + d.uniform(0.008, 0.012)
    path = [
        (wx, wy, wire_r),
        (wx, wy, rise),
        (wx + reach * 0.55, wy - 0.003, rise + 0.002),
        (wx + reach, wy - 0.006, thick * 0.6),
        (wx + reach * 1.15, wy - 0.007, wire_r),
    ]
    for j, (a, b) in enumerate(zip(path, path[1:], strict=False)):
        d.segment(f"wire_{j}", "capsule", a, b, wire_r, "plastic", cover)
    tip = (path[-1][0] + 0.009, path[-1][1] - 0.0005, wire_r * 0.6)
    d.segment("copper", "capsule", path[-1], tip, wire_r * 0.6, "metal", "golden")
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


@generator(
    "coaster", size=(0.08, 0.12), synonyms=("coaster", "drink coaster"), graspable=False, revision=3
)
def coaster_3(d: Design) -> Traits:
    """Revision 3: a set of square or round coasters (slate, ceramic, bamboo or felt, each
    printed with a geometric tile in a contrasting ink): standing on edge in a rack between
    two uprights, the front one's print facing out, or lying in a box caddy open at the
    front, the top one rimmed (a stack of round cork discs read as tortillas)."""
    material, color, inks = d.choice(
        [
            ("stone", "black", ["white", "golden"]),
            ("stone", "gray", ["white", "black"]),
            ("ceramic", "white", ["blue", "black", "green", "red"]),
            ("ceramic", "blue", ["white"]),
            ("wood", "brown", ["black", "white"]),
            ("fabric", "gray", ["red", "white"]),
        ]
    )
    ink = d.choice(inks)
    fill = dict(solid_fraction=0.5) if material in ("stone", "ceramic") else {}
    caddy = d.choice(["brown", "black", "silver", "white"])
    caddy_mat = {"brown": "wood", "white": "plastic"}.get(caddy, "metal")
    caddy_fill = dict(solid_fraction=0.25) if caddy_mat == "metal" else {}
    half = d.uniform(0.04, 0.045)  # half the coaster's side
    thick = d.uniform(0.005, 0.007)
    if d.rng.random() < 0.5:  # standing on edge in a rack, faces along x, the print at +x
        count = d.choice([4, 5])
        pitch = thick + d.uniform(0.004, 0.006)
        base = 0.006
        depth = count * pitch / 2 + 0.006
        d.slab("rack_base", (depth, half + 0.008, base / 2), 0.0, caddy_mat, caddy, **caddy_fill)
        for k, s in enumerate((-1, 1)):  # the two uprights, and a low rail at each side
            d.slab(
                f"rack_upright_{k}",
                (0.004, 0.004, half * 0.75),
                base,
                caddy_mat,
                caddy,
                xy=(0.0, s * (half + 0.004)),
                **caddy_fill,
            )
            d.slab(
                f"rack_rail_{k}",
                (0.003, half, 0.006),
                base,
                caddy_mat,
                caddy,
                xy=(s * (depth - 0.003), 0.0),
                **caddy_fill,
            )
        x0 = -(count - 1) * pitch / 2
        for k in range(count):
            x = x0 + k * pitch
            d.box(
                f"coaster_{k}",
                (thick / 2, half, half),
                (x, 0, base + half),
                material,
                color,
                **fill,
            )
        face = x0 + (count - 1) * pitch + thick / 2 + 0.0002
        _tile_print(d, ink, half, (face, 0.0, base + half), "x")
    else:  # lying in a box caddy open at +x, the stack's edges showing at the front
        count = d.choice([4, 5])
        floor, wall = 0.004, 0.004
        inner = half + 0.002
        height = floor + count * thick * 0.5
        sides = (inner + wall / 2, inner + wall, (height - floor) / 2)
        d.slab(
            "caddy_floor",
            (inner + wall / 2, inner + wall, floor / 2),
            0.0,
            caddy_mat,
            caddy,
            xy=(-wall / 2, 0.0),
            **caddy_fill,
        )
        d.slab(
            "caddy_back",
            (wall / 2, inner + wall, sides[2]),
            floor,
            caddy_mat,
            caddy,
            xy=(-inner - wall / 2, 0.0),
            **caddy_fill,
        )
        for k, s in enumerate((-1, 1)):
            d.slab(
                f"caddy_side_{k}",
                (inner, wall / 2, sides[2]),
                floor,
                caddy_mat,
                caddy,
                xy=(0.0, s * (inner + wall / 2)),
                **caddy_fill,
            )
        for k in range(count):
            d.slab(
                f"coaster_{k}", (half, half, thick / 2), floor + k * thick, material, color, **fill
            )
        top = floor + count * thick
        d.frame("rim", (half, half), 0.0035, top, 0.0012, material, color, **fill)
        _tile_print(d, ink, half - 0.004, (0.0, 0.0, top + 0.0003), "z")
    colors = (color,) if caddy == color else (color, caddy)
    return Traits(colors, material, "flat")


def _tile_print(d: Design, ink: str, half: float, center, normal: str) -> None:
    """A print on a coaster's face (normal +x or +z) at ``center``: an inset border round a
    cocktail glass, or round a diamond with a square dot at the middle."""
    cx, cy, cz = center

    def put(name, u, v, hu, hv, turn=0.0):
        if normal == "z":  # upright to a viewer at +x: u along +y, v along -x
            quat = axis_angle_quat((0, 0, 1), turn + math.pi / 2)
            pos, size = (cx - v, cy + u, cz), (hu, hv, 0.0003)
        else:
            quat = axis_angle_quat((1, 0, 0), turn)
            pos, size = (cx, cy + u, cz + v), (0.0003, hu, hv)
        d.add(name, "box", size, pos, "paper", ink, quat=quat, visual_only=True)

    b, w = half * 0.82, 0.0022
    for k, s in enumerate((-1, 1)):
        put(f"print_edge_u{k}", s * b, 0.0, w, b + w)
        put(f"print_edge_v{k}", 0.0, s * b, b + w, w)
    if d.rng.random() < 0.5:  # a cocktail glass: a V bowl on a stem and a foot
        top, tip, base = b * 0.5, -b * 0.05, -b * 0.5
        put("print_glass_rim", 0.0, top, b * 0.45, w)
        arm = math.hypot(b * 0.45, top - tip)
        for k, s in enumerate((-1, 1)):
            turn = math.atan2(top - tip, s * b * 0.45)
            put(f"print_glass_{k}", s * b * 0.225, (top + tip) / 2, arm / 2, w, turn)
        put("print_glass_stem", 0.0, (tip + base) / 2, w, (tip - base) / 2)
        put("print_glass_foot", 0.0, base, b * 0.25, w)
        put("print_olive", -b * 0.1, top - b * 0.15, b * 0.06, b * 0.06)
        return
    r = b * 0.72  # the diamond's corners, on the axes
    side = r / math.sqrt(2)
    for k, (su, sv) in enumerate(((1, 1), (-1, 1), (-1, -1), (1, -1))):
        turn = -math.pi / 4 if su * sv > 0 else math.pi / 4
        put(f"print_diamond_{k}", su * r / 2, sv * r / 2, side, w, turn)
    put("print_dot", 0.0, 0.0, b * 0.16, b * 0.16, math.pi / 4)


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


@generator(
    "thermos", size=(0.18, 0.33), synonyms=("thermos", "vacuum flask", "thermos flask"), revision=3
)
def thermos_3(d: Design) -> Traits:
    """Revision 3: a vacuum flask: a steel or coloured body on a black rubber foot, its
    shoulder narrowing to a neck, a carry handle on two lugs up its side, and on top either
    a screw-on cup (its lip ridge over a dark thread gap, a stopper's knob peeping above)
    or a flip lid with a push button and a spout (a plain banded cylinder read as a stack of
    cups)."""
    color = d.choice(["silver", "silver", "green", "black", "blue", "red", "white"])
    r, h = d.uniform(0.034, 0.038), d.uniform(0.22, 0.29)
    foot = 0.014
    d.upright("foot", r + 0.0008, foot, 0.0, "rubber", "black")
    shoulder = h * d.uniform(0.62, 0.66)
    d.upright("body", r, shoulder - foot, foot, "metal", color, solid_fraction=0.05)
    d.upright("body_seam", r + 0.0005, 0.002, foot + 0.012, "metal", "silver", visual_only=True)
    steps = (0.93, 0.82, 0.7)
    for k, f in enumerate(steps):  # the shoulder, narrowing in steps
        d.upright(
            f"shoulder_{k}", r * f, 0.006, shoulder + 0.006 * k, "metal", color, solid_fraction=0.1
        )
    z = shoulder + 0.006 * len(steps)
    d.upright("neck", r * 0.62, 0.01, z, "metal", "silver", solid_fraction=0.2)
    if d.rng.random() < 0.6:  # a screw-on cup over a stopper
        cap = d.choice(["silver", "black", color])
        d.upright("thread_gap", r * 0.74, 0.004, z, "rubber", "black")
        z += 0.004
        cup_h = h - z - 0.006
        d.upright("cup_lip", r * 0.97, 0.006, z, "plastic", cap, solid_fraction=0.3)
        d.upright("cup", r * 0.9, cup_h - 0.006, z + 0.006, "plastic", cap, solid_fraction=0.15)
        for k in range(2):  # grip rings round the cup
            d.upright(
                f"cup_ring_{k}",
                r * 0.9 + 0.0008,
                0.002,
                z + cup_h * (0.45 + 0.2 * k),
                "plastic",
                "gray" if cap == "black" else "black",
                visual_only=True,
            )
        d.upright("stopper_knob", r * 0.3, 0.006, h - 0.006, "plastic", "black")
    else:  # a flip lid: a push button on top, a spout at the front
        cap = d.choice(["black", "gray", color])
        lid_h = h - z - 0.004
        d.upright("lid", r * 0.8, lid_h, z, "plastic", cap, solid_fraction=0.3)
        d.upright("lid_top", r * 0.7, 0.004, z + lid_h, "plastic", cap, solid_fraction=0.3)
        d.upright(
            "button", r * 0.3, 0.004, h - 0.002, "plastic", "gray" if cap != "gray" else "black"
        )
        d.box(
            "spout",
            (r * 0.2, 0.006, 0.006),
            (r * 0.8 + r * 0.1, 0, z + lid_h - 0.01),
            "plastic",
            cap,
        )
    # a carry handle up the side (+y), on two lugs round the body
    gap, grip_w = 0.02, 0.0065
    lo, hi = foot + (shoulder - foot) * 0.3, shoulder - 0.01
    for k, zz in enumerate((lo, hi)):
        d.upright(f"lug_band_{k}", r + 0.0015, 0.01, zz - 0.005, "plastic", "black")
        d.box(f"lug_{k}", (0.006, gap / 2 + 0.001, 0.005), (0, r + gap / 2, zz), "plastic", "black")
    d.box(
        "handle_grip",
        (0.006, grip_w / 2, (hi - lo) / 2 + 0.005),
        (0, r + gap + grip_w / 2, (lo + hi) / 2),
        "plastic",
        "black",
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
