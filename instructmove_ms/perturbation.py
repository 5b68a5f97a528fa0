"""Perturbation axes: named, leveled domain randomization of a stored scene.

Each axis has levels 0 (none) to 3 (strong), declared once in ``LEVELS``. ``perturb`` draws
an axis's values from the episode's seed (so the same scene can be run at every level and a
perturbed episode rebuilds bit for bit) and stores them in ``EpisodeSpec.perturbation``:
``{"levels": {axis: level}, axis: values, ...}``. Axes that change the spec itself
(``robot_init``, ``layout``, ``language``, ``distractors``) rewrite its joints, poses,
instruction or objects; the others (``lighting``, ``table``, ``background``, ``camera``)
are values the env renders.

Nothing the instruction relies on moves: the stored objects (colour, material, size) stay;
a jittered layout keeps the clearance, the workspace and the family's cue (the verifier
checks the relation again); a paraphrase must still single out the goal, and so must the
scene with more distractors. An axis and level that cannot keep an episode
text-indispensable raises ``PerturbationError``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from .episode import EpisodeSpec, ObjectSpec
from .layout import Placement, Workspace, corners, gap, random_placement
from .sampler import RoleError, RoleSpec, more_members, symmetric, with_constraints

#: The axes, in the order a sweep runs them.
AXES = (
    "lighting",
    "table",
    "background",
    "camera",
    "robot_init",
    "layout",
    "language",
    "distractors",
)
MAX_LEVEL = 3
#: How many draws a spec-changing axis tries before it refuses the episode.
ATTEMPTS = 32
#: How many moves the layout axis tries for one object before it leaves it in place.
TRIES_PER_OBJECT = 16
#: How many places the distractors axis tries for an added object, and how many draws of
#: objects for each number it tries to add.
TRIES_PER_PLACE = 256
DRAWS_PER_COUNT = 8

#: Every level's numbers, per axis (index = level; level 0 changes nothing).
LEVELS: dict[str, tuple[dict, ...]] = {
    # intensity: scale of the default lights; tilt: degrees the key light's direction
    # turns; kelvin: colour temperature range; extra: added directional lights
    "lighting": (
        {},
        {"intensity": (0.8, 1.25), "tilt": 15.0, "kelvin": (5000, 7500), "extra": 0},
        {"intensity": (0.6, 1.6), "tilt": 30.0, "kelvin": (4000, 9000), "extra": 1},
        {"intensity": (0.4, 2.2), "tilt": 45.0, "kelvin": (3000, 11000), "extra": 2},
    ),
    # tint: largest change of each colour channel; height: table height change, metres;
    # texture: whether the top gets a procedural texture
    "table": (
        {},
        {
            "tint": 0.1,
            "roughness": (0.6, 0.8),
            "metallic": (0.0, 0.0),
            "height": 0.01,
            "texture": False,
        },
        {
            "tint": 0.3,
            "roughness": (0.3, 0.9),
            "metallic": (0.0, 0.2),
            "height": 0.02,
            "texture": False,
        },
        {
            "tint": 0.5,
            "roughness": (0.1, 0.9),
            "metallic": (0.0, 0.5),
            "height": 0.03,
            "texture": True,
        },
    ),
    # floor: largest change of each channel of the floor colour; walls: walls around
    "background": (
        {},
        {"floor": 0.15, "walls": 0},
        {"floor": 0.35, "walls": 1},
        {"floor": 0.5, "walls": 3},
    ),
    # every camera moves this far (cm) and turns this much (degrees), in random directions
    "camera": ({}, {"cm": 1.0, "deg": 1.0}, {"cm": 2.5, "deg": 2.5}, {"cm": 5.0, "deg": 5.0}),
    # Gaussian noise (std, rad) added to the stored arm joints
    "robot_init": ({}, {"std": 0.03}, {"std": 0.06}, {"std": 0.12}),
    # each object moves up to cm and turns up to deg around its stored pose
    "layout": ({}, {"cm": 1.0, "deg": 5.0}, {"cm": 2.0, "deg": 10.0}, {"cm": 4.0, "deg": 20.0}),
    # 1: another template and expression of the same pools; 2: the unseen expression pool;
    # 3: also the grammar's verb synonyms
    "language": (
        {},
        {"pool": "seen", "synonyms": False},
        {"pool": "unseen", "synonyms": False},
        {"pool": "unseen", "synonyms": True},
    ),
    # this many more distractors of the family's own kind, up to the most it allows
    "distractors": ({}, {"add": 1}, {"add": 2}, {"add": 3}),
}


class PerturbationError(ValueError):
    """An axis and level cannot keep an episode text-indispensable."""


def parse_levels(value: str | Mapping[str, int] | None) -> dict[str, int]:
    """``{axis: level}`` of ``"lighting:2,camera:1"`` or a mapping; levels of 0 dropped.
    A ``ValueError`` names an unknown axis or a level outside 0..3."""
    if value is None or value == "":
        return {}
    if isinstance(value, str):
        pairs = {}
        for item in value.split(","):
            axis, sep, level = item.strip().partition(":")
            if not sep or not level.strip().lstrip("-").isdigit():
                raise ValueError(
                    f"perturbation {item.strip()!r} is not AXIS:LEVEL (for example lighting:2)"
                )
            pairs[axis.strip()] = int(level)
        value = pairs
    levels = {}
    for axis, level in dict(value).items():
        if axis not in AXES:
            raise ValueError(f"unknown perturbation axis {axis!r}; axes: {', '.join(AXES)}")
        if not isinstance(level, int | np.integer) or not 0 <= level <= MAX_LEVEL:
            raise ValueError(f"perturbation level {level!r} of {axis!r} outside 0..{MAX_LEVEL}")
        if level:
            levels[axis] = int(level)
    return {a: levels[a] for a in AXES if a in levels}


def levels_text(levels: Mapping[str, int]) -> str:
    """``"lighting:2,camera:1"`` (``"none"`` for no perturbation)."""
    return ",".join(f"{a}:{v}" for a, v in levels.items()) or "none"


def _rng(spec: EpisodeSpec, axis: str, level: int, attempt: int = 0) -> np.random.Generator:
    return np.random.default_rng([spec.seed, AXES.index(axis), level, attempt])


def kelvin_rgb(kelvin: float) -> list[float]:
    """The RGB colour (peak 1) of a black body at ``kelvin``, by the usual fit to the
    CIE tables (valid 1000-40000 K)."""
    t = kelvin / 100.0
    r = 255.0 if t <= 66 else 329.7 * (t - 60) ** -0.1332
    g = 99.47 * math.log(t) - 161.12 if t <= 66 else 288.12 * (t - 60) ** -0.0755
    b = 255.0 if t >= 66 else (0.0 if t <= 19 else 138.52 * math.log(t - 10) - 305.04)
    rgb = np.clip([r, g, b], 0, 255) / 255.0
    return [float(c) for c in rgb / rgb.max()]


def _turn(direction, degrees: float, rng: np.random.Generator) -> list[float]:
    """``direction`` turned by ``degrees`` about a random axis perpendicular to it."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    axis = np.cross(d, rng.normal(size=3))
    axis /= np.linalg.norm(axis)
    a = math.radians(degrees)
    turned = d * math.cos(a) + np.cross(axis, d) * math.sin(a)
    return [float(x) for x in turned]


