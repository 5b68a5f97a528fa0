"""Fruits, ingredients and beverages."""

from __future__ import annotations

import math

from ..design import Design, Traits
from ..parts import X_TO_Z, axis_angle_quat, quat_mul
from ..textures import Texture
from .registry import generator
from .reprints import reprint


@generator("apple", size=(0.055, 0.09), revision=3)
def apple_3(d: Design) -> Traits:
    """Revision 3: a smooth red or green apple, wider than tall: broad shoulders round a
    dimple at the top with the stalk sunk in it, tapering to a smaller dimpled base (the
    first, a faceted ball, read as a pear or an Asian pear when yellow with a leaf)."""
    color = d.choice(["red", "red", "green"])
    r = d.uniform(0.033, 0.037)  # half the width
    # the body: rings of smooth spheres round the axis, (ring radius, height, sphere radius)
    # in half widths, from the shoulders (their inner sides meeting round the dimple) down
    # to a narrower base that rests on a dimpled ring
    rings = ((0.38, 1.1, 0.62), (0.34, 0.9, 0.6), (0.29, 0.7, 0.55), (0.22, 0.52, 0.46))
    squat = d.uniform(0.94, 1.04)  # taller or squatter
    fill = 0.1  # the spheres overlap: the union holds about a tenth of their volume
    turn = d.uniform(0, math.pi)
    for j, (ring, z, s) in enumerate(rings):
        for k in range(12):
            a = turn + 2 * math.pi * k / 12
            center = (r * ring * math.cos(a), r * ring * math.sin(a), r * (0.5 + (z - 0.5) * squat))
            d.sphere(f"lobe_{j}_{k}", r * s, center, "organic", color, solid_fraction=fill)
    top_z, s, ring = r * (0.5 + 0.6 * squat), r * 0.62, r * 0.38
    height = top_z + s
    # a disc hidden at the widest, where fingers close round the apple
    d.upright("core", r - 0.003, 0.006, top_z - 0.003, "organic", color, solid_fraction=fill)
    dimple = top_z + math.sqrt(s * s - ring * ring)  # where the shoulders meet on the axis
    # the stalk, sunk in the dimple and leaning a little
    length, tilt = d.uniform(0.016, 0.022), d.uniform(0.12, 0.35)
    quat = quat_mul(axis_angle_quat((0, 1, 0), tilt), X_TO_Z)
    root = dimple - 0.004
    center = (math.sin(tilt) * length / 2, 0.0, root + math.cos(tilt) * length / 2)
    d.add("stalk", "cylinder", (0.0018, length / 2), center, "organic", "brown", quat=quat)
    if d.rng.random() < 0.35:  # a leaf on the stalk, lying back over the shoulder
        yaw = d.uniform(2.2, 4.0)
        reach = 0.017
        pos = (reach * math.cos(yaw), reach * math.sin(yaw), height + 0.001)
        d.add(
            "apple_leaf",
            "ellipsoid",
            (0.016, 0.007, 0.0012),
            pos,
            "organic",
            "green",
            quat=quat_mul(axis_angle_quat((0, 0, 1), yaw), axis_angle_quat((0, 1, 0), 0.2)),
        )
    return Traits((color,), "organic", "sphere")


@generator("lemon", size=(0.06, 0.1), revision=3)
def lemon_3(d: Design) -> Traits:
    """Revision 3: a bright yellow lemon lying on its side along y (seen side on from the
    front): an oval a little longer than wide that tapers at each end, to a pointed nipple
    at one end and a small stalk end with a brown scar at the other (the first, an
    egg-like oval that was sometimes green, seen end on, read as a lime)."""
    color = "yellow"
    a = d.uniform(0.031, 0.036)  # half the body's length (along y)
    b = a / d.uniform(1.1, 1.18)  # its half width
    c = b * 0.96  # its half height (it rests a little flattened)
    d.ellipsoid("body", (b, a, c), (0, 0, c), "organic", color)
    for k, s in enumerate((1, -1)):  # the ends taper
        d.ellipsoid(
            f"taper_{k}", (b * 0.5, a * 0.5, c * 0.5), (0, s * a * 0.62, c), "organic", color
        )
    reach = a * 1.12  # where the tapers end
    d.ellipsoid("nipple", (0.0042, 0.0065, 0.0042), (0, reach + 0.0012, c), "organic", color)
    d.ellipsoid("stalk_end", (0.0045, 0.003, 0.0045), (0, -reach + 0.0004, c), "organic", color)
    d.rod(
        "stem_scar",
        0.002,
        0.001,
        (0, -reach - 0.0017, c),
        "organic",
        "brown",
        axis="y",
        visual_only=True,
    )
    return Traits((color,), "organic", "ellipsoid")


