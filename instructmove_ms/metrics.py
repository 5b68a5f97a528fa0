"""Episode scores and aggregates: stage metrics, grounding vs control errors, intervals.

Stage flags are latched in the env, so the last step's info of an episode holds its
result; the family's ``StageSchema`` says which flags are its stages. Aggregates report
rates with Wilson 95% intervals and the paper's table format, the family's stages then the
score: ``Reach/Lift (S)`` (pick) or ``ReachPick/LiftPick/ReachPlace/Place (S)``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import asdict, dataclass, field

from .assets.catalog import Catalog
from .episode import EpisodeSpec
from .family import StageSchema

SHARED_ATTRIBUTES = ("category", "color", "shape", "material", "size")


@dataclass(frozen=True)
class EpisodeResult:
    """One scored episode."""

    family: str
    robot: str
    split: str
    condition: str
    seed: int
    num_goals: int
    stages: dict[str, bool]
    success: bool
    stage_score: float
    any_reach: bool
    any_lift: bool
    grounding_error: bool  # a distractor was reached or lifted first
    control_error: bool  # the right object was reached, the task not completed
    shared: tuple[str, ...] = field(default=())  # attributes a wrong choice shares with target
    #: the success condition held at the last step (None: not known, the run ended early)
    success_at_end: bool | None = None
    #: what the policy went for first (lifted, else reached): the instruction's ``target``,
    #: the ``original`` target the scene was made for (another than the instruction's under
    #: the alternative_target condition), another ``candidate``, or ``none``
    choice: str = "none"

    @classmethod
    def failed(cls, spec: EpisodeSpec, stages: StageSchema) -> EpisodeResult:
        """The score of an episode the policy failed: nothing achieved."""
        return cls.of(
            spec,
            stages=dict.fromkeys(stages.names, False),
            success=False,
            stage_score=0.0,
            any_reach=False,
            any_lift=False,
            grounding_error=False,
            control_error=False,
            success_at_end=False,
        )

    @classmethod
    def of(cls, spec: EpisodeSpec, **scores) -> EpisodeResult:
        """The result of episode ``spec`` with the given stages and scores."""
        return cls(
            family=spec.family,
            robot=spec.robot,
            split=spec.split,
            condition=spec.condition,
            seed=spec.seed,
            num_goals=spec.num_goals,
            **scores,
        )

    def to_dict(self) -> dict:
        return asdict(self)


def _value(info: dict, key: str):
    value = info[key]
    return value.reshape(-1)[0].item() if hasattr(value, "reshape") else value


def shared_attributes(catalog: Catalog, spec: EpisodeSpec, wrong: int) -> tuple[str, ...]:
    """Which annotated attributes object ``wrong`` shares with the target."""
    a, b = catalog[spec.objects[wrong].uuid], catalog[spec.objects[spec.target].uuid]
    shared = [
        k for k in ("category", "shape", "material", "size") if getattr(a, k) == getattr(b, k)
    ]
    if set(a.colors) & set(b.colors):
        shared.append("color")
    return tuple(k for k in SHARED_ATTRIBUTES if k in shared)


def score_episode(
    spec: EpisodeSpec, info: dict, stages: StageSchema, catalog: Catalog
) -> EpisodeResult:
    """Score an episode of a family with ``stages`` from the info of its last step."""
    flags = {k: bool(_value(info, k)) for k in stages.names}
    first = [int(_value(info, k)) for k in ("reached_object", "lifted_object")]
    wrong = next((k for k in first if k >= 0 and k != spec.target), -1)
    went = first[1] if first[1] >= 0 else first[0]
    has_target = spec.target >= 0
    grounding = has_target and wrong >= 0
    reached = flags[stages.reached]
    success = bool(_value(info, "success"))
    return EpisodeResult.of(
        spec,
        stages=flags,
        success=success,
        stage_score=float(_value(info, "stage_score")),
        any_reach=bool(_value(info, "any_reach")),
        any_lift=bool(_value(info, "any_lift")),
        grounding_error=grounding,
        control_error=has_target and reached and not success and not grounding,
        shared=shared_attributes(catalog, spec, wrong) if grounding else (),
        success_at_end=bool(_value(info, "success_now")) if "success_now" in info else None,
        choice=choice(spec, went),
    )


def choice(spec: EpisodeSpec, k: int) -> str:
    """What object ``k`` is to episode ``spec`` (see ``EpisodeResult.choice``)."""
    if k < 0:
        return "none"
    if k == spec.target:
        return "target"
    if spec.objects[k].role == "target":  # the scene's own target, not the instruction's
        return "original"
    return "candidate"


def wilson(successes: float, n: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a binomial rate (95% by default); ``successes`` may be a
    sum of scores in [0, 1]."""
    if n == 0:
        return (0.0, 1.0)
    p = successes / n
    denom = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denom
    return (max(0.0, centre - half), min(1.0, centre + half))


