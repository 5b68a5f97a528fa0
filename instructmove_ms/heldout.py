"""Held-out evaluation sets: fixed episode specs per family, robot and split.

Evaluation seeds come from ``splits.eval_seed`` (training data and demos use seeds below
``splits.EVAL_SEED_BASE``, so the two never share an episode). The sets ship with the
package under ``tasks/episodes/v<version>/<env id>/<robot>/<split>.jsonl``. Each released
benchmark version is one set version (``BENCHMARKS``): InstructMove 1.0 is set version 7,
drawn by sampler 1; InstructMove 2.0 is set version 8, drawn by the symmetric sampler (2,
``sampler``), the default. Both play on the ``recognisable`` snapshot, said as people say it
(``assets.expressions``). Each episode names its snapshot and its sampler, and an env builds
it from that snapshot. A later benchmark version adds its sets beside these, which stay
loadable (``--set-version``); the pre-release versions 2-6 are in the repository's history
(``git checkout ee264ad``).

A set also exports as a config of ManiSkill's evaluator convention: ``env_info`` (``env_id``,
``max_episode_steps``, ``env_kwargs``) and ``episodes`` of ``{episode_id, reset_kwargs}``,
where ``reset_kwargs = {"seed": seed, "options": {"episode": spec dict}}`` rebuilds the
episode exactly (see ``InstructMoveEnv.reset``).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
from collections.abc import Iterator
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from mani_skill.agents.registration import REGISTERED_AGENTS

from .assets import load_snapshot
from .episode import CONDITIONS, EpisodeSpec
from .files import write_json, write_text
from .perturbation import parse_levels
from .splits import EVAL_SPLITS, eval_seed
from .tasks import TASKS
from .tasks.visibility import hidden_objects, measure
from .validation import check_choice
from .verify import verify

EPISODES_PER_SET = 100
#: Each released benchmark version, by the stored set version that makes it.
BENCHMARKS = {7: "1.0", 8: "2.0"}
#: The stored set versions (``--set-version``) and the one evaluation uses by default.
SET_VERSIONS = tuple(BENCHMARKS)
SET_VERSION = max(SET_VERSIONS)
#: Seeds tried per kept episode at most (seeds whose scenes hide a candidate are skipped).
SEEDS_PER_EPISODE = 5
#: Each version's file of its set files' SHA-256 (``instructmove doctor`` checks them).
CHECKSUMS = "checksums.json"


def benchmark_name(version: int | None = None) -> str:
    """The benchmark version the stored sets of ``version`` (None: the current one) make."""
    version = SET_VERSION if version is None else version
    check_choice("set version", version, SET_VERSIONS)
    return f"InstructMove {BENCHMARKS[version]} (held-out sets v{version})"


def default_folder(version: int | None = None) -> Path:
    """The package's folder of the stored sets of ``version`` (None: the current one)."""
    version = SET_VERSION if version is None else version
    check_choice("set version", version, SET_VERSIONS)
    return Path(str(resources.files("instructmove_ms.tasks").joinpath(f"episodes/v{version}")))


def set_path(
    env_id: str, robot: str, split: str, folder: Path | None = None, version: int | None = None
) -> Path:
    """Where the set (env, robot, split) lies: under ``folder`` if given, else in the
    package's sets of ``version``."""
    return (folder or default_folder(version)) / env_id / robot / f"{split}.jsonl"


def write_set(path: Path, specs: list[EpisodeSpec]) -> Path:
    """Write ``specs`` as JSON lines, atomically."""
    return write_text(path, "".join(spec.to_json() + "\n" for spec in specs))


def checksums(folder: Path) -> dict[str, str]:
    """The SHA-256 of every set file under ``folder``, keyed by its path there."""
    return {
        path.relative_to(folder).as_posix(): hashlib.sha256(path.read_bytes()).hexdigest()
        for path in sorted(folder.glob("*/*/*.jsonl"))
    }


