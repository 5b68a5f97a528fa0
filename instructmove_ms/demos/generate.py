"""Resumable, parallel demo generation: planned rollouts recorded with ManiSkill's
``RecordEpisode``.

Demos go into shards under ``out_dir/shards/``. Shard ``i`` tries the seeds
``seed0 + i * SEED_BLOCK`` onwards until it has kept its share of demos, so its content does
not depend on how many workers run or in which order shards finish. A shard (trajectory
``.h5`` + ``.json`` and a sidecar ``.episodes.json`` with every kept episode's EpisodeSpec and
per-step stage flags) is written into a staging folder and moved into place; then the
ledger ``<task>_<robot>.ledger.json`` (written atomically) records it with its seed and
failure counts. Each seed is one scene, played as ``synthesis.synthesize_scene`` does (a
slipped grasp is tried again with the next plan; only the kept rollout is recorded). A
shard missing from the ledger is unfinished and is redone, so an interruption loses at most
the shards in flight and never duplicates a demo. The finished shards are merged into
``out_dir/<task>_<robot>.h5`` + ``.json`` + ``.episodes.json``. A run holds the output
folder's lock (a second run on it is refused, naming the first) and first removes the
staging folders a killed run left.
"""

from __future__ import annotations

import functools
import json
import os
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import gymnasium as gym
from mani_skill.trajectory.merge_trajectory import merge_trajectories
from mani_skill.utils.wrappers import RecordEpisode
from tqdm import tqdm

from instructmove_ms.executor import Workers, worker_state
from instructmove_ms.files import OutputLock, clean_stale, staging, write_json
from instructmove_ms.perturbation import levels_text, parse_levels
from instructmove_ms.sampler import SAMPLER, SAMPLERS
from instructmove_ms.splits import is_training_seed
from instructmove_ms.tasks import TASKS
from instructmove_ms.validation import check_choice

from .synthesis import FAILURES, synthesize, synthesize_scene

SHARD_SIZE = 5  # kept demos per shard
SEED_BLOCK = 1000  # seeds reserved for each shard

Progress = Callable[[str | None], None]  # called per seed tried: None (kept) or the failure


@dataclass
class Report:
    """Outcome of a (possibly resumed) run: demos kept, seeds (scenes) tried, rollouts run
    (``synthesize_scene``), failures by reason (of the scenes left out)."""

    kept: int
    tried: int
    rollouts: int = 0
    failures: dict[str, int] = field(default_factory=dict)
    path: Path | None = None

    @property
    def rate(self) -> float:
        """Valid-synthesis rate: kept demos per seed tried."""
        return self.kept / max(1, self.tried)


@dataclass(frozen=True)
class Job:
    """One shard to record: its index and name, the first seed and how many demos to keep."""

    task: str
    robot: str
    out: Path
    index: int
    name: str
    seed: int
    want: int
    perturbation: tuple[tuple[str, int], ...] = ()  # (axis, level) pairs
    sampler: int = SAMPLER  # the sampler that draws the scenes (``sampler.SAMPLERS``)


class _Shared(gym.Wrapper):
    """A worker's env under one shard's recorder: closing the recorder leaves it open for
    the worker's next shard."""

    def close(self) -> None:
        pass


def _make_env(
    task: str, robot: str, perturbation: tuple[tuple[str, int], ...], sampler: int
) -> gym.Env:
    extra = {"perturbation": dict(perturbation)} if perturbation else {}
    return gym.make(
        task,
        robot_uids=robot,
        sampler=sampler,
        obs_mode="state",
        control_mode="pd_joint_pos",
        render_backend="cpu",  # recorded into env_kwargs: replay to visual modes needs it
        **extra,
    )


