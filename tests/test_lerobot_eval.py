"""lerobot-eval on the stored held-out episodes (``integrations.lerobot_env``): the real lerobot
0.4.4 (the isolated environment of scripts/lerobot_env.sh, given this checkout and the main
environment's simulator by tests/tools/lerobot_bridge) loads our plugin, evaluates a checkpoint
declared with our LeRobot export's features on a stored episode with ``lerobot-eval``, and its
own rollout scores the planner oracle's actions as ``StoredEpisodes`` scores them here."""

from __future__ import annotations

import json
import os
import subprocess
import sysconfig
import time
from pathlib import Path
from types import SimpleNamespace

import gymnasium as gym
import imageio.v2 as imageio
import numpy as np
import pytest
from oracle_replay import EPISODES, oracle_actions, same_scores
from test_lerobot import ACT, CAMERAS, LEROBOT_PYTHON

from instructmove_ms.export.lerobot import ACTION, STATE
from instructmove_ms.export.lerobot_formats import IMAGE
from instructmove_ms.integrations import lerobot_env
from instructmove_ms.integrations.lerobot_env import (
    NAMESPACE,
    EpisodeSchedule,
    StoredEpisodesEnv,
    describe,
)
from instructmove_ms.integrations.stored import StoredEpisodes

ROOT = Path(__file__).resolve().parent.parent
TOOLS = Path(__file__).parent / "tools"
PLUGIN = ROOT / "integrations" / "lerobot_env_instructmove"
WIDTH, HEIGHT = 128, 96  # not the default: the requested size must come out
CLI_STEPS = 30  # lerobot-eval's episode (--env.episode_length): the random policy's whole run


def _bridged() -> dict:
    """The environment of a LeRobot-environment process that imports instructmove_ms, the
    plugin and ManiSkill from here (appended after its own packages)."""
    main = sysconfig.get_paths()
    paths = dict.fromkeys(map(str, [ROOT, PLUGIN, main["purelib"], main["platlib"]]))
    return {
        **os.environ,
        "PYTHONPATH": str(TOOLS / "lerobot_bridge"),
        "INSTRUCTMOVE_BRIDGE_PATH": os.pathsep.join(paths),
        "HF_HUB_OFFLINE": "1",
    }


def _reference(actions: np.ndarray) -> SimpleNamespace:
    """Stored episode 0 under ``actions`` in ``StoredEpisodes`` until its first success: the
    steps, the score, the instruction and the first frame (its cameras side by side)."""
    stored = StoredEpisodes(EPISODES, (WIDTH, HEIGHT))
    try:
        first = stored.reset(0)
        for action in actions:
            stored.step(action)
            if stored.success:
                break
        assert stored.success, "the oracle's actions succeed in the stored episode"
        return SimpleNamespace(
            steps=stored.steps,
            result=json.loads(json.dumps(stored.result())),  # as a JSON row holds it
            instruction=first.instruction,
            frame=np.concatenate(list(first.images.values()), axis=1),
        )
    finally:
        stored.close()


def _tail(log: Path) -> str:
    return log.read_text(errors="replace")[-3000:]


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> SimpleNamespace:
    """Stored episode 0 three ways, two of them at once in the LeRobot environment:
    ``lerobot_env_check.py`` (lerobot's own rollout of the oracle's actions; it first saves
    the random checkpoint), ``lerobot-eval`` of that checkpoint as soon as it is saved, and
    the oracle's actions in ``StoredEpisodes`` here meanwhile."""
    missing = f"{LEROBOT_PYTHON} missing: run scripts/lerobot_env.sh (test.sh does)"
    assert LEROBOT_PYTHON.is_file(), missing
    out = tmp_path_factory.mktemp("lerobot_eval")
    actions = oracle_actions(EPISODES, [0])[0]
    np.save(out / "oracle.npy", actions)
    dim = actions.shape[1]
    features = {IMAGE.format(camera): ["VISUAL", [3, HEIGHT, WIDTH]] for camera in CAMERAS}
    features.update({STATE: ["STATE", [dim]], ACTION: ["ACTION", [dim]]})
    scene = {"task": EPISODES.env_id, "robot": EPISODES.robot, "split": EPISODES.split}
    scene.update(width=WIDTH, height=HEIGHT)
    check = [str(LEROBOT_PYTHON), str(TOOLS / "lerobot_env_check.py"), str(out / "check")]
    check += ["--actions", str(out / "oracle.npy"), "--policy-args", json.dumps(ACT)]
    check += ["--policy-features", json.dumps(features), *(f"--{k}={v}" for k, v in scene.items())]
    cli = [str(LEROBOT_PYTHON.parent / "lerobot-eval"), f"--policy.path={out / 'check/policy'}"]
    cli += ["--env.discover_packages_path=lerobot_env_instructmove", "--env.type=instructmove"]
    cli += [f"--env.{k}={v}" for k, v in scene.items()]
    cli += [f"--env.episode_length={CLI_STEPS}", f"--env.results={out / 'eval.jsonl'}"]
    cli += ["--policy.device=cpu", "--eval.n_episodes=1", "--eval.batch_size=1"]
    cli += [f"--output_dir={out / 'eval'}"]
    env, started = _bridged(), []
    try:
        with (out / "check.log").open("w") as log:
            started.append(subprocess.Popen(check, stdout=log, stderr=log, env=env))
        deadline = time.monotonic() + 300
        while not (out / "check" / "policy.ready").exists():
            assert started[0].poll() is None, _tail(out / "check.log")
            assert time.monotonic() < deadline, "no checkpoint in 300 s"
            time.sleep(0.5)
        with (out / "eval.log").open("w") as log:
            started.append(subprocess.Popen(cli, stdout=log, stderr=log, env=env))
        reference = _reference(actions)
        for process, name in zip(started, ("check", "eval"), strict=True):
            assert process.wait(timeout=600) == 0, _tail(out / f"{name}.log")
    finally:
        for process in started:
            if process.poll() is None:
                process.kill()
                process.wait()
    rows = {
        name: [json.loads(line) for line in path.read_text().splitlines()]
        for name, path in (("check", out / "check/rollout.jsonl"), ("eval", out / "eval.jsonl"))
    }
    return SimpleNamespace(
        out=out,
        features=features,
        reference=reference,
        report=json.loads((out / "check" / "report.json").read_text()),
        eval_info=json.loads((out / "eval" / "eval_info.json").read_text()),
        rows=rows,
    )


