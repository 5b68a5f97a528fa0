"""Batch evaluation of a policy on held-out episodes, resumable.

The episodes come from an evaluator config (ManiSkill's convention, see ``heldout``): a
stored set re-rendered for an instruction condition (same scene, other instruction), or a
config file. Each episode's env is reset to its spec, the policy acts for the whole horizon
(ManiSkill's convention) and the info of the last step is scored: the latched stages and
``success`` (success once), and ``success_at_end`` (the success condition holds at the last
step). Results append to ``episodes.jsonl`` as they finish, so an interrupted
run resumes where it stopped; the reports (see ``reports``) are rewritten at the end.

Each episode has a seed of its own (its ``reset_kwargs`` seed): a policy whose ``reset``
takes a ``seed`` argument gets it (a list, one per sub-scene, with ``num_envs > 1``) and
draws its randomness from it, so a run that was interrupted and resumed scores exactly what
an uninterrupted one does. A torn last row (a run killed while writing it) is dropped on
resume. One run at a time holds the output folder (``files.OutputLock``).

A policy that fails an episode (raises, or returns an action of the wrong shape or with
NaN/inf; see ``guard``) gets the message in that row's ``error`` field and the traceback in
``errors.log``; the episode is scored as failed and the run goes on to the next one. A
failure of the policy's infrastructure (``guard.ServerError``: a policy server that cannot
be reached) is not the policy's: the run stops there and the episodes in flight stay
unscored, so that a resume runs them.

``num_envs > 1`` runs that many episodes at once, one per sub-scene of ManiSkill's GPU
simulation: the policy gets batched observations and returns (num_envs, dim) actions; a
policy failure fails the batch's episodes that had not succeeded yet. The CPU simulation
runs one env per process; ``workers`` (local processes or a Ray cluster, see ``executor``)
run batches in parallel, each worker with its own env and its own copy of the policy
(pickled into it: a served policy connects again from there). Rows are appended as batches
finish and ``episodes.jsonl`` is rewritten in the config's order at the end, so the output
equals a one-process run's.

Observations on demand: a policy that holds actions it will play without looking (a chunked
or served policy) says how many with ``held_actions()``; while it holds any, the env steps
without computing its observation (no camera is rendered) and the policy gets ``None``. The
observation is computed on the step before the policy asks again, as the env always does, so
physics, per-step info, scores and videos are those of a run that renders every step. A
policy without ``held_actions`` gets every step's observation but the last's, which no
policy reads.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import json
import re
import traceback
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import torch
from tqdm import tqdm

from . import heldout
from .executor import Tick, Workers, job_token, worker_state
from .files import OutputLock, append_text, clean_stale, read_rows, write_text
from .gpu_physics import GPU_BACKENDS, check_gpu_physics, uses_gpu_physics
from .guard import PolicyError, check_action, guarded
from .heldout import ConfigEpisode, EvaluatorConfig
from .metrics import EpisodeResult, score_episode
from .reports import write_reports
from .video import VideoSettings, outcome_text, write_video

STATE_MODES = ("state", "state_dict")  # observation modes that need no renderer
GPU_SIM_BACKENDS = ("auto", *GPU_BACKENDS)  # "auto" is the GPU for num_envs > 1


def check_backend(num_envs: int, sim_backend: str, on_cluster: bool = False) -> None:
    """Fail early where ``num_envs`` sub-scenes cannot run: more than one needs the GPU
    simulation backend, and GPU physics needs PhysX's GPU library and a CUDA device (here,
    unless the episodes run ``on_cluster``, whose GPU workers Ray schedules;
    ``gpu_physics.GpuPhysicsUnavailable`` says which is missing)."""
    if num_envs < 1:
        raise ValueError(f"num_envs must be at least 1, got {num_envs}")
    if num_envs > 1 and sim_backend.split(":")[0] not in GPU_SIM_BACKENDS:
        needs = f"num_envs={num_envs} needs the GPU sim backend (sim_backend='physx_cuda')"
        raise ValueError(f"{needs}; {sim_backend!r} simulates one env per process")
    if not on_cluster and uses_gpu_physics(sim_backend, num_envs):
        check_gpu_physics()


def takes_seed(reset: Any) -> bool:
    """Whether a policy's ``reset`` takes the episode seed (a ``seed`` or ``**`` argument)."""
    try:
        parameters = inspect.signature(reset).parameters.values()
    except (TypeError, ValueError):
        return False
    return any(p.name == "seed" or p.kind is p.VAR_KEYWORD for p in parameters)