def write_checksums(folder: Path) -> Path:
    """Record the set files' checksums in ``folder``'s ``CHECKSUMS`` file (``episodes write``
    does after writing sets)."""
    return write_json(folder / CHECKSUMS, checksums(folder))


def changed_sets(version: int | None = None) -> list[str]:
    """The stored set files of ``version`` (None: the current one) that differ from the
    checksums they shipped with, are missing or were added: empty where all are intact."""
    folder = default_folder(version)
    shipped = json.loads((folder / CHECKSUMS).read_text())
    found = checksums(folder)
    return sorted(
        name for name in shipped.keys() | found.keys() if shipped.get(name) != found.get(name)
    )


def load_set(
    env_id: str, robot: str, split: str, folder: Path | None = None, version: int | None = None
) -> list[EpisodeSpec]:
    """The stored held-out episodes of (env, robot, split), from ``folder`` or the package's
    sets of ``version``."""
    check_choice("split", split, EVAL_SPLITS)
    path = set_path(env_id, robot, split, folder, version)
    if not path.is_file():
        stored = sorted(
            p.relative_to(path.parents[2]).as_posix() for p in path.parents[2].glob("*/*/*.jsonl")
        )
        raise ValueError(f"no held-out set {env_id}/{robot}/{split}; stored: {stored}")
    return [EpisodeSpec.from_json(line) for line in path.read_text().splitlines() if line]


def generate_set(
    env, count: int = EPISODES_PER_SET, measured: tuple[EpisodeSpec, ...] = ()
) -> Iterator[EpisodeSpec]:
    """``count`` held-out specs of the split ``env`` (a rendering env) was made for: the
    first evaluation seeds whose episodes show every candidate and receptacle to the scene
    cameras, each certified with its visibility figures (``tasks.visibility``). An episode
    of ``measured`` (an earlier version's set) with the same scene lends its figures
    instead of a render: visibility depends on the scene alone."""
    unwrapped = env.unwrapped
    known = {scene_key(s): s.certificate["visibility"] for s in measured}
    kept = 0
    for index in range(count * SEEDS_PER_EPISODE):
        if kept == count:
            return
        seed = eval_seed(unwrapped.split, index)
        spec = unwrapped.sample_episode(seed)
        figures = known.get(scene_key(spec))
        if figures is None:
            env.reset(seed=seed)
            spec, figures = unwrapped.episode, measure(env)
        if not hidden_objects(figures):
            kept += 1
            yield dataclasses.replace(spec, certificate={**spec.certificate, "visibility": figures})
    raise RuntimeError(
        f"only {kept} of {count} {unwrapped.task.env_id} episodes show every candidate in "
        f"{count * SEEDS_PER_EPISODE} seeds"
    )


def scene_key(spec: EpisodeSpec) -> str:
    """What the cameras see of ``spec``'s scene (its robot, objects and poses), as a key."""
    objects = [dataclasses.asdict(o) for o in spec.objects]
    return json.dumps([spec.robot, list(spec.robot_qpos), objects])


@dataclass(frozen=True)
class ConfigEpisode:
    """One episode of an evaluator config: its id, reset seed and spec."""

    episode_id: int | str
    seed: int
    spec: EpisodeSpec