#: A banana's half thickness (the apothem of its five-sided section) at the joints of its
#: body, in parts of the thickest, from the blossom tip to the neck before the stalk.
BANANA_TAPER = (0.36, 0.66, 0.86, 0.97, 1.0, 0.99, 0.93, 0.8, 0.6)


def _matrix_quat(x, y, z) -> tuple[float, float, float, float]:
    """The rotation (w, x, y, z) that turns the local axes into the orthonormal ``x``, ``y``,
    ``z``."""
    m = ((x[0], y[0], z[0]), (x[1], y[1], z[1]), (x[2], y[2], z[2]))
    w = math.sqrt(max(1.0 + m[0][0] + m[1][1] + m[2][2], 1e-12)) / 2
    if w > 0.1:
        return (
            w,
            (m[2][1] - m[1][2]) / (4 * w),
            (m[0][2] - m[2][0]) / (4 * w),
            (m[1][0] - m[0][1]) / (4 * w),
        )
    k = max(range(3), key=lambda i: m[i][i])
    i, j = (k + 1) % 3, (k + 2) % 3
    s = math.sqrt(max(1.0 + m[k][k] - m[i][i] - m[j][j], 1e-12)) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[0] = (m[j][i] - m[i][j]) / s
    q[1 + k] = s / 4
    q[1 + i] = (m[i][k] + m[k][i]) / s
    q[1 + j] = (m[j][k] + m[k][j]) / s
    return tuple(q)


def _loft(d: Design, name: str, joints, color: str, colors=None) -> None:
    """A five-sided prism bent and tapered along ``joints`` ((point, horizontal heading,
    apothem) on its axis): between each two joints, five flat face slabs half the apothem
    thick from section to section (a flat face down, a ridge on top), so that the faces run
    on without steps; ``colors`` gives a colour per span."""

    def face(point, heading, apothem, i):
        side = (-math.sin(heading), math.cos(heading))
        t = 2 * math.pi * i / 5  # face 0 faces down
        n = (side[0] * math.sin(t), side[1] * math.sin(t), -math.cos(t))
        return tuple(p + apothem * v for p, v in zip(point, n, strict=True)), n

    for k in range(len(joints) - 1):
        (p0, h0, a0), (p1, h1, a1) = joints[k], joints[k + 1]
        apothem = (a0 + a1) / 2
        width, thick = 2 * apothem * math.tan(math.pi / 5), apothem / 2
        for i in range(5):
            q0, n0 = face(p0, h0, a0, i)
            q1, n1 = face(p1, h1, a1, i)
            u = [b - a for a, b in zip(q0, q1, strict=True)]
            length = math.sqrt(sum(v * v for v in u))
            u = [v / length for v in u]
            n = [a + b for a, b in zip(n0, n1, strict=True)]
            dot = sum(a * b for a, b in zip(n, u, strict=True))
            z = [a - dot * b for a, b in zip(n, u, strict=True)]
            norm = math.sqrt(sum(v * v for v in z))
            z = [v / norm for v in z]
            y = (z[1] * u[2] - z[2] * u[1], z[2] * u[0] - z[0] * u[2], z[0] * u[1] - z[1] * u[0])
            center = [(a + b) / 2 - c * thick / 2 for a, b, c in zip(q0, q1, z, strict=True)]
            d.add(
                f"{name}_{k}_{i}",
                "box",
                (length / 2 + 0.0003, width / 2, thick / 2),
                center,
                "organic",
                colors[k] if colors else color,
                quat=_matrix_quat(u, y, z),
            )