def _numpy(x: Any) -> np.ndarray:
    return x.detach().cpu().numpy() if isinstance(x, torch.Tensor) else np.asarray(x)


def _sub_info(info: dict, i: int) -> dict:
    """Sub-scene ``i``'s part of a batched step info."""
    return {
        k: v[i : i + 1] if isinstance(v, torch.Tensor) and v.ndim else v for k, v in info.items()
    }


def reads_next_observation(policy: Any) -> bool:
    """Whether ``policy`` will read the observation the next step gives (see the module
    docstring: not while it holds actions)."""
    held = getattr(policy, "held_actions", None)
    return held is None or held() == 0


@contextmanager
def observations_off(env: gym.Env) -> Iterator[None]:
    """Steps of ``env`` inside the block compute no observation (ManiSkill's ``"none"``
    observation mode: no sensor is captured, nothing is rendered); they return ``{}``."""
    u = env.unwrapped
    struct = getattr(u, "obs_mode_struct", None)  # None: not a ManiSkill env, steps as usual
    if struct is None or struct.state:  # a flattened state part expects the whole observation
        yield
        return
    mode, u._obs_mode = u._obs_mode, "none"
    try:
        yield
    finally:
        u._obs_mode = mode


@dataclass
class _Runner:
    """Runs batches of episodes (one per sub-scene) and scores them."""

    env: gym.Env
    policy: Any
    horizon: int
    out: Path
    video: VideoSettings | None
    filmed: set

    def _frames(self, frames: list[list[np.ndarray] | None]) -> None:
        """Add a rendered frame to each filmed episode."""
        if any(film is not None for film in frames):
            images = _numpy(self.env.render())
            for i, film in enumerate(frames):
                if film is not None:
                    film.append(images[i])

    def _play(
        self, batch: list[ConfigEpisode], obs: Any, frames: list, first: list, last: list
    ) -> None:
        """Step the policy for the whole horizon (ManiSkill's convention: no early end, so
        that success at the end is measured), keeping each episode's info at its first
        success in ``first`` and at the last step in ``last`` (a failure leaves ``last``
        None)."""
        u = self.env.unwrapped
        dim = u.single_action_space.shape[0]
        self._frames(frames)
        if hasattr(self.policy, "bind"):
            guarded("bind", self.policy.bind, self.env)
        if takes_seed(self.policy.reset):
            seeds = [e.seed for e in batch]
            seed = seeds if u.num_envs > 1 else seeds[0]
            guarded("reset", lambda: self.policy.reset(obs, seed=seed))
        else:
            guarded("reset", self.policy.reset, obs)
        info: dict = {}
        for t in range(self.horizon):
            action = check_action(guarded("act", self.policy.act, obs), dim, u.num_envs)
            final = t + 1 == self.horizon  # no policy reads the last step's observation
            obs, info = self._step(action, not final and reads_next_observation(self.policy))
            self._frames(frames)
            for i, episode in enumerate(batch):
                if first[i] is None and episode.spec.target >= 0 and bool(info["success"][i]):
                    first[i] = _sub_info(info, i)
        for i in range(len(batch)):
            last[i] = _sub_info(info, i)

    def _step(self, action: Any, observe: bool) -> tuple[Any, dict]:
        """(observation, info) of a step; the observation is None unless ``observe``."""
        if observe:
            obs, _, _, _, info = self.env.step(action)
            return obs, info
        with observations_off(self.env):
            _, _, _, _, info = self.env.step(action)
        return None, info

    def run(self, batch: list[ConfigEpisode]) -> list[dict]:
        """The result rows of ``batch`` (at most one episode per sub-scene)."""
        u = self.env.unwrapped
        padded = batch + [batch[-1]] * (u.num_envs - len(batch))
        obs, _ = self.env.reset(
            seed=[e.seed for e in padded],
            options={"episode": [e.spec.to_dict() for e in padded]},
        )
        frames = [[] if e.episode_id in self.filmed else None for e in batch]
        first: list[dict | None] = [None] * len(batch)
        last: list[dict | None] = [None] * len(batch)
        error = None
        try:
            self._play(batch, obs, frames, first, last)
        except PolicyError as exc:
            error = str(exc)
            self._log_error([e for e, x in zip(batch, first, strict=True) if x is None], exc)
        rows = []
        for episode, once, end, film in zip(batch, first, last, frames, strict=True):
            stages, catalog = u.task.stages, u.catalog_of(episode.spec)
            if end is not None:  # the latched stages of the last step, and success at the end
                result, failed = score_episode(episode.spec, end, stages, catalog), None
            elif once is not None:  # succeeded before the policy failed: success at the end
                result, failed = score_episode(episode.spec, once, stages, catalog), None
                result = dataclasses.replace(result, success_at_end=None)  # is not known
            else:
                result, failed = EpisodeResult.failed(episode.spec, stages), error
            rows.append({"episode_id": episode.episode_id, **result.to_dict(), "error": failed})
            if film:
                self._write_video(episode, film, result, failed)
        return rows

    def close(self) -> None:
        self.env.close()

    def _log_error(self, batch: list[ConfigEpisode], exc: PolicyError) -> None:
        ids = ", ".join(str(e.episode_id) for e in batch)
        tqdm.write(f"episode {ids}: {exc}")
        text = f"episode {ids}:\n{''.join(traceback.format_exception(exc))}\n"
        append_text(self.out / "errors.log", text)

    def _write_video(
        self, episode: ConfigEpisode, frames: list, result: EpisodeResult, error: str | None
    ) -> None:
        name = re.sub(r"[^\w.-]", "_", str(episode.episode_id))
        write_video(
            self.out / "videos" / f"episode_{name}.mp4",
            frames,
            episode.spec.instruction,
            outcome_text(result.success, result.stages, error),
            self.video.fps,
        )