#: ManiSkill's default lights (``BaseEnv._load_lighting``): ambient, then directional.
DEFAULT_AMBIENT = 0.3
DEFAULT_LIGHTS = (((1.0, 1.0, -1.0), True), ((0.0, 0.0, -1.0), False))  # (direction, shadow)
#: A lamp's (point light's) colour scale: about the default lights' brightness on the table.
LAMP_POWER = 1.5


def _lighting(rng: np.random.Generator, p: dict, ctx: Context) -> dict:
    scale = float(rng.uniform(*p["intensity"]))
    color = kelvin_rgb(float(rng.uniform(*p["kelvin"])))
    lights = [
        {
            "direction": _turn(d, p["tilt"] if k == 0 else 0.0, rng),
            "color": [scale * c for c in color],
            "shadow": shadow,
        }
        for k, (d, shadow) in enumerate(DEFAULT_LIGHTS)
    ]
    lamps = [
        {
            "position": [
                float(rng.uniform(-0.2, 0.9)),
                float(rng.uniform(-0.8, 0.8)),
                float(rng.uniform(0.8, 1.5)),
            ],
            "color": [LAMP_POWER * scale * c for c in color],
        }
        for _ in range(p["extra"])
    ]
    return {
        "ambient": [DEFAULT_AMBIENT * scale * c for c in color],
        "lights": lights,
        "lamps": lamps,
    }


