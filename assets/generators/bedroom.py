"""Bedroom storage and small electronics."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import X_TO_Y, X_TO_Z, axis_angle_quat
from ..textures import Texture
from .registry import generator


def _open_lid(
    d: Design, name, half_x, half_h, thick, hinge, material, color, tilt=0.2, mirror=False
) -> None:
    """A lid hinged along x at ``hinge`` (x, y, z), opened upright and leaning back (-y),
    with a mirror on its inner face if ``mirror``."""
    x, y, z = hinge
    quat = axis_angle_quat((1, 0, 0), tilt)
    pos = (x, y - half_h * math.sin(tilt), z + half_h * math.cos(tilt))
    d.add(name, "box", (half_x, thick / 2, half_h), pos, material, color, quat=quat)
    if mirror:
        out = thick / 2 + 0.0005
        pos = (x, pos[1] + out * math.cos(tilt), pos[2] + out * math.sin(tilt))
        d.add(
            "mirror",
            "box",
            (half_x * 0.75, 0.0005, half_h * 0.7),
            pos,
            "glass",
            "silver",
            quat=quat,
            visual_only=True,
        )


@generator(
    "storage_box",
    size=(0.22, 0.4),
    synonyms=("storage box", "storage bin", "storage container"),
    graspable=False,
    container=True,
    revision=3,
)
def storage_box_3(d: Design) -> Traits:
    """Revision 3: an open moulded plastic storage bin, long and lower than it is long: thin
    walls stiffened by vertical moulded ribs, a thick rolled lip round the top standing out
    from the walls (often in a second colour on a clear or frosted body), a grip ledge with
    a dark hand slot under the lip at each end, and a label plate on the front; open, so its
    interior stays clear (a fabric cube with handle cut-outs read as a storage basket, a
    grey tub with its lid pushed half off as a printer, a hinged lid as a toolbox)."""
    color = d.choice(["transparent", "transparent", "white", "gray", "blue", "pink"])
    lip = d.choice(
        ["blue", "white", "gray", "black", "green"] if color == "transparent" else [color]
    )
    material, t = "plastic", 0.004
    # long along y (across the camera's view), lower than long
    hx, hy = d.uniform(0.1, 0.12), d.uniform(0.14, 0.17)
    h = d.uniform(0.12, 0.16)
    floor = d.open_box("box", (hx, hy), h, t, material, color, full="x")
    lo, lh = 0.007, 0.011  # the lip's overhang and depth
    d.frame("lip", (hx + lo, hy + lo), lo + 0.005, h - lh + 0.002, lh, material, lip)
    # moulded ribs down the long sides and the ends, under the lip
    rib_h = (h - lh - 0.006) / 2
    ribs = d.choice([4, 6])  # an even count: a gap in the middle for the label
    for k, sign in enumerate((-1, 1)):
        for j in range(ribs):
            y = -hy + 0.02 + j * (2 * hy - 0.04) / (ribs - 1)
            d.box(
                f"rib_x{k}_{j}",
                (0.003, 0.003, rib_h),
                (sign * (hx + 0.003), y, 0.006 + rib_h),
                material,
                color,
            )
        for j, x in enumerate((-hx * 0.55, hx * 0.55)):
            d.box(
                f"rib_y{k}_{j}",
                (0.0025, 0.002, rib_h * 0.7),
                (x, sign * (hy + 0.002), 0.006 + rib_h * 0.7),
                material,
                color,
            )
        # a grip ledge under the lip at each end, a dark hand slot in the wall below it
        d.box(
            f"grip_{k}",
            (hx * 0.42, 0.006, 0.003),
            (0, sign * (hy + lo + 0.005), h - lh + 0.003),
            material,
            lip,
        )
        d.box(
            f"hand_slot_{k}",
            (hx * 0.32, 0.0008, 0.007),
            (0, sign * (hy + 0.0008), h - lh - 0.012),
            material,
            "black",
            visual_only=True,
        )
    # a label plate on the front, between the middle ribs
    lw, lz = min(hy * 0.22, (2 * hy - 0.04) / (ribs - 1) / 2 - 0.006), h * 0.45
    d.box(
        "label_plate", (0.0008, lw, 0.016), (hx + 0.0008, 0, lz), "paper", "white", visual_only=True
    )
    d.interior((hx - t - 0.005, hy - t - 0.005), floor_z=floor, rim_z=h)
    colors = (color,) if lip == color else (color, lip)
    return Traits(colors, material, "cuboid")


#: A jewellery box's (material, colour), every build of it.
JEWELRY_BOX_FINISHES = [
    ("wood", "brown"),
    ("wood", "beige"),
    ("leather", "black"),
    ("leather", "red"),
    ("leather", "pink"),
    ("plastic", "white"),
    ("leather", "blue"),
]


@generator(
    "jewelry_box",
    size=(0.1, 0.22),
    synonyms=("jewelry box", "jewellery box", "trinket box"),
    container=True,
    revision=3,
)
def jewelry_box_3(d: Design) -> Traits:
    """Revision 3: an open jewellery box, its hinged lid leaning back with a mirror in it,
    lined in velvet: at the back, velvet ring rolls nearly up to the rim, two or three gold
    or silver rings with a big gem standing in the slits between them; in front, past a low
    divider, a pearl or gold bead necklace coiled on a velvet cushion (an empty box with a
    mirror in its lid and a dark floor read as a wooden box)."""
    material, color = d.choice(JEWELRY_BOX_FINISHES)
    velvet = d.choice([c for c in ("red", "purple", "black", "blue") if c != color])
    hx, hy, h = d.uniform(0.072, 0.085), d.uniform(0.04, 0.047), d.uniform(0.046, 0.052)
    t = 0.006
    floor = d.open_box("base", (hx, hy), h, t, material, color, full="y")
    inner_x, inner_y = hx - t, hy - t
    # the ring rolls at the back (-x): plush velvet rolls along x on a velvet block
    rolls, td = 4, 0.004
    rr = inner_y / rolls
    x0, x1 = -inner_x, -inner_x + d.uniform(0.05, 0.058)
    top = h - 0.003  # the rolls' tops, just under the rim
    block = top - 1.9 * rr
    mid = ((x0 + x1) / 2, 0)
    d.slab(
        "roll_block", ((x1 - x0) / 2, inner_y, (block - floor) / 2), floor, "foam", velvet, xy=mid
    )
    for j in range(rolls):
        center = (mid[0], -inner_y + rr * (2 * j + 1), block + 0.9 * rr)
        d.rod(f"ring_roll_{j}", rr, x1 - x0, center, "foam", velvet, capsule=True)
    # rings standing in the slits between the rolls, their gems up
    metal = d.choice(["golden", "golden", "silver"])
    count = d.choice([2, 3])
    slits = [int(k) for k in d.rng.permutation(rolls - 1)[:count]]
    for k, slit in enumerate(slits):
        y = -inner_y + rr * 2 * (slit + 1)
        x = x0 + (x1 - x0) * (k + 0.5) / count
        ring = d.uniform(0.0085, 0.0095)
        zc = top - ring * 0.1
        angles = [math.radians(-30 + 240 * s / 5) for s in range(6)]
        points = [(x, y + ring * math.cos(a), zc + ring * math.sin(a)) for a in angles]
        for s in range(5):
            d.segment(
                f"ring_{k}_{s}",
                "capsule",
                points[s],
                points[s + 1],
                0.0014,
                "metal",
                metal,
                visual_only=True,
            )
        gem = d.choice(["red", "blue", "green", "purple", "transparent"])
        size = d.uniform(0.0034, 0.004)
        pos = (x, y, zc + ring + size * 0.6)
        stone = "glass" if gem == "transparent" else "stone"
        d.sphere(f"gem_{k}", size, pos, stone, gem, visual_only=True)
    # a low divider, and in front the necklace coiled on a velvet cushion
    d.slab("divider", (td / 2, inner_y, 0.007), floor, material, color, xy=(x1 + td / 2, 0))
    x0, x1 = x1 + td, inner_x
    rim = h - 0.031  # the cushion: the compartment stays deep enough to put things in
    mid = ((x0 + x1) / 2, 0)
    d.slab("cushion", ((x1 - x0) / 2, inner_y, (rim - floor) / 2), floor, "foam", velvet, xy=mid)
    pearl, bead = d.choice([("white", 0.0035), ("golden", 0.003)])
    ax, ay = (x1 - x0) / 2 - bead - 0.004, inner_y - bead - 0.004
    beads = min(20, int(math.pi * (ax + ay) * 0.85 / (2.05 * bead)))
    gap = d.uniform(0, 2 * math.pi)  # where the clasp opens the loop
    look = ("stone", "white") if pearl == "white" else ("metal", "golden")
    for k in range(beads):
        a = gap + 0.3 + (2 * math.pi - 0.6) * k / (beads - 1)
        pos = (mid[0] + ax * math.cos(a), ay * math.sin(a), rim + bead)
        d.sphere(f"bead_{k}", bead, pos, *look, visual_only=True)
    d.box(
        "clasp",
        (0.006, 0.001, 0.005),
        (0, hy + 0.001, h - 0.006),
        "metal",
        "golden",
        visual_only=True,
    )
    _open_lid(d, "lid", hx, hy, 0.008, (0, -hy + 0.004, h), material, color, mirror=True)
    d.interior((ax, ay), floor_z=rim, rim_z=h, center=mid)
    return Traits((color, velvet), material, "cuboid")


@generator(
    "glasses_case", size=(0.14, 0.19), synonyms=("glasses case", "spectacle case"), revision=3
)
def glasses_case_3(d: Design) -> Traits:
    """Revision 3: a hard clamshell case standing open, a pair of round glasses folded inside
    in thick dark rims, with a bridge, hinges and folded temples (the closed first case read
    as a stapler or as nothing at all; thin rims round pink discs as a contact lens case)."""
    material, color, fill = d.choice(
        [
            ("leather", "brown", 0.3),
            ("leather", "black", 0.3),
            ("plastic", "black", 0.3),
            ("plastic", "blue", 0.3),
            ("plastic", "red", 0.3),
            ("aluminium", "silver", 0.08),
        ]
    )
    lining = d.choice(["beige", "gray", "white"] if color != "black" else ["beige", "gray"])
    frame = d.choice([c for c in ("black", "black", "brown", "blue") if c != color])
    length, w = d.uniform(0.15, 0.17), d.uniform(0.054, 0.059)
    hb, t = d.uniform(0.02, 0.024), 0.003
    core = length / 2 - w / 2
    kw = dict(solid_fraction=fill)
    # the lower shell: a floor, two long walls and round ends of boxes (open to see in)
    d.stadium("floor", core, w / 2 - t / 2, 0.0, t, material, color, end_fill=0.5)
    d.box(
        "lining",
        (core, w / 2 - t - 0.001, 0.0004),
        (0, 0, t + 0.0004),
        "fabric",
        lining,
        visual_only=True,
    )
    for k, sign in enumerate((-1, 1)):
        d.box(
            f"wall_{k}",
            (core, t / 2, hb / 2),
            (0, sign * (w / 2 - t / 2), hb / 2),
            material,
            color,
            **kw,
        )
        for j in range(5):
            a = math.pi / 2 - math.pi * (j + 0.5) / 5
            r = w / 2 - t / 2
            pos = (sign * (core + r * math.cos(a)), r * math.sin(a), hb / 2)
            chord = 2 * w / 2 * math.tan(math.pi / 10) * 1.05
            d.box(
                f"end_{k}_{j}",
                (t / 2, chord / 2, hb / 2),
                pos,
                material,
                color,
                yaw=a if sign > 0 else math.pi - a,
                **kw,
            )
    # the lid, open and leaning back on its hinge along the back edge (-y)
    tilt = 1.62  # nearly upright: the case stays narrow enough to grip across
    quat = axis_angle_quat((1, 0, 0), tilt)
    hz = hb * 0.45
    hinge_y, hinge_z = -w / 2, hb
    ux, uz = math.cos(tilt), math.sin(tilt)  # the lid's width axis after the turn
    lid_c = (0, hinge_y + ux * w / 2, hinge_z + uz * w / 2)
    d.add("lid", "ellipsoid", (length / 2, w / 2, hz), lid_c, material, color, quat=quat, **kw)
    d.add("hinge", "cylinder", (0.003, core * 0.5), (0, hinge_y, hinge_z), "metal", "silver")
    # the glasses inside, lenses up: two round lenses in thick rims, a bridge between them,
    # hinge blocks at the outer edges and the temples folded under the lenses
    z = t + 0.0045  # the frame's mid-plane
    fw, ft = 0.0036, 0.003  # the rims' width and depth
    bh = 0.005  # half the bridge
    lens = min((length / 2 - t - 0.008 - bh - 2 * fw) / 2, w / 2 - t - fw - 0.004, 0.022)
    look = ("plastic", frame)
    ghost = dict(visual_only=True)
    for k, sign in enumerate((-1, 1)):
        cx = sign * (bh + fw + lens)
        d.add(
            f"lens_{k}",
            "cylinder",
            (lens, 0.0006),
            (cx, 0, z),
            "glass",
            "transparent",
            quat=X_TO_Z,
            **ghost,
        )
        d.flat_ring(
            f"rim_{k}",
            lens + fw / 2,
            fw,
            ft,
            z - ft / 2,
            *look,
            center=(cx, 0),
            segments=12,
            **ghost,
        )
        hinge_x = sign * (bh + 2 * fw + 2 * lens)
        d.box(
            f"hinge_{k}",
            (0.0022, 0.003, ft / 2 + 0.0004),
            (hinge_x, lens * 0.35, z),
            *look,
            **ghost,
        )
        # the temple, folded: from the hinge across under the lenses
        d.segment(
            f"temple_{k}",
            "box",
            (hinge_x, lens * 0.35 - k * 0.004, z - ft / 2 - 0.0012),
            (-sign * lens * 0.5, lens * 0.15 - k * 0.006, z - ft / 2 - 0.0012),
            (0.0017, 0.001),
            *look,
            **ghost,
        )
    d.box("bridge", (bh + fw * 0.4, 0.002, ft / 2), (0, lens * 0.45, z), *look, **ghost)
    return Traits((color,), material, "ellipsoid")


@generator(
    "pill_organizer",
    size=(0.12, 0.24),
    synonyms=("pill organizer", "pill box", "weekly pill organizer"),
    container=True,
)
def pill_organizer(d: Design) -> Traits:
    body = d.choice(["white", "transparent", "blue", "pink", "purple"])
    lids = d.choice(["rainbow", "transparent", "blue", "pink", "green", "purple"])
    cell, hy, h = d.uniform(0.02, 0.028), d.uniform(0.013, 0.018), d.uniform(0.018, 0.026)
    t = 0.0018
    hx = 3.5 * cell + t / 2
    floor = d.open_box("tray", (hx, hy), h, t, "plastic", body, full="y")
    rainbow = ["red", "orange", "yellow", "green", "blue", "purple", "pink"]
    for k in range(7):
        x = (k - 3) * cell
        if k:
            d.box(
                f"divider_{k}",
                (t / 2, hy - t, (h - t) / 2),
                (x - cell / 2, 0, (h + t) / 2),
                "plastic",
                body,
            )
        color = rainbow[k] if lids == "rainbow" else lids
        _open_lid(
            d,
            f"lid_{k}",
            cell / 2 - 0.001,
            hy,
            0.0015,
            (x, -hy + 0.001, h),
            "plastic",
            color,
            tilt=0.3,
        )
        d.box(f"tab_{k}", (0.003, 0.0015, 0.0012), (x, hy + 0.0015, h - 0.0012), "plastic", body)
    d.interior((cell / 2 - t, hy - t), floor_z=floor, rim_z=h)
    colors = (body,) if lids in ("rainbow", body) else (body, lids)
    return Traits(colors, "plastic", "cuboid")


@generator(
    "remote_holder",
    size=(0.12, 0.26),
    synonyms=("remote holder", "remote control holder", "remote caddy"),
    container=True,
    revision=3,
)
def remote_holder_3(d: Design) -> Traits:
    """Revision 3: an open caddy with TV remotes standing in two of its pockets (the empty
    stepped caddy read as a shelf, a bench or a spice rack); the third pocket stays free."""
    material, color = d.choice(
        [
            ("wood", "brown"),
            ("wood", "beige"),
            ("plastic", "black"),
            ("plastic", "white"),
            ("leather", "black"),
            ("leather", "brown"),
            ("plastic", "gray"),
        ]
    )
    t = 0.006 if material == "wood" else 0.004
    hx, hy = d.uniform(0.075, 0.095), d.uniform(0.028, 0.034)
    back, front = d.uniform(0.085, 0.1), d.uniform(0.05, 0.06)
    d.box("floor", (hx, hy, t / 2), (0, 0, t / 2), material, color)
    d.box("back", (hx, t / 2, back / 2), (0, -hy + t / 2, back / 2), material, color)
    d.box("front", (hx, t / 2, front / 2), (0, hy - t / 2, front / 2), material, color)
    for k, sign in enumerate((-1, 1)):
        d.segment(
            f"side_{k}",
            "box",
            (sign * (hx - t / 2), -hy + t, back - 0.012),
            (sign * (hx - t / 2), hy - t, front - 0.004),
            (t / 2, 0.012),
            material,
            color,
        )
        d.box(
            f"side_low_{k}",
            (t / 2, hy - t, (front - 0.01) / 2),
            (sign * (hx - t / 2), 0, (front - 0.01) / 2),
            material,
            color,
        )
    pocket = (2 * hx - t) / 3  # three pockets across x, the last one (+x) left free
    for k in (1, 2):
        x = -hx + t / 2 + k * pocket
        d.box(
            f"pocket_wall_{k}", (t / 2, hy - t, front * 0.45), (x, 0, front * 0.45), material, color
        )
    remotes = d.choice(
        [["black", "black"], ["black", "gray"], ["gray", "black"], ["black", "silver"]]
    )
    for k, shell in enumerate(remotes):
        x = -hx + t / 2 + (k + 0.5) * pocket
        rl, rw, rt = d.uniform(0.15, 0.175), min(pocket - t - 0.006, 0.045) / 2, 0.0085
        lean = d.uniform(0.04, 0.12)  # leaning back against the back wall
        quat = axis_angle_quat((1, 0, 0), lean)
        c = (x, 0.0, t + rl / 2)
        d.add(
            f"remote_{k}",
            "box",
            (rw, rt, rl / 2),
            c,
            "plastic",
            shell,
            quat=quat,
            solid_fraction=0.4,
        )
        key = "gray" if shell == "black" else "black"

        def face(u, v, name, color, half, c=c, lean=lean, rt=rt, quat=quat):
            """A button on the remote's front face at (across u, up v from its centre)."""
            y = c[1] + (rt + 0.0005) * math.cos(lean) - v * math.sin(lean)
            z = c[2] + v * math.cos(lean) + (rt + 0.0005) * math.sin(lean)
            d.add(name, "box", half, (c[0] + u, y, z), "rubber", color, quat=quat, visual_only=True)

        top = rl / 2 - 0.012
        face(-rw * 0.5, top, f"power_{k}", "red", (0.0035, 0.0006, 0.0025))
        face(0, top - 0.022, f"nav_{k}", key, (rw * 0.55, 0.0006, rw * 0.55))
        face(0, top - 0.022, f"ok_{k}", shell, (rw * 0.22, 0.0009, rw * 0.22))
        for row in range(2):
            for col in (-1, 0, 1):
                face(
                    col * rw * 0.55,
                    top - 0.045 - row * 0.011,
                    f"key_{k}_{row}_{col}",
                    key,
                    (rw * 0.2, 0.0006, 0.0035),
                )
    d.interior(
        (pocket / 2 - t - 0.002, hy - t - 0.002),
        floor_z=t,
        rim_z=front,
        center=(hx - t / 2 - pocket / 2, 0.0),
    )
    return Traits((color,), material, "cuboid")