def aggregate(
    results: Iterable[EpisodeResult],
    keys: tuple[str, ...] = ("family", "robot", "split", "condition"),
) -> list[dict]:
    """Rates with Wilson intervals per group of ``keys`` (a group holds one family's
    episodes; ``stages`` lists its stage names, each with its rate)."""
    groups: dict[tuple, list[EpisodeResult]] = {}
    for r in results:
        groups.setdefault(tuple(getattr(r, k) for k in keys), []).append(r)
    rows = []
    for key, group in sorted(groups.items()):
        n = len(group)
        row = dict(zip(keys, key, strict=True), episodes=n, stages=list(group[0].stages))
        rates = {s: sum(r.stages[s] for r in group) for s in row["stages"]}
        rates.update(
            success=sum(r.success for r in group),
            any_reach=sum(r.any_reach for r in group),
            any_lift=sum(r.any_lift for r in group),
            grounding_error=sum(r.grounding_error for r in group),
            control_error=sum(r.control_error for r in group),
        )
        known = [r.success_at_end for r in group if r.success_at_end is not None]
        for name, k in rates.items():
            row[name] = k / n
            row[f"{name}_ci"] = wilson(k, n)
        if known:
            row["success_at_end"] = sum(known) / len(known)
            row["success_at_end_ci"] = wilson(sum(known), len(known))
        if row.get("condition") == "alternative_target":
            # of the episodes that went for one of the two, those that took the object the
            # instruction names rather than the one the scene was made for
            followed, original = (sum(r.choice == c for r in group) for c in ("target", "original"))
            row["language_following"] = followed / max(1, followed + original)
            row["language_following_ci"] = wilson(followed, followed + original)
        row["stage_score"] = sum(r.stage_score for r in group) / n
        # S averages scores in [0, 1], whose variance is at most S (1 - S): the Wilson
        # interval of the rate S over n episodes holds it (conservatively)
        row["stage_score_ci"] = wilson(row["stage_score"] * n, n)
        row["chance"] = sum(1.0 / r.num_goals for r in group) / n
        rows.append(row)
    return rows


def paper_cell(row: dict) -> str:
    """The group's stage rates and score: ``Reach/Lift (S)`` for a pick family."""
    return "/".join(f"{row[s]:.2f}" for s in row["stages"]) + f" ({row['stage_score']:.2f})"


def markdown_table(
    rows: list[dict], keys: tuple[str, ...] = ("family", "robot", "split", "condition")
) -> str:
    """The aggregates as a markdown table in the paper's format, with any-object reach and
    lift (the scores of the no-target conditions), the error split, success at the end of
    the horizon and (alternative_target) the language-following rate."""
    head = (
        *keys,
        "episodes",
        "stages (S)",
        "S [95% CI]",
        "success [95% CI]",
        "any reach / lift",
        "grounding errors",
        "control errors",
        "success at end",
        "language following [95% CI]",
    )
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for row in rows:
        cells = [
            *(str(row[k]) for k in keys),
            str(row["episodes"]),
            paper_cell(row),
            _rate(row, "stage_score"),
            _rate(row, "success"),
            f"{row['any_reach']:.2f} / {row['any_lift']:.2f}",
            f"{row['grounding_error']:.2f}",
            f"{row['control_error']:.2f}",
            f"{row['success_at_end']:.2f}" if "success_at_end" in row else "-",
            _rate(row, "language_following"),
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _rate(row: dict, name: str) -> str:
    """``rate [lo, hi]`` of ``name`` in ``row``, or "-" where the group has none."""
    if name not in row:
        return "-"
    lo, hi = row[f"{name}_ci"]
    return f"{row[name]:.2f} [{lo:.2f}, {hi:.2f}]"


def comparison_table(
    runs: dict[str, list[dict]], keys: tuple[str, ...] = ("family", "robot", "split", "condition")
) -> str:
    """Several policies side by side: one row per group of ``keys``, one ``Reach/Lift (S)``
    column per policy (``runs`` maps a policy name to its aggregate rows), and chance
    (1/|G|, what a policy that ignores the instruction reaches)."""
    cells: dict[tuple, dict[str, str]] = {}
    chance: dict[tuple, float] = {}
    for policy, rows in runs.items():
        for row in rows:
            key = tuple(row[k] for k in keys)
            cells.setdefault(key, {})[policy] = paper_cell(row)
            chance[key] = row["chance"]
    head = (*keys, *runs, "chance (1/G)")
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for key in sorted(cells):
        row = [*map(str, key), *(cells[key].get(p, "-") for p in runs), f"{chance[key]:.2f}"]
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)