@generator("banana", size=(0.12, 0.22), revision=3)
def banana_3(d: Design) -> Traits:
    """Revision 3: a banana lying on its side along y: a curved, angular fruit of five flat
    sides with ridges between them, thick in the middle and tapering to a dark blossom tip
    at one end and through a narrow neck into a tapered five-sided stalk ending in a dark
    cut stub at the other; ripe yellow, yellow freckled with brown, or yellow still green at
    both ends (the first, smooth capsules, read as a cucumber or a courgette when green)."""
    ripeness = d.choice(["yellow", "yellow", "spotted", "spotted", "green_ends"])
    color = "yellow"
    ends = "green" if ripeness == "green_ends" else color
    thick = d.uniform(0.0145, 0.0175)  # the thickest apothem
    arc = d.uniform(0.1, 0.13)  # radius of the curve
    sweep = d.uniform(0.95, 1.15)
    n = len(BANANA_TAPER) - 1

    def at(a: float) -> tuple[tuple[float, float], float]:
        """The point on the arc at angle ``a`` and the heading there: along y, the ends
        towards +x (seen from the front, the whole curve shows)."""
        return (arc * (1 - math.cos(a)), arc * math.sin(a)), math.atan2(math.cos(a), math.sin(a))

    joints = []
    for k, taper in enumerate(BANANA_TAPER):
        (x, y), heading = at(-sweep / 2 + sweep * k / n)
        apothem = thick * taper
        joints.append(((x, y, apothem), heading, apothem))
    spans = [ends if k in (0, n - 1) else color for k in range(n)]
    _loft(d, "side", joints, color, spans)
    # the stalk, straight on from the neck, narrowing and then slimmer still
    (x, y, z), heading, neck = joints[-1]
    ahead = (math.cos(heading), math.sin(heading))
    stalk = thick * 0.34
    length = d.uniform(0.016, 0.022)
    stalk_joints = [joints[-1]]
    for dist, apothem in ((0.007, stalk * 1.05), (length, stalk)):
        stalk_joints.append(((x + ahead[0] * dist, y + ahead[1] * dist, z), heading, apothem))
    _loft(d, "stalk", stalk_joints, ends)
    end = stalk_joints[-1][0]
    d.add(
        "stub",
        "cylinder",
        (stalk * 1.12, 0.0018),
        (end[0] + ahead[0] * 0.0012, end[1] + ahead[1] * 0.0012, z),
        "organic",
        "brown",
        quat=axis_angle_quat((0, 0, 1), heading),
    )
    # the blossom tip: a dark nub on the thin end
    (x, y, z), heading, tip = joints[0]
    back = (-math.cos(heading), -math.sin(heading))
    d.add(
        "blossom_tip",
        "ellipsoid",
        (0.005, tip * 0.8, tip * 0.8),
        (x + back[0] * 0.0015, y + back[1] * 0.0015, z),
        "organic",
        "black",
        quat=axis_angle_quat((0, 0, 1), heading),
    )
    if ripeness == "spotted":  # brown freckles on the upper faces
        for k in range(d.choice([4, 5, 6])):
            j = d.uniform(1.0, n - 1.5)
            (p, heading, apothem) = joints[int(j)]
            t = 2 * math.pi * d.choice([2, 3, 1, 4]) / 5
            side = (-math.sin(heading), math.cos(heading))
            along = (j - int(j)) * sweep / n * arc
            pos = (
                p[0] + side[0] * math.sin(t) * apothem + math.cos(heading) * along,
                p[1] + side[1] * math.sin(t) * apothem + math.sin(heading) * along,
                p[2] - math.cos(t) * apothem,
            )
            size = d.uniform(0.0015, 0.0025)
            d.sphere(f"freckle_{k}", size, pos, "organic", "brown", visual_only=True)
    return Traits((color,) if ends == color else (color, ends), "organic", "elongated")