def _record(job: Job, folder: Path, progress: Progress) -> tuple[list[dict], Counter[str], int]:
    """Try the job's seeds until it has kept ``job.want`` demos, recording them into
    ``folder/<job.name>.h5`` with this worker's env of the task; returns the sidecar
    entries, the failure counts and the number of rollouts run (``synthesize_scene``: only
    a scene's successful rollout is kept)."""
    make = functools.partial(_make_env, job.task, job.robot, job.perturbation, job.sampler)
    token = f"demos {job.task} {job.robot} {levels_text(dict(job.perturbation))} {job.sampler}"
    env = RecordEpisode(
        _Shared(worker_state(token, make)),
        str(folder),
        trajectory_name=job.name,
        save_video=False,
        save_on_reset=False,
        source_type="motion_planning",
        source_desc="instructmove_ms.demos: OMPL plans checked with fcl, run with pd_joint_pos",
    )
    episodes: list[dict] = []
    failures: Counter[str] = Counter()
    rollouts = 0
    try:
        for seed in range(job.seed, job.seed + SEED_BLOCK):
            if len(episodes) == job.want:
                break
            scene = synthesize_scene(
                env, seed, lambda: env.flush_trajectory(save=False), synthesize
            )
            rollouts += scene.rollouts
            failure = scene.failure
            if failure is None:
                env.flush_trajectory()
                stages = {k: [f[k] for f in scene.flags] for k in scene.flags[0]}
                spec = env.unwrapped.episode.to_dict()
                episodes.append(
                    {"seed": seed, "variant": scene.variant, "spec": spec, "stages": stages}
                )
            else:
                failures[failure] += 1
                if scene.flags:
                    env.flush_trajectory(save=False)
            progress(failure)
        else:
            raise RuntimeError(
                f"{job.task} with {job.robot}: only {len(episodes)} of {job.want} demos from "
                f"{SEED_BLOCK} seeds ({dict(failures)}); synthesis fails too often"
            )
    finally:
        env.close()
    return episodes, failures, rollouts


def run_job(job: Job, progress: Progress) -> dict:
    """Record one shard atomically into ``job.out/shards``; returns its ledger entry."""
    shards = job.out / "shards"
    with staging(job.out) as tmp:
        episodes, failures, rollouts = _record(job, tmp, progress)
        write_json(tmp / f"{job.name}.episodes.json", episodes)
        for suffix in (".h5", ".json", ".episodes.json"):
            os.replace(tmp / f"{job.name}{suffix}", shards / f"{job.name}{suffix}")
    tried = len(episodes) + sum(failures.values())
    return {
        "index": job.index,
        "name": job.name,
        "kept": len(episodes),
        "tried": tried,
        "rollouts": rollouts,
        "failures": dict(failures),
    }


def _pending(ledger: dict, task: str, robot: str, out: Path, n: int) -> list[Job]:
    """The shards still to record for ``n`` demos: the lowest free indices, in order."""
    size = ledger["shard_size"]
    done = {s["index"] for s in ledger["shards"]}
    remaining = n - sum(s["kept"] for s in ledger["shards"])
    jobs, index = [], 0
    while remaining > 0:
        if index not in done:
            want = min(size, remaining)
            seed = ledger["seed0"] + index * SEED_BLOCK
            if not is_training_seed(seed + SEED_BLOCK - 1):
                raise ValueError(f"seed block {seed}.. leaves the training seeds")
            name = f"{task}_{robot}_{index:05d}"
            levels = tuple(ledger.get("perturbation", {}).items())
            sampler = ledger.get("sampler", 1)
            jobs.append(Job(task, robot, out, index, name, seed, want, levels, sampler))
            remaining -= want
        index += 1
    return jobs