def _make_env(
    policy: Any,
    config: EvaluatorConfig,
    num_envs: int,
    sim_backend: str,
    video: VideoSettings | None,
) -> gym.Env:
    obs_mode = policy.get_obs_mode()
    cameras = getattr(policy, "get_sensor_configs", lambda: None)()
    if video:
        render = {"render_mode": "rgb_array", "human_render_camera_configs": video.camera}
    else:  # a policy that names its cameras' resolution renders them, whatever it observes
        render = {"render_backend": "none"} if obs_mode in STATE_MODES and not cameras else {}
    if cameras:  # the resolution the policy's images come from
        render["sensor_configs"] = cameras
    return gym.make(
        config.env_id,
        **{
            **config.env_kwargs,
            **render,
            "obs_mode": obs_mode,
            "control_mode": policy.get_control_mode(),
            "num_envs": num_envs,
            "sim_backend": sim_backend,
        },
    )


@dataclass(frozen=True)
class _Setup:
    """What a worker needs to run batches of one evaluation (picklable: the policy is
    pickled into each worker process, and a served policy connects again there)."""

    policy: Any
    config: EvaluatorConfig  # without its episodes: the shards carry them
    out: Path
    num_envs: int
    sim_backend: str
    video: VideoSettings | None
    filmed: frozenset

    def runner(self) -> _Runner:
        env = _make_env(self.policy, self.config, self.num_envs, self.sim_backend, self.video)
        horizon = self.config.max_episode_steps
        return _Runner(env, self.policy, horizon, self.out, self.video, set(self.filmed))


def _run_batch(token: str, setup: _Setup, batch: list[ConfigEpisode], tick: Tick) -> list[dict]:
    """A shard: the rows of one batch, run by this process's runner of the evaluation."""
    return worker_state(token, setup.runner).run(batch)