@generator("flashlight", size=(0.1, 0.25), synonyms=("flashlight", "torch"))
def flashlight(d: Design) -> Traits:
    color = d.choice(["black", "black", "silver", "red", "blue", "yellow", "orange"])
    material = "aluminium" if color in ("black", "silver") else "plastic"
    bezel = d.choice([color, "silver"])
    rb, length = d.uniform(0.011, 0.016), d.uniform(0.11, 0.22)
    apo, head = rb + d.uniform(0.004, 0.01), d.uniform(0.025, 0.04)
    x1 = length / 2 - head / 2
    d.hex_rod("head", apo, head, (x1, 0, apo), material, bezel)  # anti-roll
    d.add(
        "lens",
        "cylinder",
        (apo * 0.85, 0.0006),
        (length / 2 + 0.0006, 0, apo),
        "glass",
        "transparent",
        visual_only=True,
    )
    body = length - head - 0.016
    d.rod("body", rb, body, (x1 - head / 2 - body / 2, 0, apo), material, color, solid_fraction=0.6)
    d.rod("tail_cap", apo, 0.016, (-length / 2 + 0.008, 0, apo), "rubber", "black")
    d.box(
        "switch",
        (0.008, 0.005, 0.002),
        (x1 - head / 2 - 0.015, 0, apo + rb + 0.001),
        "rubber",
        "black",
        visual_only=True,
    )
    colors = (color,) if bezel == color else (color, bezel)
    return Traits(colors, material, "cylinder")