def generate(
    task: str,
    robot: str,
    n: int,
    out_dir: str | Path,
    seed0: int = 0,
    workers: Workers | int = 1,
    shard_size: int = SHARD_SIZE,
    perturbation: dict[str, int] | str | None = None,
    sampler: int = SAMPLER,
) -> Report:
    """Write ``n`` successful demos of ``task`` with ``robot`` into ``out_dir`` (see the module
    docstring) with ``workers`` (local processes or a Ray cluster, see ``executor``),
    ``shard_size`` demos per shard, their scenes drawn by ``sampler`` at the ``perturbation``
    levels (recorded in each spec), resuming from its ledger (which fixes ``seed0``,
    ``shard_size``, the perturbation and the sampler)."""
    levels = parse_levels(perturbation)
    check_choice("sampler", sampler, SAMPLERS)
    check_choice("task", task, TASKS)
    check_choice("robot", robot, TASKS[task].supported_robots)
    workers = Workers.of(workers)
    for name, value in (("n", n), ("shard_size", shard_size)):
        if value < 1:
            raise ValueError(f"{name} must be at least 1, got {value}")
    out = Path(out_dir)
    stem = f"{task}_{robot}"  # no dot: ManiSkill names replays after the first dot
    with OutputLock(out, f"instructmove demos generate {stem}"):
        clean_stale(out)  # what a killed run left
        (out / "shards").mkdir(parents=True, exist_ok=True)
        report = _generate(task, robot, n, out, stem, seed0, workers, shard_size, levels, sampler)
        clean_stale(out)  # what a worker killed mid-shard left (its shard ran again)
        return report


def _generate(
    task: str,
    robot: str,
    n: int,
    out: Path,
    stem: str,
    seed0: int,
    workers: Workers,
    shard_size: int,
    levels: dict[str, int],
    sampler: int,
) -> Report:
    ledger_path = out / f"{stem}.ledger.json"
    ledger = (
        json.loads(ledger_path.read_text())
        if ledger_path.exists()
        else {"seed0": seed0, "shard_size": shard_size, "shards": [], "sampler": sampler}
    )
    if levels and not ledger["shards"]:
        ledger["perturbation"] = levels
    ledger.setdefault("sampler", 1)  # a ledger written before samplers were named
    given = (
        ("seed0", seed0),
        ("shard_size", shard_size),
        ("perturbation", levels),
        ("sampler", sampler),
    )
    for key, value in given:
        if ledger.get(key, {}) != value:
            raise ValueError(
                f"{ledger_path} was started with {key}={ledger.get(key, {})}, not {value}"
            )
    jobs = _pending(ledger, task, robot, out, n)
    kept = sum(s["kept"] for s in ledger["shards"])
    with tqdm(total=n, initial=kept, desc=stem, unit="demo") as bar:
        tried = Counter()

        def tick(failure: str | None) -> None:
            tried[failure is None] += 1
            bar.update(failure is None)
            bar.set_postfix(rate=f"{tried[True] / sum(tried.values()):.0%}")

        def finished(entry: dict) -> None:
            ledger["shards"].append(entry)
            ledger["shards"].sort(key=lambda s: s["index"])
            write_json(ledger_path, ledger)

        for _, entry in workers.run(run_job, jobs, tick, folder=out):
            finished(entry)  # the ledger is updated as each shard lands
    path = out / f"{stem}.h5"
    if jobs or not (out / f"{stem}.episodes.json").exists():  # the merge's last file
        _merge(out, stem, [s["name"] for s in ledger["shards"]])
    failures = Counter()
    for shard in ledger["shards"]:
        failures.update(shard["failures"])
    return Report(
        sum(s["kept"] for s in ledger["shards"]),
        sum(s["tried"] for s in ledger["shards"]),
        sum(s.get("rollouts", s["tried"]) for s in ledger["shards"]),
        {k: failures.get(k, 0) for k in FAILURES},
        path,
    )


def _merge(out: Path, stem: str, names: list[str]) -> None:
    """Merge the shards into ``out/<stem>.h5`` + ``.json`` + ``.episodes.json``, each moved
    into place when complete (the sidecar last)."""
    with staging(out) as tmp:
        merged = tmp / f"{stem}.h5"
        merge_trajectories(str(merged), [str(out / "shards" / f"{name}.h5") for name in names])
        os.replace(merged, out / merged.name)
        os.replace(merged.with_suffix(".json"), out / f"{stem}.json")
    sidecar = []
    for name in names:
        sidecar += json.loads((out / "shards" / f"{name}.episodes.json").read_text())
    write_json(
        out / f"{stem}.episodes.json", [{"episode_id": k, **e} for k, e in enumerate(sidecar)]
    )