def evaluate_config(
    policy: Any,
    config: EvaluatorConfig,
    out: Path,
    num_envs: int = 1,
    sim_backend: str = "auto",
    video: VideoSettings | None = None,
    workers: Workers | int = 1,
) -> dict:
    """Run ``policy`` on exactly the episodes of ``config``; write the config used, the
    results and the reports to ``out``; return the summary. ``workers`` (local processes or
    a Ray cluster, see ``executor``) run batches of ``num_envs`` episodes each; the policy's
    own statistics (a served policy's timing) are reported when it runs in this process."""
    workers = Workers.of(workers)
    check_backend(num_envs, sim_backend, workers.ray is not None)
    config.check()  # before anything is written
    with OutputLock(out, "instructmove eval"):
        clean_stale(out)
        return _evaluate(policy, config, out, num_envs, sim_backend, video, workers)


def _still_valid(rows: list[dict], previous: Path, config: EvaluatorConfig) -> dict:
    """episode id -> row of ``rows`` (a run's finished episodes) whose episode, as the
    run's config at ``previous`` gave it, is the one ``config`` gives under that id: a set
    rewritten since (or another config) runs its changed episodes again."""
    done = {row["episode_id"]: row for row in rows}
    if not done or not previous.is_file():
        return done
    before = {e.episode_id: e for e in EvaluatorConfig.load(previous).episodes}
    now = {e.episode_id: e for e in config.episodes}
    stale = {i for i in done if i in now and before.get(i) != now[i]}
    if stale:
        print(f"{len(stale)} finished episodes in {previous.parent} were other episodes: run again")
    return {i: row for i, row in done.items() if i not in stale}


def _evaluate(
    policy: Any,
    config: EvaluatorConfig,
    out: Path,
    num_envs: int,
    sim_backend: str,
    video: VideoSettings | None,
    workers: Workers,
) -> dict:
    log = out / "episodes.jsonl"
    done = _still_valid(read_rows(log), out / "config.json", config)
    config.write(out / "config.json")
    todo = [e for e in config.episodes if e.episode_id not in done]
    batches = [todo[start : start + num_envs] for start in range(0, len(todo), num_envs)]
    if todo:
        filmed = {e.episode_id for e in config.episodes[: video.first]} if video else set()
        shell = dataclasses.replace(config, episodes=[])
        setup = _Setup(policy, shell, out, num_envs, sim_backend, video, frozenset(filmed))
        run = functools.partial(_run_batch, job_token(), setup)
        desc = f"{config.env_id} {todo[0].spec.split} {todo[0].spec.condition}"
        with log.open("a") as sink, tqdm(total=len(todo), desc=desc, unit="episode") as bar:
            for _, rows in workers.run(run, batches, folder=out):
                for row in rows:  # appended as they finish: a killed run loses none
                    sink.write(json.dumps(row) + "\n")
                    sink.flush()
                    done[row["episode_id"]] = row
                    bar.update()
        clean_stale(out)  # what a worker killed mid-episode left (the episode ran again)
    rows = [done[e.episode_id] for e in config.episodes if e.episode_id in done]
    if todo:  # in the config's order, however the shards finished
        write_text(log, "".join(json.dumps(row) + "\n" for row in rows))
    stats = getattr(policy, "stats", dict)() if workers.in_process(len(batches)) else {}
    return write_reports(out, rows, stats, config.about())


def evaluate(
    policy: Any,
    env_id: str,
    split: str,
    out: Path,
    robot: str | None = None,
    condition: str = "normal",
    episodes: int | None = None,
    num_envs: int = 1,
    sim_backend: str = "auto",
    video: VideoSettings | None = None,
    workers: Workers | int = 1,
    version: int | None = None,
) -> dict:
    """Run ``policy`` on the held-out set of (env, robot, split) of ``version`` (default: the
    current one) under ``condition`` (the first ``episodes`` of it, all by default)."""
    check_backend(num_envs, sim_backend, Workers.of(workers).ray is not None)
    config = heldout.evaluator_config(env_id, robot, split, condition, episodes, version=version)
    return evaluate_config(policy, config, out, num_envs, sim_backend, video, workers)