def _tint(rng: np.random.Generator, base, amount: float) -> list[float]:
    return [float(np.clip(c + rng.uniform(-amount, amount), 0.02, 0.98)) for c in base]


#: The table's default look (``tasks.scene.build_table``).
TABLE_COLOR = (0.55, 0.40, 0.25)
FLOOR_COLOR = (0.8, 0.8, 0.8)


def _table(rng: np.random.Generator, p: dict, ctx: Context) -> dict:
    values = {
        "color": _tint(rng, TABLE_COLOR, p["tint"]),
        "roughness": float(rng.uniform(*p["roughness"])),
        "metallic": float(rng.uniform(*p["metallic"])),
        "height": float(rng.uniform(-p["height"], p["height"])),
    }
    if p["texture"]:
        values["stripes"] = {
            "color": _tint(rng, values["color"], 0.25),
            "period": int(rng.integers(4, 17)),
        }
    return values


def _background(rng: np.random.Generator, p: dict, ctx: Context) -> dict:
    walls = rng.permutation(3)[: p["walls"]]
    return {
        "floor": _tint(rng, FLOOR_COLOR, p["floor"]),
        "walls": [
            {"side": int(w), "color": [float(c) for c in rng.uniform(0.2, 0.9, 3)]}
            for w in sorted(walls)
        ],
    }


def _random_unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def _camera(rng: np.random.Generator, p: dict, ctx: Context) -> dict:
    """Per camera: an offset of exactly ``cm`` and a turn of exactly ``deg`` about a random
    axis (a quaternion wxyz), both in the camera mount's frame."""
    values = {}
    for uid in ctx.cameras:
        offset = _random_unit(rng) * p["cm"] / 100.0
        axis, half = _random_unit(rng), math.radians(p["deg"]) / 2
        values[uid] = {
            "offset": [float(x) for x in offset],
            "turn": [math.cos(half), *(float(x) * math.sin(half) for x in axis)],
        }
    return values


#: Axes whose values the env renders, and how each is drawn: (rng, level numbers, context).
RENDERED: dict[str, Callable] = {
    "lighting": _lighting,
    "table": _table,
    "background": _background,
    "camera": _camera,
}


@dataclass(frozen=True)
class Context:
    """What spec-changing axes need to know of the scene's env: the family (its cue and
    templates), the catalog, the robot's arm joints (qpos indices) and joint limits
    ((D, 2)), its cameras, where objects may stand, and a check that returns the verifier's
    problems of a spec (empty when it is text-indispensable)."""

    task: object
    catalog: object
    arm: tuple[int, ...]
    limits: np.ndarray
    cameras: tuple[str, ...]
    workspace: Workspace
    problems: Callable[[EpisodeSpec], list[str]]
    #: the spec's instruction said again: (spec, rng, unseen pool?, verb synonyms?) -> text
    rephrase: Callable[[EpisodeSpec, np.random.Generator, bool, bool], str]


def _robot_init(spec: EpisodeSpec, rng, p: dict, ctx: Context) -> tuple[EpisodeSpec, dict]:
    qpos = np.asarray(spec.robot_qpos, float)
    noise = np.zeros_like(qpos)
    noise[list(ctx.arm)] = rng.normal(0.0, p["std"], size=len(ctx.arm))
    moved = np.clip(qpos + noise, ctx.limits[:, 0], ctx.limits[:, 1])
    spec = dataclasses.replace(spec, robot_qpos=tuple(float(q) for q in moved))
    return spec, {"noise": [float(x) for x in moved - qpos]}


def _yaw(q) -> float:
    return 2.0 * math.atan2(q[3], q[0])


def _footprint(ctx: Context, uuid: str) -> tuple[float, float]:
    """Half extents of an instance's footprint padded by half the family's clearance."""
    lo, hi = ctx.catalog[uuid].bounds
    pad = ctx.task.clearance / 2
    return (hi[0] - lo[0]) / 2 + pad, (hi[1] - lo[1]) / 2 + pad