def test_lerobot_eval_runs_a_checkpoint_with_the_exports_features_on_a_stored_episode(runs):
    """``lerobot-eval --env.type=instructmove`` of a checkpoint declared with the export's
    feature names (no rename map) plays stored episode 0 for ``--env.episode_length`` steps:
    lerobot's success and summed reward are the env's own score row of the episode, and its
    video starts on the stored episode's cameras side by side."""
    (task,) = runs.eval_info["per_task"]
    assert (task["task_group"], task["task_id"]) == ("instructmove", 0)
    (row,) = runs.rows["eval"]
    assert (row["episode_index"], row["steps"]) == (0, CLI_STEPS)
    assert row["instruction"] == runs.reference.instruction
    assert task["metrics"]["successes"] == [row["success"]] == [False]  # a random policy
    assert task["metrics"]["sum_rewards"] == [pytest.approx(row["stage_score"])]
    overall = runs.eval_info["overall"]
    assert (overall["n_episodes"], overall["pc_success"]) == (1, 0.0)
    (video,) = overall["video_paths"]
    with imageio.get_reader(video, format="FFMPEG") as reader:
        frames = list(reader.iter_data())  # (its len() is inf)
    assert len(frames) == CLI_STEPS, "one frame from the reset, one per step but the last"
    assert frames[0].shape == runs.reference.frame.shape == (HEIGHT, 3 * WIDTH, 3)
    difference = np.abs(frames[0].astype(int) - runs.reference.frame.astype(int)).mean()
    assert difference < 3.0, "the video starts on another scene than stored episode 0"


def test_lerobots_rollout_scores_the_oracle_as_stored_episodes_does(runs):
    """lerobot's ``rollout`` of the oracle's actions ends the episode at the step
    ``StoredEpisodes`` first succeeds at with the same actions, counts the success (from the
    vector env's ``final_info``) and sums the rewards to the stage score; the env's row is
    ``StoredEpisodes``'s score."""
    rollout, reference = runs.report["rollout"], runs.reference
    assert rollout["success"] and rollout["first_success"] == reference.steps
    assert (rollout["steps"], rollout["done_index"]) == (reference.steps, reference.steps - 1)
    assert rollout["sum_reward"] == pytest.approx(reference.result["stage_score"]) == 1.0
    (row,) = runs.rows["check"]
    assert (row["episode_index"], row["steps"], rollout["played"]) == (0, reference.steps, 0)
    same_scores(row, reference.result)
    assert {key: row[key] for key in reference.result} == reference.result


def test_the_env_hands_a_policy_what_a_checkpoint_trained_on_the_export_reads(runs):
    """The config's features, as lerobot turns them into a policy's, are the export's names
    and shapes; the observation lerobot makes of the env holds exactly those inputs (float
    images in [0, 1] channels first, a batch of one) and the stored episode's instruction."""
    report, features = runs.report, runs.features
    assert report["registered"] and report["env"] == {
        "class": "StoredEpisodesEnv",
        "max_steps": [StoredEpisodes(EPISODES).max_steps],
    }
    assert report["features"] == features
    inputs = {k: ["float32", [1, *shape]] for k, (kind, shape) in features.items() if k != ACTION}
    assert report["observation"] == {**inputs, "task": [runs.reference.instruction]}


def test_create_envs_gives_each_env_of_a_vector_env_its_own_episodes(runs):
    """lerobot >= 0.6's hook: env i of 2 from ``--env.episode_index=5`` plays 5 + i, then
    7 + i; the autoresets of finished episodes start none; the first seeds again start over."""
    assert runs.report["create_envs"] == [[5, 6], [7, 8], [5, 6]]


def _env(**kwargs) -> StoredEpisodesEnv:
    kwargs = {"robot": EPISODES.robot, "width": WIDTH, "height": HEIGHT, **kwargs}
    return gym.make(f"{NAMESPACE}/{EPISODES.env_id}", disable_env_checker=True, **kwargs)