@dataclass(frozen=True)
class EvaluatorConfig:
    """An evaluator config: the env to make and exactly which episodes to run; ``benchmark``
    names the benchmark version its episodes come from (None: not from a stored set)."""

    env_id: str
    max_episode_steps: int
    env_kwargs: dict
    episodes: tuple[ConfigEpisode, ...]
    benchmark: str | None = None

    @property
    def perturbation(self) -> dict[str, int]:
        """The perturbation levels of the config's episodes ({} for none)."""
        return dict(self.episodes[0].spec.perturbation.get("levels", {})) if self.episodes else {}

    def about(self) -> dict:
        """What a number measured on this config must name: the benchmark version, the
        package, the env and its horizon, robot, split, condition, perturbation, episodes,
        their seeds and the asset snapshots they use."""
        from . import __version__

        seeds = sorted(e.seed for e in self.episodes)
        return {
            "benchmark": self.benchmark or "episodes of their own config, not a stored set",
            "package": f"instructmove-ms {__version__}",
            "env": self.env_id,
            "horizon": self.max_episode_steps,
            **{
                key: ", ".join(sorted({str(getattr(e.spec, key)) for e in self.episodes}))
                for key in ("robot", "split", "condition")
            },
            "perturbation": ", ".join(f"{a} {lv}" for a, lv in self.perturbation.items()) or "none",
            "episodes": len(self.episodes),
            "seeds": f"{seeds[0]} to {seeds[-1]}" if seeds else "none",
            "snapshots": ", ".join(sorted({e.spec.snapshot for e in self.episodes})),
        }

    def to_dict(self) -> dict:
        return {
            **({"benchmark": self.benchmark} if self.benchmark else {}),
            "env_info": {
                "env_id": self.env_id,
                "max_episode_steps": self.max_episode_steps,
                "env_kwargs": self.env_kwargs,
            },
            "episodes": [
                {
                    "episode_id": e.episode_id,
                    "reset_kwargs": {"seed": e.seed, "options": {"episode": e.spec.to_dict()}},
                }
                for e in self.episodes
            ],
        }

    @classmethod
    def from_dict(cls, data: dict) -> EvaluatorConfig:
        """The config of ``data``; a ``ValueError`` names what is missing or wrong."""
        try:
            info, items = data["env_info"], data["episodes"]
            check_choice("env_info.env_id", info["env_id"], TASKS)
        except (KeyError, TypeError) as exc:
            raise ValueError(
                f"not an evaluator config: no env_info.env_id or episodes ({exc})"
            ) from None
        episodes = []
        for i, item in enumerate(items):
            episode_id = item.get("episode_id", i)
            reset = item.get("reset_kwargs", {})
            if "episode" not in reset.get("options", {}):
                raise ValueError(
                    f"config episode {episode_id!r} has no reset_kwargs.options.episode: "
                    "InstructMove episodes are given by their spec"
                )
            try:
                spec = EpisodeSpec.from_dict(reset["options"]["episode"])
            except (KeyError, TypeError, ValueError) as exc:
                raise ValueError(f"config episode {episode_id!r}: {exc}") from None
            episodes.append(ConfigEpisode(episode_id, int(reset.get("seed", spec.seed)), spec))
        ids = [e.episode_id for e in episodes]
        if len(set(ids)) != len(ids):
            raise ValueError("config episode ids are not unique")
        return cls(
            env_id=info["env_id"],
            max_episode_steps=int(
                info.get("max_episode_steps", TASKS[info["env_id"]].max_episode_steps)
            ),
            env_kwargs=dict(info.get("env_kwargs", {})),
            episodes=tuple(episodes),
            benchmark=data.get("benchmark"),
        )

    @classmethod
    def from_trajectory(cls, path: str | Path) -> EvaluatorConfig:
        """The episodes of a recorded trajectory (a demo file): each reset to its recorded
        seed and spec, the recording's robot and split, its episode ids."""
        from .export.source import load_trajectory

        traj = load_trajectory(path)
        kwargs = {k: traj.env_kwargs[k] for k in ("robot_uids", "split") if k in traj.env_kwargs}
        return cls(
            env_id=traj.env_id,
            max_episode_steps=TASKS[traj.env_id].max_episode_steps,
            env_kwargs=kwargs,
            episodes=tuple(
                ConfigEpisode(ep.episode_id, ep.seed, EpisodeSpec.from_dict(ep.spec))
                for ep in traj.episodes
            ),
        )

    def write(self, path: Path) -> Path:
        """Write the config as JSON, atomically."""
        return write_json(path, self.to_dict(), indent=2)

    def check(self) -> None:
        """Raise a ``ValueError`` naming the first episode the config's env cannot build:
        one of another family or robot, with an object its snapshot lacks, or one the
        verifier refuses."""
        if not self.episodes:
            raise ValueError("the evaluator config holds no episodes")
        task = TASKS.get(self.env_id)
        robot = self.env_kwargs.get("robot_uids") or (task.default_robot if task else None)
        for e in self.episodes:
            catalog = load_snapshot(e.spec.snapshot)
            if task is not None and e.spec.family != task.family:
                raise ValueError(
                    f"config episode {e.episode_id!r} is a {e.spec.family} episode, "
                    f"not one of {self.env_id} ({task.family})"
                )
            if robot is not None and e.spec.robot != robot:
                raise ValueError(
                    f"config episode {e.episode_id!r} is for robot {e.spec.robot!r}, not {robot!r}"
                )
            for obj in e.spec.objects:
                if obj.uuid not in catalog:
                    raise ValueError(
                        f"config episode {e.episode_id!r}: object {obj.uuid!r} "
                        f"({obj.category}) is not in snapshot {catalog.name!r}"
                    )
            if task is not None and robot is not None:
                opening = REGISTERED_AGENTS[robot].agent_cls.gripper.max_width
                problems = verify(e.spec, catalog, task, opening)
                if problems:
                    raise ValueError(
                        f"config episode {e.episode_id!r} fails the verifier: {'; '.join(problems)}"
                    )

    @classmethod
    def load(cls, path: Path) -> EvaluatorConfig:
        """The config file ``path``; a ``ValueError`` names the file and the fault."""
        try:
            return cls.from_dict(json.loads(Path(path).read_text()))
        except FileNotFoundError:
            raise ValueError(f"{path}: no such evaluator config file") from None
        except (ValueError, AttributeError) as exc:  # JSONDecodeError is a ValueError
            raise ValueError(f"{path}: {exc}") from None