ALARM_CLOCK_COLORS = ["red", "black", "white", "blue", "green", "silver", "pink", "yellow"]


@generator("alarm_clock", size=(0.08, 0.18), synonyms=("alarm clock",), revision=2)
def alarm_clock_2(d: Design) -> Traits:
    """Revision 2: the digital clock is a low wedge with a lit seven-segment time on a dark
    screen and buttons on top (the first read as a radio); the twin-bell clock is unchanged."""
    color = d.choice(ALARM_CLOCK_COLORS)
    if d.rng.random() < 0.5:
        return _digital_clock_2(d, color)
    return _twin_bell_clock(d, color)


def _twin_bell_clock(d: Design, color: str) -> Traits:
    rc, depth, leg = d.uniform(0.04, 0.055), d.uniform(0.032, 0.045), d.uniform(0.01, 0.015)
    zc = leg + rc
    material = "metal" if color == "silver" else d.choice(["metal", "plastic"])
    fill = 0.12 if material == "metal" else 0.4
    d.rod("body", rc, depth, (0, 0, zc), material, color, solid_fraction=fill)
    d.add(
        "face",
        "cylinder",
        (rc * 0.85, 0.0005),
        (depth / 2 + 0.0005, 0, zc),
        "paper",
        "white",
        visual_only=True,
        texture=Texture("dial", ("black",)),
    )
    for k, (hand, angle) in enumerate(((0.5, d.uniform(0, 6.3)), (0.75, d.uniform(0, 6.3)))):
        r = rc * hand / 2
        d.add(
            f"hand_{k}",
            "box",
            (0.0004, 0.0012, r),
            (depth / 2 + 0.0012, -math.sin(angle) * r, zc + math.cos(angle) * r),
            "metal",
            "black",
            quat=axis_angle_quat((1, 0, 0), angle),
            visual_only=True,
        )
    for k, sign in enumerate((-1, 1)):
        d.rod(f"foot_{k}", 0.004, depth, (0, sign * rc * 0.6, 0.004), "metal", "silver")
        d.upright(f"leg_{k}", 0.003, leg, 0.002, "metal", "silver", xy=(0, sign * rc * 0.6))
        d.ellipsoid(
            f"bell_{k}",
            (rc * 0.45, rc * 0.45, rc * 0.32),
            (0, sign * rc * 0.5, zc + rc * 0.85),
            "metal",
            color,
            solid_fraction=0.3,
        )
    d.upright("hammer", 0.003, rc * 0.3, zc + rc * 0.95, "metal", "silver")
    d.add(
        "handle",
        "cylinder",
        (0.0025, rc * 0.4),
        (0, 0, zc + rc * 1.25 + 0.0025),
        "metal",
        "silver",
        quat=X_TO_Y,
    )
    return Traits((color,), material, "cylinder")