def _layout(spec: EpisodeSpec, rng, p: dict, ctx: Context) -> tuple[EpisodeSpec, dict] | None:
    """Each object in turn moved up to ``cm`` and turned up to ``deg`` around its stored
    pose where it keeps the clearance to every other object and its centre stays in the
    workspace, as the layout engine places them (one hemmed in by its neighbours may move
    less, or stay); None where the verifier refuses the result."""
    ws = ctx.workspace
    halves = [_footprint(ctx, obj.uuid) for obj in spec.objects]
    places = [Placement(obj.pose[0], obj.pose[1], _yaw(obj.pose[3:])) for obj in spec.objects]
    quads = [corners(h, q) for h, q in zip(halves, places, strict=True)]
    for k in rng.permutation(len(places)):
        for _ in range(TRIES_PER_OBJECT):
            r, a = p["cm"] / 100.0 * math.sqrt(rng.uniform()), rng.uniform(-math.pi, math.pi)
            old = places[k]
            place = Placement(
                old.x + r * math.cos(a),
                old.y + r * math.sin(a),
                old.yaw + math.radians(rng.uniform(-p["deg"], p["deg"])),
            )
            quad = corners(halves[k], place)
            inside = ws.x[0] <= place.x <= ws.x[1] and ws.y[0] <= place.y <= ws.y[1]
            if inside and all(gap(quad, q) > 0 for j, q in enumerate(quads) if j != k):
                places[k], quads[k] = place, quad
                break
    objects = tuple(
        dataclasses.replace(
            obj,
            pose=q.pose(obj.pose[2]),
        )
        for obj, q in zip(spec.objects, places, strict=True)
    )
    moved = dataclasses.replace(spec, objects=objects)
    if ctx.problems(moved):
        return None
    moves = [
        [q.x - o.pose[0], q.y - o.pose[1], q.yaw - _yaw(o.pose[3:])]
        for o, q in zip(spec.objects, places, strict=True)
    ]
    return moved, {"moves": [[float(v) for v in m] for m in moves]}


def _group(
    spec: EpisodeSpec, ctx: Context, assigned: dict[str, list], count: int
) -> tuple[RoleSpec | None, dict[str, list]]:
    """(the candidates' group role as the symmetric sampler cast it, ``assigned`` with every
    candidate its member); no role where the cue's group cannot take ``count`` more (a size
    or material told apart between two)."""
    candidates = [ctx.catalog[spec.objects[k].uuid] for k in spec.candidates]
    if ctx.task.cue.group_size(spec.cue, len(candidates) + count) < len(candidates) + count:
        return None, assigned
    roles = with_constraints(ctx.task.roles, "distractor", *ctx.task.cue.rivals(spec.cue))
    group = next(r for r in symmetric(roles, "target", "distractor") if r.name == "target")
    others = {name: members for name, members in assigned.items() if name != "distractor"}
    return group, {**others, "target": candidates}


def _add_distractors(
    spec: EpisodeSpec, rng, count: int, ctx: Context
) -> tuple[EpisodeSpec, dict] | None:
    """``count`` more distractors drawn under the family's distractor role and placed where
    the layout engine would allow them; None where none qualifies, no place is free or the
    verifier refuses the scene. Under the symmetric sampler they join the candidates' group
    (``_group``): what they must differ in, they differ in from every candidate."""
    assigned: dict[str, list] = {}
    for obj in spec.objects:
        assigned.setdefault(obj.role, []).append(ctx.catalog[obj.uuid])
    key = f"{spec.seed}:more:{int(rng.integers(1 << 31))}"
    role = ctx.task.role("distractor")
    if spec.sampler != 1:
        role, assigned = _group(spec, ctx, assigned, count)
        if role is None:
            return None
    try:
        extra = more_members(role, assigned, count, ctx.catalog, spec.split, key, spec.sampler)
    except RoleError:
        return None
    quads = [
        corners(_footprint(ctx, o.uuid), Placement(o.pose[0], o.pose[1], _yaw(o.pose[3:])))
        for o in spec.objects
    ]
    ws, z, added = ctx.workspace, spec.objects[0].pose[2], []
    for inst in extra:
        for _ in range(TRIES_PER_PLACE):
            place = random_placement(rng, ws, inst.back)
            quad = corners(_footprint(ctx, inst.uuid), place)
            if all(gap(quad, q) > 0 for q in quads):
                quads.append(quad)
                added.append(ObjectSpec(inst.uuid, inst.category, "distractor", place.pose(z)))
                break
        else:
            return None
    first = len(spec.objects)
    crowded = dataclasses.replace(
        spec,
        objects=spec.objects + tuple(added),
        candidates=spec.candidates + tuple(range(first, first + len(added))),
    )
    if ctx.problems(crowded):
        return None
    return crowded, {"added": [o.uuid for o in added]}