def evaluator_config(
    env_id: str,
    robot: str | None,
    split: str,
    condition: str = "normal",
    episodes: int | None = None,
    folder: Path | None = None,
    perturbation: dict[str, int] | str | None = None,
    version: int | None = None,
) -> EvaluatorConfig:
    """The evaluator config of the first ``episodes`` of the stored set of ``version`` (all
    by default), each re-rendered for ``condition`` (the same scene with that condition's
    instruction) and perturbed at ``perturbation``'s levels (see ``perturbation``)."""
    check_choice("task", env_id, TASKS)
    check_choice("condition", condition, CONDITIONS)
    if episodes is not None and episodes < 1:
        raise ValueError(f"episodes must be at least 1, got {episodes}")
    robot = robot or TASKS[env_id].default_robot
    check_choice("robot", robot, TASKS[env_id].supported_robots)
    specs = load_set(env_id, robot, split, folder, version)[:episodes]
    levels = parse_levels(perturbation)
    if condition != "normal" or levels:
        specs = _respec(env_id, robot, split, condition, levels, specs)
    config = config_of(env_id, robot, split, condition, specs)
    return dataclasses.replace(config, benchmark=benchmark_name(version))


def config_of(
    env_id: str, robot: str, split: str, condition: str, specs: list[EpisodeSpec]
) -> EvaluatorConfig:
    """The evaluator config that plays ``specs`` in this order (episode ids 0, 1, ...)."""
    return EvaluatorConfig(
        env_id=env_id,
        max_episode_steps=TASKS[env_id].max_episode_steps,
        env_kwargs={"robot_uids": robot, "split": split, "condition": condition},
        episodes=tuple(ConfigEpisode(k, s.seed, s) for k, s in enumerate(specs)),
    )


def _respec(
    env_id: str,
    robot: str,
    split: str,
    condition: str,
    levels: dict[str, int],
    specs: list[EpisodeSpec],
) -> list[EpisodeSpec]:
    """``specs`` under ``condition`` at the perturbation ``levels``."""
    import gymnasium as gym

    env = gym.make(env_id, robot_uids=robot, split=split, obs_mode="state", render_backend="none")
    unwrapped = env.unwrapped
    try:
        return [unwrapped.perturbed(unwrapped.under_condition(s, condition), levels) for s in specs]
    finally:
        env.close()