@generator("tomato", size=(0.05, 0.09), revision=3)
def tomato_3(d: Design) -> Traits:
    """Revision 3: a ripe red tomato: smooth round lobes bulging round a flattened body
    (a dimple at the top), a green star-shaped calyx of pointed sepals lying over the
    shoulders and a short stem (the first, a plain ellipsoid that was sometimes orange,
    read as an orange)."""
    color = "red"
    r = d.uniform(0.03, 0.038)  # the half width
    lobes = d.choice([5, 6, 6, 7])
    s = r * d.uniform(0.74, 0.8)  # each lobe a smooth sphere round the axis
    ring = r - s
    h = s * d.uniform(0.97, 1.0)
    turn = d.uniform(0, math.pi)
    for k in range(lobes):
        a = turn + 2 * math.pi * k / lobes
        center = (ring * math.cos(a), ring * math.sin(a), h)
        d.sphere(f"lobe_{k}", s, center, "organic", color, solid_fraction=1.3 / lobes)
    top = h + math.sqrt(s * s - ring * ring)  # the dimple where the lobes meet
    d.ellipsoid(
        "core", (ring * 1.6, ring * 1.6, s * 0.95), (0, 0, h), "organic", color, solid_fraction=0.3
    )
    # the calyx: pointed sepals curling down over the shoulders from the stem
    sepals = d.choice([5, 6])
    reach = r * d.uniform(0.42, 0.5)
    spin = d.uniform(0, math.pi)
    for k in range(sepals):
        a = spin + 2 * math.pi * k / sepals + d.uniform(-0.15, 0.15)
        u = (math.cos(a), math.sin(a))
        tip = reach * d.uniform(0.85, 1.1)

        def over(rho: float, lift: float, u=u) -> tuple[float, float, float]:
            """A point ``lift`` above the skin, ``rho`` out from the axis towards ``u``."""
            z = h + math.sqrt(max(s * s - (rho - ring) ** 2, 0.0)) + lift
            return (u[0] * rho, u[1] * rho, z)

        mid = over(ring * 1.2, 0.0012)
        d.segment(
            f"sepal_{k}",
            "ellipsoid",
            over(0.0, 0.002),
            mid,
            (0.004, 0.001),
            "organic",
            "green",
            visual_only=True,
        )
        d.segment(
            f"sepal_tip_{k}",
            "ellipsoid",
            mid,
            over(tip, 0.0006),
            (0.003, 0.0008),
            "organic",
            "green",
            visual_only=True,
        )
    d.upright("calyx", 0.0045, 0.002, top, "organic", "green", visual_only=True)
    d.upright("stem", 0.0018, d.uniform(0.006, 0.01), top + 0.001, "organic", "green")
    return Traits((color,), "organic", "sphere")


@generator("egg", size=(0.045, 0.07), revision=3)
def egg_3(d: Design) -> Traits:
    """Revision 3: a whole egg standing in a short, low egg cup, its narrow end up: blunt
    below, tapering to a rounded point, nearly all of it above the cup's flared rim (the
    first, a plain ellipsoid lying on its side, read as a kiwi or a coconut when brown; a
    tall cup holding half the egg, as an egg cup)."""
    color = d.choice(["white", "beige", "brown"])
    cup = d.choice([c for c in ("white", "white", "yellow", "blue", "red", "green") if c != color])
    r = d.uniform(0.0175, 0.0195)
    d.upright("cup_foot", r * 0.9, 0.0025, 0.0, "ceramic", cup)
    d.upright("cup_stem", r * 0.5, 0.003, 0.0025, "ceramic", cup)
    base = 0.0055
    d.upright("cup_floor", r * 0.75, 0.0025, base, "ceramic", cup)
    rim = r * d.uniform(0.45, 0.6)  # the egg shows four fifths of its height above it
    d.wall("cup", r * 0.75, 0.002, rim, base, "ceramic", cup, segments=18, flare=0.35)
    z0 = base + 0.0025 + 1.15 * r
    d.ellipsoid("shell", (r, r, 1.15 * r), (0, 0, z0), "organic", color)
    d.ellipsoid("shell_top", (0.93 * r, 0.93 * r, 1.3 * r), (0, 0, z0 + 0.15 * r), "organic", color)
    return Traits((color, cup), "organic", "ellipsoid")