def test_a_shared_schedule_hands_out_episodes_in_reset_order_and_autoresets_hold():
    """lerobot 0.4.4's loop on two envs sharing the config's schedule: each rollout's reset
    (seeded) starts the next episodes in turn; the vector env's autoreset of a finished
    episode (no arguments) holds it: steps repeat its last transition with reward 0."""
    schedule = EpisodeSchedule(3, shared=True)
    makers = [lambda: _env(episode_length=2, hold_after_end=True, schedule=schedule)] * 2
    vec = gym.vector.SyncVectorEnv(makers, autoreset_mode=gym.vector.AutoresetMode.SAME_STEP)
    try:
        assert type(vec.envs[0]) is StoredEpisodesEnv, "bare: lerobot reads its attributes"
        played = []
        for seeds in ([1000, 1001], [1002, 1003], [1000, 1001]):
            obs, info = vec.reset(seed=seeds)
            assert obs["pixels"]["wrist_camera"].shape == (2, HEIGHT, WIDTH, 3)
            played.append(info["episode_index"].tolist())
            held = None
            for step in range(3):
                obs, reward, terminated, truncated, info = vec.step(obs["agent_pos"])
                assert ((terminated | truncated) == (step >= 1)).all()
                if step == 1:
                    final = info["final_info"]
                    assert final["episode_index"].tolist() == played[-1]
                    assert not final["is_success"].any() and "instructmove" in final
                    held = obs["agent_pos"].copy()
                if step == 2:
                    assert (reward == 0).all() and (obs["agent_pos"] == held).all()
            assert [env.index for env in vec.envs] == played[-1]
        assert played == [[3, 4], [5, 6], [3, 4]]
        instructions = vec.call("task_description")
        assert all(instructions) and instructions == vec.call("task")
        assert vec.envs[0].render().shape == (HEIGHT, 3 * WIDTH, 3)
    finally:
        vec.close()


def test_a_plain_env_starts_the_next_episode_at_each_reset_and_wraps_round():
    env = _env(episode_index=98, episode_length=1)
    try:
        count = env.stored.count
        obs, info = env.reset()
        assert count == 100 and info["episode_index"] == 98
        _, reward, terminated, truncated, info = env.step(obs["agent_pos"])
        assert truncated and not terminated and info["instructmove"]["success"] is False
        assert env.reset()[1]["episode_index"] == 99, "no hold outside lerobot's vector env"
        with pytest.warns(UserWarning, match="past the 100 stored episodes"):
            assert env.reset()[1]["episode_index"] == 0
    finally:
        env.close()
    copied = EpisodeSchedule(shared=True)
    copied.pid = -1  # as a worker process's copy
    with pytest.raises(RuntimeError, match="use_async_envs"):
        copied.claim(1000)


def test_set_version_picks_the_stored_sets_an_env_plays():
    """Beside a newer benchmark version, ``set_version=7`` plays 1.0's stored episodes (what
    results on 1.0 were measured on), the default the newer version's; a version the
    package does not hold is refused by name."""
    from instructmove_ms import heldout

    played = {}
    for version in (7, None):
        env = _env(set_version=version)
        try:
            played[version] = [e.spec.instruction for e in env.unwrapped.stored.config.episodes]
            stored = heldout.load_set(
                EPISODES.env_id, EPISODES.robot, EPISODES.split, version=version
            )
            assert played[version] == [s.instruction for s in stored]
        finally:
            env.close()
    assert played[7] != played[None]
    with pytest.raises(ValueError, match="set version 9"):
        _env(set_version=9)


def test_the_config_declares_what_the_env_gives_the_other_robot():
    """``describe`` (what the config declares before lerobot makes the env, without
    rendering) gives the cameras, in their order, and the dimension a rendering env has: the
    PiperX's here, the Franka's in the LeRobot environment above."""
    env = _env(robot="piperx")
    try:
        space = env.observation_space
        cameras, dim = tuple(space["pixels"].spaces), space["agent_pos"].shape[0]
        assert env.action_space.shape == (dim,)
    finally:
        env.close()
    assert describe(EPISODES.env_id, "piperx", EPISODES.split, "normal", None) == (
        "piperx",
        cameras,
        dim,
    )


def test_the_plugin_is_a_lerobot_env_distribution_and_the_env_needs_no_lerobot():
    """lerobot >= 0.6 imports each installed distribution named ``lerobot_env_*`` by that
    name: the plugin's is its package's. Without lerobot the gymnasium env still imports."""
    tomllib = pytest.importorskip("tomllib")
    project = tomllib.loads((PLUGIN / "pyproject.toml").read_text())["project"]
    assert project["name"].startswith("lerobot_env_") and project["name"].isidentifier()
    assert (PLUGIN / project["name"] / "__init__.py").is_file()
    if not hasattr(lerobot_env, "InstructMoveEnv"):  # lerobot lives in its own environment
        with pytest.raises(AttributeError, match="lerobot is not installed"):
            lerobot_env.InstructMoveEnv  # noqa: B018
