"""Office stationery and office tools."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import axis_angle_quat
from ..textures import Texture
from .desktop import BRIGHT
from .registry import generator


@generator("stapler", size=(0.12, 0.2))
def stapler(d: Design) -> Traits:
    body = d.choice(["black", "red", "blue", "gray", "silver", "green"])
    base = d.choice(["black", "silver", "gray"])
    material = "metal" if body == "silver" else "plastic"
    lx, w = d.uniform(0.13, 0.18), d.uniform(0.032, 0.042)
    base_t, arm_z, arm_t = 0.006, d.uniform(0.022, 0.028), d.uniform(0.014, 0.019)
    d.slab("base", (lx / 2, w / 2, base_t / 2), 0.0, "metal", base, solid_fraction=0.35)
    anvil = (lx / 2 - 0.016, 0, base_t + 0.0004)
    d.box("anvil", (0.008, w * 0.25, 0.0004), anvil, "metal", "silver", visual_only=True)
    hinge = (lx * 0.07, w * 0.4, (arm_z - base_t) / 2)
    d.slab("hinge", hinge, base_t, "metal", base, xy=(-lx / 2 + hinge[0], 0), solid_fraction=0.35)
    arm_l = lx * d.uniform(0.94, 0.99)
    arm_x, fill = -lx / 2 + arm_l / 2, 0.12 if material == "metal" else 0.45
    arm = (arm_l / 2, w * 0.42, arm_t / 2)
    d.slab("arm", arm, arm_z, material, body, xy=(arm_x, 0), solid_fraction=fill)
    cover = (arm_l / 2, w * 0.42, arm_t * 0.4)
    d.ellipsoid("cover", cover, (arm_x, 0, arm_z + arm_t), material, body, visual_only=True)
    nose = (0.007, w * 0.36, 0.003)
    d.slab("nose", nose, arm_z - 0.006, "metal", "silver", xy=(arm_x + arm_l / 2 - 0.007, 0))
    return Traits((body, base), material, "elongated")


@generator("ballpoint_pen", size=(0.12, 0.16), synonyms=("pen", "ballpoint pen", "ballpoint"))
def ballpoint_pen(d: Design) -> Traits:
    ink = d.choice(["blue", "black", "red", "green"])
    length = d.uniform(0.135, 0.15)
    if d.rng.random() < 0.5:  # stick pen: hexagonal clear barrel, cap and end plug in ink colour
        a = d.uniform(0.0036, 0.0044)
        body = d.choice(["transparent", "transparent", "white", "yellow"])
        cap = d.uniform(0.03, 0.035)
        barrel = length - cap - 0.004
        x0 = -length / 2
        d.rod("plug", a * 0.8, 0.004, (x0 + 0.002, 0, a), "plastic", ink)
        d.hex_rod("barrel", a, barrel, (x0 + 0.004 + barrel / 2, 0, a), "plastic", body)
        refill = (x0 + 0.004 + barrel / 2, 0, a)
        d.rod("refill", a * 0.3, barrel, refill, "plastic", ink, visual_only=True)
        d.hex_rod("cap", a + 0.0007, cap, (length / 2 - cap / 2, 0, a + 0.0007), "plastic", ink)
        clip = (length / 2 - cap / 2 - 0.002, 0, 2 * a + 0.0026)
        d.box("clip", (cap * 0.4, 0.0016, 0.0012), clip, "plastic", ink)
        return Traits((body, ink), "plastic", "elongated")
    body = d.choice(["black", "silver", "blue", "white", "red", "purple"])
    material = "metal" if body == "silver" else "plastic"
    r = d.uniform(0.0042, 0.0055)
    grip, cone, button = length * 0.25, 0.012, 0.008
    barrel = length - grip - cone - button
    x = -length / 2
    d.rod("button", r * 0.55, button, (x + button / 2, 0, r), "plastic", ink)
    x += button
    d.rod("barrel", r, barrel, (x + barrel / 2, 0, r), material, body, solid_fraction=0.6)
    d.box("clip", (0.022, 0.0016, 0.0011), (x + 0.024, 0, 2 * r + 0.0011), "metal", "silver")
    x += barrel
    d.rod("grip", r + 0.0005, grip, (x + grip / 2, 0, r), "rubber", d.choice(["black", ink]))
    x += grip
    d.rod("cone", r * 0.55, cone, (x + cone / 2, 0, r), "metal", "silver")
    return Traits((body,), material, "elongated")


@generator(
    "pen_holder",
    size=(0.085, 0.13),
    synonyms=("pen holder", "pencil holder", "pen cup", "pencil cup"),
    container=True,
    revision=3,
)
def pen_holder_3(d: Design) -> Traits:
    """Revision 3: the holder carries a few pens and pencils standing against its wall and
    sticking out above the rim, clear of the interior (an empty one read as a cup)."""
    material = d.choice(["plastic", "metal", "wood", "ceramic"])
    color = d.choice(
        {
            "plastic": BRIGHT + ["white"],
            "metal": ["silver", "black", "gray"],
            "wood": ["brown", "beige"],
            "ceramic": ["white", "blue", "black", "green", "beige"],
        }[material]
    )
    t = {"metal": 0.0015, "wood": 0.006, "plastic": 0.003, "ceramic": 0.005}[material]
    h, floor = d.uniform(0.078, 0.09), 0.006
    round_cup = d.rng.random() < 0.6
    if round_cup:
        r = d.uniform(0.034, 0.04)
        d.upright("floor", r + t, floor, 0.0, material, color)
        d.wall("wall", r, t, h - floor, floor, material, color, segments=20)
        half = (r * 0.6, r * 0.6)
        if material == "metal":  # a wire mesh: dark holes in rows round the wall
            for k in range(20):
                a = 2 * math.pi * (k + 0.5) / 20
                pos = ((r + t + 0.0004) * math.cos(a), (r + t + 0.0004) * math.sin(a))
                d.box(
                    f"mesh_{k}",
                    (0.0003, 0.0012, (h - floor) * 0.42),
                    (*pos, floor + h * 0.46),
                    "metal",
                    "gray" if color == "black" else "black",
                    yaw=a,
                    visual_only=True,
                )
        spots = [(r - 0.005, 0.0), (0.0, r - 0.005), (-(r - 0.005), 0.0), (0.0, -(r - 0.005))]
    else:
        r = d.uniform(0.03, 0.034)
        d.open_box("cup", (r + t, r + t), h, t, material, color, floor=floor, tags=(-1, 1))
        half = (r * 0.62, r * 0.62)
        spots = [(r - 0.005, 0.0), (0.0, r - 0.005), (-(r - 0.005), 0.0), (0.0, -(r - 0.005))]
    d.interior(half, floor_z=floor, rim_z=h)
    order = [int(k) for k in d.rng.permutation(4)][: d.choice([2, 3, 3])]
    for n, k in enumerate(sorted(order)):
        x, y = spots[k]
        _desk_pen(d, f"pen_{n}", x, y, floor, h + d.uniform(0.025, 0.038), d.uniform(-0.07, 0.07))
    shape = "cylinder" if round_cup else "cuboid"
    return Traits((color,), material, shape)


def _desk_pen(d: Design, name: str, x: float, y: float, z0: float, top: float, lean: float) -> None:
    """A pen or a pencil standing in a holder at (x, y), from z0 to top, leaning ``lean``
    radians sideways (along the wall), its writing end down (visual: it rides in the cup)."""
    along = math.atan2(y, x) + math.pi / 2  # the wall's direction here
    length = top - z0
    sx, sy = math.cos(along) * math.sin(lean), math.sin(along) * math.sin(lean)
    p0, p1 = (x, y, z0), (x + sx * length, y + sy * length, z0 + math.cos(lean) * length)

    def at(f: float) -> tuple[float, float, float]:
        return tuple(a + (b - a) * f for a, b in zip(p0, p1, strict=True))

    kind = d.choice(["pencil", "pen", "pen", "marker"])
    if kind == "pencil":
        d.segment(name, "cylinder", p0, at(0.93), 0.0037, "wood", "yellow", visual_only=True)
        d.segment(
            f"{name}_ferrule",
            "cylinder",
            at(0.93),
            at(0.965),
            0.0038,
            "metal",
            "silver",
            visual_only=True,
        )
        d.segment(
            f"{name}_eraser",
            "cylinder",
            at(0.965),
            p1,
            0.0036,
            "rubber",
            "pink",
            visual_only=True,
        )
        return
    if kind == "marker":
        ink = d.choice(BRIGHT)
        d.segment(name, "cylinder", p0, at(0.7), 0.0055, "plastic", "white", visual_only=True)
        d.segment(f"{name}_cap", "cylinder", at(0.7), p1, 0.006, "plastic", ink, visual_only=True)
        return
    ink = d.choice(["blue", "black", "red"])
    body = d.choice(["white", "transparent", "black", "blue"])
    d.segment(name, "cylinder", p0, at(0.9), 0.0042, "plastic", body, visual_only=True)
    d.segment(f"{name}_button", "cylinder", at(0.9), p1, 0.0025, "plastic", ink, visual_only=True)
    d.segment(
        f"{name}_clip",
        "box",
        at(0.72),
        at(0.95),
        (0.0012, 0.0008),
        "plastic",
        ink,
        visual_only=True,
    )


@generator("glue_stick", size=(0.07, 0.12), synonyms=("glue stick", "stick of glue"), revision=3)
def glue_stick_3(d: Design) -> Traits:
    """Revision 3: an open glue stick, a stubby printed tube with the white glue twisted up
    out of it, its ribbed twist base, and the cap lying beside it (capped, it read as a
    marker or a lip balm)."""
    body = d.choice(["white", "yellow", "blue", "purple", "green", "red"])
    cap = d.choice(["white", "red", "blue", "orange", "purple", "black"])
    glue = d.choice(["white", "white", "white", "purple"])
    r, h = d.uniform(0.011, 0.013), d.uniform(0.08, 0.095)
    twist = 0.009
    d.upright("twist", r * 0.96, twist, 0.0, "plastic", cap)
    for k in range(12):  # the grip ribs of the twist base
        a = 2 * math.pi * k / 12
        pos = (r * 0.96 * math.cos(a), r * 0.96 * math.sin(a), twist / 2)
        d.box(
            f"rib_{k}",
            (0.0006, 0.0007, twist * 0.4),
            pos,
            "plastic",
            cap,
            yaw=a,
            visual_only=True,
        )
    body_h = h - twist - d.uniform(0.01, 0.013)
    ink = "white" if body in ("blue", "purple", "green", "red") else "blue"
    band = Texture("label_around_glue", (ink, body if ink == "white" else "white"))
    d.upright("body", r, body_h, twist, "plastic", body, solid_fraction=0.6, texture=band)
    d.upright("rim", r + 0.0003, 0.0015, twist + body_h - 0.0015, "plastic", body, visual_only=True)
    stick = h - twist - body_h
    d.upright("glue", r * 0.86, stick - 0.002, twist + body_h, "plastic", glue)
    d.add(  # the glue's worn, slanted top
        "glue_top",
        "ellipsoid",
        (r * 0.86, r * 0.86, 0.0025),
        (0, 0, h - 0.0027),
        "plastic",
        glue,
        quat=axis_angle_quat((0, 1, 0), 0.18),
        visual_only=True,
    )
    cap_h = d.uniform(0.024, 0.03)
    cr = r + 0.0008
    side = (0.0, r + cr + 0.006)
    d.rod("cap_lying", cr, cap_h, (side[0], side[1], cr), "plastic", cap)
    d.rod(
        "cap_rim",
        cr + 0.0004,
        0.002,
        (side[0] + cap_h / 2 - 0.001, side[1], cr),
        "plastic",
        cap,
        visual_only=True,
    )
    d.rod(
        "cap_hollow",
        cr - 0.0015,
        0.0006,
        (side[0] + cap_h / 2 + 0.0003, side[1], cr),
        "plastic",
        "gray",
        visual_only=True,
    )
    return Traits((body, cap), "plastic", "cylinder")


@generator(
    "correction_tape", size=(0.06, 0.1), synonyms=("correction tape", "white-out tape"), revision=3
)
def correction_tape_3(d: Design) -> Traits:
    """Revision 3: a flat, mouse-shaped dispenser lying on its side, the big white tape roll
    and the smaller take-up reel showing on its top, the white tape running along to the
    applicator tip at the tapered front (a round reel case with a stubby nose read as a
    whistle)."""
    color = d.choice(["blue", "pink", "purple", "green", "orange", "blue"])
    hub = d.choice(["white", "gray", "black"])
    length, w, h = d.uniform(0.085, 0.095), d.uniform(0.034, 0.04), d.uniform(0.014, 0.017)
    R = w / 2
    xr = -length / 2 + R  # the rear reel's centre
    kw = dict(solid_fraction=0.5)
    # the shell: a round back, a body tapering to a narrow nose
    d.upright("shell_back", R, h, 0.0, "plastic", color, xy=(xr, 0), **kw)
    mid = length * 0.2
    d.slab(
        "shell",
        (mid / 2 + R / 2, R * 0.92, h / 2),
        0.0,
        "plastic",
        color,
        xy=(xr + mid / 2, 0),
        **kw,
    )
    nose_x0 = xr + mid + R * 0.5
    nose_x1 = length / 2 - 0.006
    for k, sign in enumerate((-1, 1)):
        p0 = (nose_x0 - 0.003, sign * (R * 0.92 - 0.003), 0.0)
        p1 = (nose_x1, sign * 0.0035, 0.0)
        half_w = 0.003
        dx, dy = p1[0] - p0[0], p1[1] - p0[1]
        ln = math.hypot(dx, dy)
        d.box(
            f"nose_{k}",
            (ln / 2, half_w, h * 0.42),
            ((p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2, h * 0.42),
            "plastic",
            color,
            yaw=math.atan2(dy, dx),
            **kw,
        )
    d.slab(
        "nose",
        ((nose_x1 - nose_x0) / 2, 0.005, h * 0.42),
        0.0,
        "plastic",
        color,
        xy=((nose_x0 + nose_x1) / 2, 0),
        **kw,
    )
    # the applicator tip, the white tape wrapped over it
    d.slab(
        "tip",
        (0.003, 0.0045, h * 0.16),
        h * 0.26,
        "plastic",
        "transparent",
        xy=(nose_x1 + 0.002, 0),
    )
    d.box(
        "tape_tip",
        (0.0006, 0.0047, h * 0.17),
        (nose_x1 + 0.0052, 0, h * 0.42),
        "paper",
        "white",
        visual_only=True,
    )
    # the white tape roll standing proud of the shell, the take-up reel beside the tape
    # and the tape running from the roll to the tip
    roll, rh = R * 0.88, 0.004
    d.upright("roll", roll, rh, h - 0.001, "paper", "white", xy=(xr, 0), visual_only=True)
    d.upright(
        "roll_core",
        roll * 0.45,
        rh + 0.0004,
        h - 0.001,
        "plastic",
        hub,
        xy=(xr, 0),
        visual_only=True,
    )
    for j in range(3):
        d.box(
            f"spoke_{j}",
            (roll * 0.4, 0.0008, 0.0004),
            (xr, 0, h + rh - 0.0006),
            "plastic",
            color,
            yaw=math.pi * j / 3,
            visual_only=True,
        )
    xt, yt = xr + R + 0.01, -R * 0.42
    d.upright("reel", 0.0065, 0.0012, h - 0.0004, "plastic", "gray", xy=(xt, yt), visual_only=True)
    d.upright(
        "reel_core", 0.0028, 0.0016, h - 0.0004, "plastic", hub, xy=(xt, yt), visual_only=True
    )
    run = ((xr + roll * 0.85, 0.0, h + rh * 0.5), (nose_x0, 0.0, h + 0.0004))
    run += ((nose_x1, 0.0, h * 0.84 + 0.0004), (nose_x1 + 0.0058, 0.0, h * 0.6))
    for k in range(3):
        d.segment(
            f"tape_run_{k}",
            "box",
            run[k],
            run[k + 1],
            (0.0026, 0.0003),
            "paper",
            "white",
            visual_only=True,
        )
    return Traits((color, "white"), "plastic", "flat")


@generator("sharpener", size=(0.02, 0.065), synonyms=("pencil sharpener", "sharpener"))
def sharpener(d: Design) -> Traits:
    blade = d.choice(["silver", "gray"])
    if d.rng.random() < 0.5:  # a small aluminium block
        color = d.choice(["silver", "red", "blue", "green", "golden"])
        lx, ly, lz = d.uniform(0.022, 0.03), d.uniform(0.014, 0.018), d.uniform(0.01, 0.013)
        d.slab("block", (lx / 2, ly / 2, lz / 2), 0.0, "aluminium", color)
        colors, material, z_hole, top = (color,), "aluminium", lz / 2, lz
    else:  # a plastic head over a clear shavings canister
        color = d.choice(BRIGHT)
        lx, ly = d.uniform(0.035, 0.06), d.uniform(0.022, 0.032)
        can, head = d.uniform(0.012, 0.02), d.uniform(0.014, 0.018)
        d.slab(
            "canister",
            (lx / 2, ly / 2, can / 2),
            0.0,
            "plastic",
            "transparent",
            solid_fraction=0.25,
        )
        d.slab("head", (lx / 2, ly / 2, head / 2), can, "plastic", color, solid_fraction=0.6)
        colors, material, z_hole, top = (
            (color, "transparent"),
            "plastic",
            can + head / 2,
            can + head,
        )
    d.rod("hole", 0.0045, 0.001, (lx / 2 + 0.0005, 0, z_hole), "plastic", "black", visual_only=True)
    d.box(
        "blade",
        (lx * 0.3, ly * 0.35, 0.0004),
        (0, 0, top + 0.0004),
        "metal",
        blade,
        visual_only=True,
    )
    d.upright("screw", 0.0018, 0.0006, top + 0.0008, "metal", "black", visual_only=True)
    return Traits(colors, material, "cuboid")


@generator("notebook", size=(0.14, 0.27), synonyms=("notebook", "exercise book"), graspable=False)
def notebook(d: Design) -> Traits:
    cover = d.choice(BRIGHT + ["brown", "beige", "gray", "white"])
    lx, ly = d.choice([(0.21, 0.148), (0.148, 0.105), (0.25, 0.176), (0.18, 0.13)])
    scale = d.uniform(0.97, 1.03)
    lx, ly, pages, skin = lx * scale, ly * scale, d.uniform(0.006, 0.016), 0.0012
    d.slab("back_cover", (lx / 2, ly / 2, skin / 2), 0.0, "paper", cover)
    d.slab("pages", (lx / 2 - 0.003, ly / 2 - 0.003, pages / 2), skin, "paper", "white")
    top = 2 * skin + pages
    d.slab("front_cover", (lx / 2, ly / 2, skin / 2), skin + pages, "paper", cover)
    edge = ly / 2 - 0.006
    if d.rng.random() < 0.5:
        n, rc = int(lx / 0.009), top / 2 + 0.003
        for k in range(n):
            coil = (-lx / 2 + (k + 0.5) * lx / n, edge + 0.004, rc)
            d.rod(f"coil_{k}", rc, 0.0012, coil, "metal", "silver", visual_only=True)
    else:
        spine = (0, edge, top + 0.0003)
        tape = d.choice(["black", "brown", "gray", "red"])
        d.box("spine", (lx / 2, 0.008, 0.0003), spine, "fabric", tape, visual_only=True)
    if d.rng.random() < 0.5:
        label = (lx * 0.1, -ly * 0.1, top + 0.0002)
        d.box("label", (ly * 0.22, ly * 0.13, 0.0002), label, "paper", "white", visual_only=True)
    else:
        band = (lx / 2 - 0.022, 0, top + 0.0004)
        color = d.choice(["black", "red", "gray"])
        d.box("band", (0.003, ly / 2, 0.0004), band, "fabric", color, visual_only=True)
    return Traits((cover,), "paper", "flat")


@generator("scissors", size=(0.13, 0.22), synonyms=("scissors", "pair of scissors"))
def scissors(d: Design) -> Traits:
    handle = d.choice(BRIGHT + ["black", "gray"])
    length = d.uniform(0.14, 0.21)
    blade, bw, opening = length * 0.47, d.uniform(0.009, 0.013), d.uniform(0.02, 0.07)
    ring, band, thick = d.uniform(0.012, 0.015), d.uniform(0.0045, 0.006), 0.008
    outer = ring + band
    shank = length - blade - 1.5 * outer
    for k, sign in enumerate((1, -1)):
        yaw = sign * opening
        c, s = math.cos(yaw), math.sin(yaw)
        z = 0.001 + 0.002 * k
        for name, start, stop, width in (
            ("blade", -shank, blade * 0.7, bw / 2),
            ("tip", blade * 0.7, blade, bw / 3.2),
        ):
            mid = (start + stop) / 2
            half = ((stop - start) / 2, width, 0.001)
            d.box(f"{name}_{k}", half, (c * mid, s * mid, z), "metal", "silver", yaw=yaw)
        end = (-c * shank, -s * shank)
        loop = (end[0] - 0.5 * outer, -sign * 0.8 * outer)
        dx, dy = loop[0] - end[0], loop[1] - end[1]
        dist = math.hypot(dx, dy)
        f = (dist - ring) / (2 * dist)
        mid = (end[0] + dx * f, end[1] + dy * f)
        d.slab(
            f"bridge_{k}",
            (dist * f, 0.0035, thick * 0.4),
            0.0,
            "plastic",
            handle,
            xy=mid,
            yaw=math.atan2(dy, dx),
        )
        d.flat_ring(
            f"loop_{k}",
            ring + band / 2,
            band,
            thick,
            0.0,
            "plastic",
            handle,
            center=loop,
            segments=10,
        )
    d.upright("pivot", 0.0035, 0.0008, 0.005, "metal", "gray", visual_only=True)
    return Traits((handle, "silver"), "metal", "elongated")


@generator(
    "scotch_tape",
    size=(0.045, 0.16),
    synonyms=("scotch tape", "sticky tape", "adhesive tape", "tape roll"),
)
def scotch_tape(d: Design) -> Traits:
    tape = d.choice(["transparent", "transparent", "beige", "pink", "blue", "yellow", "green"])
    core = d.choice(["white", "beige", "red", "blue"])
    width = d.uniform(0.012, 0.02)
    rc, wound = d.uniform(0.0125, 0.019), d.uniform(0.005, 0.012)
    if d.rng.random() < 0.65:  # a loose roll lying flat
        d.wall("core", rc, 0.0015, width, 0.0, "paper", core, segments=16)
        d.wall("tape", rc + 0.0015, wound, width, 0.0, "plastic", tape, segments=16)
        return Traits((tape, core), "plastic", "ring")
    body = d.choice(["black", "gray", "blue", "red", "pink"])
    R, lx, base_t = rc + 0.0015 + wound, d.uniform(0.1, 0.14), d.uniform(0.012, 0.018)
    ly = width + 0.012
    d.slab("base", (lx / 2, ly / 2, base_t / 2), 0.0, "plastic", body)
    roll_x, roll_z = -lx / 2 + R + 0.006, base_t + R + 0.001
    for sign in (-1, 1):
        cheek = (R * 0.8, 0.003, R / 2)
        d.slab(
            f"cheek_{sign}", cheek, base_t, "plastic", body, xy=(roll_x, sign * (ly / 2 - 0.003))
        )
    d.rod("roll", R, width, (roll_x, 0, roll_z), "plastic", tape, axis="y")
    d.rod("core", rc, width + 0.001, (roll_x, 0, roll_z), "paper", core, axis="y", visual_only=True)
    nose_x, nose_h = lx / 2 - 0.015, R * 1.2
    d.slab("nose", (0.015, ly / 2, nose_h / 2), base_t, "plastic", body, xy=(nose_x, 0))
    cutter = (lx / 2 - 0.002, 0, base_t + nose_h + 0.002)
    d.box("cutter", (0.002, width / 2 + 0.002, 0.002), cutter, "metal", "silver")
    run = cutter[0] - roll_x
    strip = (roll_x + run / 2, 0, base_t + nose_h + 0.0003 + (roll_z + R - base_t - nose_h) / 2)
    tilt = math.atan2(roll_z + R - base_t - nose_h, run)
    d.add(
        "strip",
        "box",
        (run / 2, width / 2, 0.0003),
        strip,
        "plastic",
        tape,
        quat=axis_angle_quat((0, 1, 0), tilt),
        visual_only=True,
    )
    return Traits((body, tape), "plastic", "elongated")


@generator("magnifier", size=(0.13, 0.26), synonyms=("magnifying glass", "magnifier", "hand lens"))
def magnifier(d: Design) -> Traits:
    rim = d.choice(["black", "silver", "golden", "gray"])
    handle = d.choice(["black", "brown", "red", "blue", "silver"])
    handle_mat = {"brown": "wood", "silver": "metal"}.get(handle, "plastic")
    rl, rh = d.uniform(0.024, 0.036), d.uniform(0.0075, 0.0105)
    hr, t = 2 * rh * d.uniform(0.7, 0.95), 0.003
    rim_mat = "metal" if rim in ("silver", "golden") else "plastic"
    d.wall("rim", rl, t, hr, 0.0, rim_mat, rim, segments=20)
    d.upright("lens", rl + 0.0005, 0.004, hr / 2 - 0.002, "glass", "transparent")
    neck = 0.012
    d.slab("neck", (neck / 2, 0.005, hr / 2), 0.0, rim_mat, rim, xy=(rl + t + neck / 2, 0))
    length = d.uniform(0.08, 0.12)
    x0 = rl + t + neck
    d.rod("ferrule", rh + 0.0008, 0.008, (x0 + 0.004, 0, rh), "metal", rim)
    d.rod(
        "handle",
        rh,
        length,
        (x0 + 0.008 + length / 2, 0, rh),
        handle_mat,
        handle,
        capsule=True,
        solid_fraction=0.6 if handle_mat == "metal" else 1.0,
    )
    return Traits((handle, rim), "glass", "irregular")


@generator(
    "cutter_knife", size=(0.13, 0.2), synonyms=("box cutter", "utility knife", "cutter knife")
)
def cutter_knife(d: Design) -> Traits:
    color = d.choice(["yellow", "orange", "blue", "black", "red", "green"])
    grip = "gray" if color == "black" else "black"
    lx, w, t = d.uniform(0.125, 0.16), d.uniform(0.017, 0.025), d.uniform(0.011, 0.015)
    d.slab("body", (lx / 2, w / 2, t / 2), 0.0, "plastic", color, solid_fraction=0.7)
    grip_half = (lx * 0.2, w / 2 + 0.0004, t / 2 + 0.0004)
    d.box("grip", grip_half, (-lx * 0.22, 0, t / 2), "rubber", grip, visual_only=True)
    d.box(
        "track",
        (lx * 0.2, w * 0.12, 0.0004),
        (lx * 0.22, 0, t + 0.0004),
        "metal",
        "silver",
        visual_only=True,
    )
    d.slab("slider", (0.007, w * 0.3, 0.0015), t, "plastic", grip, xy=(lx * d.uniform(0.1, 0.3), 0))
    ext = d.uniform(0.01, 0.025)
    d.box("blade", (ext / 2, w * 0.3, 0.0004), (lx / 2 + ext / 2, 0, t / 2), "metal", "silver")
    tip = (lx / 2 + ext, w * 0.05, t / 2)
    d.box("blade_tip", (w * 0.35, 0.002, 0.0004), tip, "metal", "silver", yaw=1.0, visual_only=True)
    return Traits((color, grip), "plastic", "elongated")


@generator("stamp", size=(0.05, 0.1), synonyms=("rubber stamp", "ink stamp"), revision=3)
def stamp_3(d: Design) -> Traits:
    """Revision 3: the classic rubber stamp: a turned wooden handle (a round knob on a slim
    waisted neck and a collar) on a grained wooden block, a white index label on top printed
    with the stamp's framed red imprint, and a thick red rubber die on a gray foam cushion
    under the block (the first's boxy self-inking stamp read as a mailbox)."""
    ink = d.choice(["red", "red", "blue", "black", "purple"])
    wood = d.choice(["brown", "brown", "beige"])
    knob = d.choice([wood, wood, "black", "red"])
    knob_mat = "wood" if knob == wood else "plastic"
    lx, ly = d.uniform(0.045, 0.058), d.uniform(0.026, 0.034)
    block = d.uniform(0.013, 0.017)
    die, foam = d.uniform(0.004, 0.005), 0.002
    d.slab("die", (lx / 2 - 0.0008, ly / 2 - 0.0008, die / 2), 0.0, "rubber", "red")
    d.slab("foam", (lx / 2 - 0.0012, ly / 2 - 0.0012, foam / 2), die, "rubber", "gray")
    z = die + foam
    d.slab("block", (lx / 2, ly / 2, block / 2), z, "wood", wood)
    z += block
    # the index label: the stamp's imprint framed in its ink
    d.slab("label", (lx * 0.42, ly * 0.4, 0.0002), z, "paper", "white", visual_only=True)
    fx, fy = lx * 0.36, ly * 0.32
    for k, sign in enumerate((-1, 1)):
        d.slab(
            f"imprint_x{k}",
            (0.0006, fy, 0.0002),
            z + 0.0002,
            "paper",
            ink,
            xy=(sign * fx, 0),
            visual_only=True,
        )
        d.slab(
            f"imprint_y{k}",
            (fx, 0.0006, 0.0002),
            z + 0.0002,
            "paper",
            ink,
            xy=(0, sign * fy),
            visual_only=True,
        )
    for j, (frac, y) in enumerate(((0.7, 0.35), (0.5, -0.3))):
        d.slab(
            f"imprint_line_{j}",
            (fx * frac, fy * 0.16, 0.0002),
            z + 0.0002,
            "paper",
            ink,
            xy=(0, y * fy),
            visual_only=True,
        )
    # the turned handle
    d.upright("collar", 0.0105, 0.004, z, knob_mat, knob)
    neck = d.uniform(0.026, 0.032)
    d.upright("neck", 0.0062, neck, z + 0.004, knob_mat, knob)
    d.ellipsoid("waist", (0.0085, 0.0085, 0.007), (0, 0, z + 0.006), knob_mat, knob)
    kr = d.uniform(0.0125, 0.015)
    top = z + 0.004 + neck
    d.ellipsoid("knob", (kr, kr, kr * 0.78), (0, 0, top + kr * 0.45), knob_mat, knob)
    colors = (wood,) if knob == wood else (wood, knob)
    return Traits(colors, "wood", "T-shape")


@generator(
    "staples_box", size=(0.05, 0.085), synonyms=("box of staples", "staples box"), revision=3
)
def staples_box_3(d: Design) -> Traits:
    """Revision 3: a small closed carton printed with a big staple, and a strip of staples
    lying in front of it on its legs, the single staples marked across it (the open box of
    silver rows read as a toaster)."""
    color = d.choice(["red", "blue", "yellow", "green", "black", "orange"])
    label = "white" if color != "white" else "black"
    lx, ly, h = d.uniform(0.05, 0.062), d.uniform(0.026, 0.032), d.uniform(0.016, 0.02)
    d.slab("carton", (lx / 2, ly / 2, h / 2), 0.0, "paper", color, solid_fraction=0.6)
    d.box(
        "flap",
        (0.0006, ly / 2 + 0.0004, h * 0.42),
        (lx / 2 - 0.004, 0, h / 2),
        "paper",
        label,
        visual_only=True,
    )
    picture = Texture("badge", (label, "silver"), "staple")
    d.box(
        "staple_print",
        (ly * 0.42, ly * 0.42, 0.0002),
        (-lx * 0.12, 0, h + 0.0002),
        "paper",
        color,
        visual_only=True,
        texture=picture,
    )
    front = Texture("sticker_words_staples", (label, "silver"), "staple")
    d.box(
        "front_print",
        (lx * 0.42, 0.0002, h * 0.38),
        (0, ly / 2 + 0.0002, h / 2),
        "paper",
        color,
        visual_only=True,
        texture=front,
    )
    strips = d.choice([1, 2])
    crown, leg = 0.0127, 0.006
    for k in range(strips):  # strips of staples in front, crowns up
        length = d.uniform(0.03, 0.042)
        x = -lx / 2 + length / 2 + k * 0.008
        y = ly / 2 + 0.005 + crown / 2 + k * (crown + 0.003)
        d.slab(
            f"strip_{k}",
            (length / 2, crown / 2, 0.00045),
            leg - 0.0009,
            "metal",
            "silver",
            xy=(x, y),
        )
        for j, s in enumerate((-1, 1)):
            d.slab(
                f"strip_{k}_leg_{j}",
                (length / 2, 0.00045, (leg - 0.0009) / 2),
                0.0,
                "metal",
                "silver",
                xy=(x, y + s * (crown / 2 - 0.00045)),
            )
        for j in range(int(length / 0.0025)):  # the joins between single staples
            sx = x - length / 2 + (j + 1) * 0.0025
            if sx < x + length / 2 - 0.001:
                d.box(
                    f"strip_{k}_seam_{j}",
                    (0.00015, crown / 2, 0.0002),
                    (sx, y, leg + 0.0001),
                    "metal",
                    "gray",
                    visual_only=True,
                )
    return Traits((color, "silver"), "paper", "cuboid")


@generator(
    "sticky_notes",
    size=(0.05, 0.1),
    synonyms=("sticky notes", "post-it notes", "sticky pad"),
    revision=3,
)
def sticky_notes_3(d: Design) -> Traits:
    """Revision 3: a square pad of canary-yellow (or bright orange or green) sticky notes,
    its sheets showing as fine lines round its sides, the top note glued along its far
    edge and curling up off the pad towards the viewer; often a second pad of another
    colour under it, turned and offset so its corners peek out (the first's plain pastel
    stacks read as napkins, its scribbles and steep peeled sheet as a notepad)."""
    first = d.choice(["yellow", "yellow", "yellow", "yellow", "orange", "green"])
    side = d.uniform(0.06, 0.066)  # square; a 0.08 m gripper still closes on it
    thick = d.uniform(0.008, 0.011)
    z0 = 0.0
    colors = [first]
    if d.rng.random() < 0.5:  # a second pad under it, turned, its corners showing
        second = d.choice([c for c in ("pink", "blue", "green", "orange") if c != first])
        colors.append(second)
        under = d.uniform(0.006, 0.008)
        yaw = d.choice([-1, 1]) * d.uniform(0.25, 0.38)
        d.slab(
            "second_pad",
            (side / 2 - 0.003, side / 2 - 0.003, under / 2),
            0.0,
            "paper",
            second,
            xy=(d.uniform(0.005, 0.008), d.uniform(0.004, 0.007)),
            yaw=yaw,
        )
        z0 = under
    d.slab("pad", (side / 2, side / 2, thick / 2), z0, "paper", first)
    for k in range(1, 5):  # the sheets' edges on the sides the viewer sees
        z = z0 + thick * k / 5
        for j, (hx, hy, x, y) in enumerate(
            ((side / 2 + 0.0002, 0.00015, 0, side / 2), (0.00015, side / 2 + 0.0002, side / 2, 0))
        ):
            d.box(
                f"sheet_edge_{k}_{j}",
                (hx, hy, 0.00014),
                (x, y, z),
                "paper",
                "white",
                visual_only=True,
            )
    top = z0 + thick
    glue = side * 0.22  # the glued band along -x stays flat
    z = top + 0.0003
    d.box("glued_band", (glue / 2, side / 2, 0.0003), (-side / 2 + glue / 2, 0, z), "paper", first)
    # the free part curls up towards +x in two bends
    lift, curl = d.uniform(0.08, 0.11), d.uniform(0.3, 0.42)
    free = side - glue
    first_len, end_len = free * 0.62, free * 0.38
    x0 = -side / 2 + glue
    cx = x0 + math.cos(lift) * first_len / 2
    cz = z + math.sin(lift) * first_len / 2
    d.add(
        "lifted_note",
        "box",
        (first_len / 2, side / 2, 0.0003),
        (cx, 0.0, cz),
        "paper",
        first,
        quat=axis_angle_quat((0, 1, 0), -lift),
        visual_only=True,
    )
    x1, z1 = x0 + math.cos(lift) * first_len, z + math.sin(lift) * first_len
    d.add(
        "curled_end",
        "box",
        (end_len / 2, side / 2, 0.0003),
        (x1 + math.cos(curl) * end_len / 2, 0.0, z1 + math.sin(curl) * end_len / 2),
        "paper",
        first,
        quat=axis_angle_quat((0, 1, 0), -curl),
        visual_only=True,
    )
    return Traits(tuple(colors), "paper", "cuboid")