def _distractors(spec: EpisodeSpec, rng, p: dict, ctx: Context) -> tuple[EpisodeSpec, dict]:
    """Up to ``add`` more distractors: as many as the family allows and the library can
    add while the instruction still singles out the goal (``added`` lists them; it may be
    fewer, or none)."""
    present = sum(o.role == "distractor" for o in spec.objects)
    for count in range(min(p["add"], ctx.task.count_limits["distractor"][1] - present), 0, -1):
        for _ in range(DRAWS_PER_COUNT):
            done = _add_distractors(spec, rng, count, ctx)
            if done is not None:
                return done
    return spec, {"added": []}


def _language(spec: EpisodeSpec, rng, p: dict, ctx: Context) -> tuple[EpisodeSpec, dict] | None:
    if spec.target < 0:  # generic, empty, absent: nothing singles out a goal to rephrase
        return spec, {"original": spec.instruction}
    text = ctx.rephrase(spec, rng, p["pool"] == "unseen", p["synonyms"])
    moved = dataclasses.replace(spec, instruction=text)
    if ctx.problems(moved):
        return None
    return moved, {"original": spec.instruction}


#: Axes that rewrite the spec (joints, poses, instruction); None from one is a refused draw.
REWRITTEN: dict[str, Callable] = {
    "robot_init": _robot_init,
    "layout": _layout,
    "language": _language,
    "distractors": _distractors,
}


def perturb(spec: EpisodeSpec, levels: Mapping[str, int], ctx: Context) -> EpisodeSpec:
    """``spec`` at ``levels`` (see ``parse_levels``); the same spec and levels give the same
    result. A spec that carries a perturbation already is refused."""
    levels = parse_levels(levels)
    if not levels:
        return spec
    if spec.perturbation:
        raise ValueError(
            f"episode seed {spec.seed} is perturbed already "
            f"({levels_text(spec.perturbation['levels'])}); perturb its unperturbed spec"
        )
    record: dict = {"levels": dict(levels)}
    for axis, level in levels.items():
        p = LEVELS[axis][level]
        if axis in RENDERED:
            record[axis] = RENDERED[axis](_rng(spec, axis, level), p, ctx)
        else:
            for attempt in range(ATTEMPTS):
                done = REWRITTEN[axis](spec, _rng(spec, axis, level, attempt), p, ctx)
                if done is not None:
                    spec, record[axis] = done
                    break
            else:
                raise PerturbationError(
                    f"{axis}:{level} cannot keep {spec.family} episode seed {spec.seed} "
                    f"text-indispensable ({ATTEMPTS} draws refused); use a lower level"
                )
    return dataclasses.replace(spec, perturbation=record)


#: How the table in docs/evaluation.md ("Perturbations") says each axis's numbers.
DESCRIBE = {
    "lighting": "intensity x{intensity[0]}-{intensity[1]}, key light turned {tilt:g} deg, "
    "{kelvin[0]}-{kelvin[1]} K, {extra} lamps",
    "table": "colour +-{tint} per channel, roughness {roughness[0]}-{roughness[1]}, metallic "
    "{metallic[0]}-{metallic[1]}, height +-{height} m, stripes: {texture}",
    "background": "floor colour +-{floor} per channel, {walls} walls",
    "camera": "every camera moved {cm:g} cm and turned {deg:g} deg",
    "robot_init": "arm joints + N(0, {std} rad)",
    "layout": "each object up to {cm:g} cm and {deg:g} deg",
    "language": "another template and expression, {pool} pool, verb synonyms: {synonyms}",
    "distractors": "up to {add} more distractors (as many as the family allows)",
}


def levels_markdown() -> str:
    """The declared levels as a markdown table (docs/evaluation.md lists it)."""
    lines = ["| axis | level 1 | level 2 | level 3 |", "|---|---|---|---|"]
    for axis in AXES:
        cells = [DESCRIBE[axis].format(**LEVELS[axis][k]) for k in range(1, MAX_LEVEL + 1)]
        lines.append(f"| `{axis}` | " + " | ".join(cells) + " |")
    return "\n".join(lines)