def _digital_clock_2(d: Design, color: str) -> Traits:
    """A bedside digital clock facing +x: a body wider than high whose front leans back,
    a black screen with the time lit in red, green, blue or white, two buttons on top."""
    hx, hy, hz = d.uniform(0.022, 0.028), d.uniform(0.06, 0.085), d.uniform(0.024, 0.032)
    d.box("body", (hx, hy, hz), (0, 0, hz), "plastic", color, solid_fraction=0.35)
    lean = 0.3  # the front face leans back by this angle
    face = axis_angle_quat((0, 1, 0), -lean)
    depth = hz * math.tan(lean)
    d.add(
        "front",
        "box",
        (depth / 2, hy, hz / math.cos(lean)),
        (hx + depth / 2 - 0.001, 0, hz),
        "plastic",
        color,
        quat=face,
        solid_fraction=0.35,
    )
    lit = d.choice(["red", "red", "green", "blue", "white"])
    out = depth / 2 + 0.0006  # from the front's centre to the screen's, along its normal
    d.add(
        "screen",
        "box",
        (0.0004, hy * 0.82, hz * 0.62),
        (hx + depth / 2 - 0.001 + out * math.cos(lean), 0, hz + out * math.sin(lean)),
        "plastic",
        "black",
        quat=face,
        visual_only=True,
        texture=Texture("digits", (lit,)),
    )
    button = d.choice(["gray", "silver", "black" if color != "black" else "gray"])
    for k, y in enumerate((-0.45, 0.45)):
        d.box(
            f"button_{k}",
            (hx * 0.35, hy * 0.22, 0.003),
            (0, y * hy, 2 * hz + 0.003),
            "plastic",
            button,
        )
    return Traits((color,), "plastic", "cuboid")