@generator(
    "canned_coke", size=(0.1, 0.14), synonyms=("can of coke", "soda can", "coke can"), revision=3
)
@reprint("cola")
def canned_coke(d: Design) -> Traits:
    color = d.choice(["red", "red", "silver", "black", "blue"])
    r = d.uniform(0.031, 0.034)
    h = d.uniform(0.105, 0.125)
    ribbon = Texture("wave", ("red" if color == "silver" else "white",))
    d.upright("body", r, h - 0.012, 0.006, "aluminium", color, solid_fraction=0.38, texture=ribbon)
    d.upright("bottom_rim", r * 0.9, 0.006, 0.0, "aluminium", "silver")
    d.upright("top_rim", r * 0.92, 0.006, h - 0.006, "aluminium", "silver")
    d.box("tab", (0.01, 0.005, 0.0008), (0.008, 0, h + 0.0008), "aluminium", "silver")
    colors = (color,) if color == "silver" else (color, "silver")
    return Traits(colors, "metal", "cylinder")


#: Soft drinks: (liquid seen through the clear bottle, label, ink, word pattern, caps).
SOFT_DRINKS = (
    ("brown", "red", "white", "wrap_cola", ("red", "red", "white", "black")),
    ("brown", "red", "white", "wrap_soda", ("red", "white")),
    ("orange", "blue", "white", "wrap_soda", ("orange", "blue", "white")),
    ("green", "yellow", "green", "wrap_lemonade", ("green", "yellow", "white")),
    ("transparent", "blue", "white", "wrap_soda", ("blue", "white")),
)


@generator(
    "beverage_bottle",
    size=(0.14, 0.26),
    synonyms=("drink bottle", "beverage bottle", "soft drink bottle"),
    revision=3,
)
def beverage_bottle_3(d: Design) -> Traits:
    """Revision 3: a plastic soft-drink bottle: the drink filling it to the shoulder (cola
    brown, orange, lemon green), a wide wrap-round label printed COLA or SODA, ribs above
    and below it, a clear shoulder and short neck with its ring, and a ribbed screw cap
    (the first, a slim coloured bottle with a long neck, read as a beer, wine or hot sauce
    bottle)."""
    liquid, label, ink, word, caps = d.choice(SOFT_DRINKS)
    cap = d.choice(list(caps))
    r = d.uniform(0.03, 0.034)
    h = d.uniform(0.2, 0.235)
    body_h = h * 0.6
    d.upright("body", r, body_h, 0.0, "plastic", liquid, solid_fraction=0.95)
    d.upright("base_ring", r * 0.93, 0.004, 0.0, "plastic", liquid, visual_only=True)
    label_h = body_h * 0.42
    label_z = body_h * 0.4
    quat = X_TO_Z  # the word towards +x (a turn about z would widen its bounds)
    d.add(
        "label",
        "cylinder",
        (r + 0.001, label_h / 2),
        (0, 0, label_z + label_h / 2),
        "paper",
        label,
        quat=quat,
        visual_only=True,
        texture=Texture(word, (ink,)),
    )
    for k, z in enumerate((body_h * 0.12, body_h * 0.24, body_h * 0.9)):
        d.upright(f"rib_{k}", r + 0.0007, 0.0025, z, "plastic", liquid, visual_only=True)
    shoulder = h * 0.2
    d.ellipsoid(
        "shoulder", (r, r, shoulder), (0, 0, body_h), "plastic", "transparent", solid_fraction=0.3
    )
    neck_z = body_h + shoulder * 0.85
    cap_h = 0.016
    d.upright("neck", 0.0125, h - neck_z - cap_h, neck_z, "plastic", "transparent")
    d.upright("neck_ring", 0.0165, 0.0018, h - cap_h - 0.005, "plastic", "transparent")
    d.upright("cap", 0.0148, cap_h, h - cap_h, "plastic", cap)
    for k in range(12):
        a = 2 * math.pi * k / 12
        d.box(
            f"cap_rib_{k}",
            (0.0006, 0.0009, cap_h * 0.4),
            (0.0149 * math.cos(a), 0.0149 * math.sin(a), h - cap_h * 0.5),
            "plastic",
            cap,
            yaw=a,
            visual_only=True,
        )
    colors = (liquid, label) if liquid != "transparent" else (label, "transparent")
    return Traits(colors, "plastic", "cylinder")
