"""Resumable demo generation: planned picks recorded with ManiSkill's ``RecordEpisode``.

Demos go into shards under ``out_dir/shards/``: each shard (trajectory ``.h5`` + ``.json`` and
a sidecar ``.episodes.json`` with every kept episode's EpisodeSpec and per-step stage flags)
is written into a temporary folder and moved into place, then the ledger
``<task>.<robot>.ledger.json`` (written atomically) records it with the next seed to try and
the failure counts. A shard missing from the ledger is unfinished and gets rewritten, so an
interruption loses at most one shard's work and never duplicates a demo. The finished shards
are merged into ``out_dir/<task>_<robot>.h5`` + ``.json`` + ``.episodes.json``.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import gymnasium as gym
from mani_skill.trajectory.merge_trajectory import merge_trajectories
from mani_skill.utils.wrappers import RecordEpisode
from tqdm import tqdm

from instructmove_ms.demos.pick import PICK_TASKS, plan_pick, rollout

TRAIN_SEEDS = 10**9  # training seeds lie below this (evaluation sets use others)
SHARD_SIZE = 10  # kept demos per shard
FAILURES = ("no_ik", "no_plan", "grasp_slipped")


@dataclass
class Report:
    """Outcome of a (possibly resumed) run: demos kept, seeds tried, failures by reason."""

    kept: int
    tried: int
    failures: dict[str, int] = field(default_factory=dict)
    path: Path | None = None

    @property
    def rate(self) -> float:
        """Valid-synthesis rate: kept demos per seed tried."""
        return self.kept / max(1, self.tried)


def _write_json(path: Path, data) -> None:
    """Write ``data`` as JSON atomically (a temporary file renamed over ``path``)."""
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(json.dumps(data, indent=1))
    os.replace(tmp, path)


def _record_shard(task: str, robot: str, folder: Path, name: str, seed: int, want: int):
    """Try seeds from ``seed`` on until ``want`` demos are kept, recording them into
    ``folder/name.h5``; returns (next seed, sidecar entries, failure counts)."""
    env = gym.make(
        task,
        robot_uids=robot,
        obs_mode="state",
        control_mode="pd_joint_pos",
        render_backend="cpu",
    )
    env = RecordEpisode(
        env,
        str(folder),
        trajectory_name=name,
        save_video=False,
        save_on_reset=False,
        source_type="motion_planning",
        source_desc="instructmove_ms.demos: OMPL pick plans (fcl collision checks)",
    )
    episodes: list[dict] = []
    failures: Counter[str] = Counter()
    try:
        while len(episodes) < want:
            if seed >= TRAIN_SEEDS:
                raise ValueError(f"ran out of training seeds (below {TRAIN_SEEDS})")
            env.reset(seed=seed)
            actions = plan_pick(env)
            flags = [] if isinstance(actions, str) else rollout(env, actions)
            if flags and flags[-1]["success"]:
                env.flush_trajectory()
                spec = env.unwrapped.episode.to_dict()
                stages = {k: [f[k] for f in flags] for k in flags[0]}
                episodes.append({"seed": seed, "spec": spec, "stages": stages})
            else:
                failures[actions if isinstance(actions, str) else "grasp_slipped"] += 1
                if flags:
                    env.flush_trajectory(save=False)
            seed += 1
    finally:
        env.close()
    return seed, episodes, failures


def generate(
    task: str, robot: str, n: int, out_dir: str | Path, seed0: int = 0, workers: int = 1
) -> Report:
    """Write ``n`` successful pick demos of ``task`` with ``robot`` into ``out_dir`` (see the
    module docstring), resuming from its ledger. Only ``workers=1`` is supported."""
    if task not in PICK_TASKS:
        raise ValueError(f"demo synthesis supports {', '.join(PICK_TASKS)}, not {task!r}")
    if workers != 1:
        raise ValueError("only workers=1 is supported")
    out = Path(out_dir)
    shards = out / "shards"
    shards.mkdir(parents=True, exist_ok=True)
    stem = f"{task}_{robot}"  # no dot: ManiSkill names replays after the first dot
    ledger_path = out / f"{stem}.ledger.json"
    ledger = (
        json.loads(ledger_path.read_text())
        if ledger_path.exists()
        else {"seed0": seed0, "next_seed": seed0, "shards": [], "failures": {}}
    )
    if ledger["seed0"] != seed0:
        raise ValueError(f"{ledger_path} began at seed {ledger['seed0']}, not {seed0}")
    kept = sum(s["kept"] for s in ledger["shards"])
    failures = Counter(ledger["failures"])
    with tqdm(total=n, initial=min(kept, n), desc=stem, unit="demo") as bar:
        while kept < n:
            name = f"{stem}_{len(ledger['shards']):05d}"
            with tempfile.TemporaryDirectory(dir=out) as tmp:
                seed, episodes, new = _record_shard(
                    task, robot, Path(tmp), name, ledger["next_seed"], min(SHARD_SIZE, n - kept)
                )
                _write_json(Path(tmp) / f"{name}.episodes.json", episodes)
                for suffix in (".h5", ".json", ".episodes.json"):
                    os.replace(Path(tmp) / f"{name}{suffix}", shards / f"{name}{suffix}")
            failures.update(new)
            kept += len(episodes)
            ledger["shards"].append({"name": name, "kept": len(episodes)})
            ledger.update(next_seed=seed, failures=dict(failures))
            _write_json(ledger_path, ledger)
            bar.update(len(episodes))
            bar.set_postfix(rate=f"{kept / max(1, seed - seed0):.0%}")
    path = _merge(out, stem, [s["name"] for s in ledger["shards"]])
    tried = ledger["next_seed"] - seed0
    return Report(kept, tried, {k: failures.get(k, 0) for k in FAILURES}, path)


def _merge(out: Path, stem: str, names: list[str]) -> Path:
    """Merge the shards into ``out/<stem>.h5`` + ``.json`` + ``.episodes.json``."""
    path = out / f"{stem}.h5"
    merge_trajectories(str(path), [str(out / "shards" / f"{name}.h5") for name in names])
    sidecar = []
    for name in names:
        sidecar += json.loads((out / "shards" / f"{name}.episodes.json").read_text())
    _write_json(
        out / f"{stem}.episodes.json", [{"episode_id": k, **e} for k, e in enumerate(sidecar)]
    )
    return path
