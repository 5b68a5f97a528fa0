"""Batch evaluation: reports, resume after interruption, identical reruns, evaluator
configs, and the vector env's backend check."""

from __future__ import annotations

import json

import gymnasium as gym
import numpy as np
import pytest
import torch

from instructmove_ms import evaluation, heldout
from instructmove_ms.cli import main
from instructmove_ms.evaluation import evaluate, evaluate_config
from instructmove_ms.gpu_physics import GpuPhysicsUnavailable
from instructmove_ms.heldout import EvaluatorConfig
from instructmove_ms.policies import RandomPolicy, ScriptedBlindPolicy, ScriptedOraclePolicy
from instructmove_ms.tasks import TASKS

TASK = "PickCategory-InstructMove"


def test_reports_and_resume(tmp_path):
    summary = evaluate(RandomPolicy(0), TASK, "seen", tmp_path, robot="franka", episodes=2)
    assert summary["episodes"] == 2
    for name in (
        "summary.json",
        "report.md",
        "episodes.csv",
        "episodes.jsonl",
        "stage_funnel.png",
        "grounding_errors.png",
        "episode_results.json",
        "average_metrics.json",
        "config.json",
    ):
        assert (tmp_path / name).is_file()
    written = json.loads((tmp_path / "summary.json").read_text())
    (group,) = written["groups"]
    assert 0.0 <= group["reach"] <= 1.0 and len(group["success_ci"]) == 2
    assert group["chance"] == 1 / 6
    low, high = group["stage_score_ci"]
    assert low <= group["stage_score"] <= high
    # what a reported number names: the benchmark version, split, condition, perturbation,
    # episodes and seeds of the stored set it was measured on
    seeds = sorted(spec.seed for spec in heldout.load_set(TASK, "franka", "seen")[:2])
    about = written["about"]
    assert about["benchmark"] == heldout.benchmark_name(heldout.SET_VERSION)
    assert (about["robot"], about["split"], about["condition"]) == ("franka", "seen", "normal")
    assert (about["perturbation"], about["episodes"]) == ("none", 2)
    assert about["seeds"] == f"{seeds[0]} to {seeds[1]}"
    report = (tmp_path / "report.md").read_text()
    assert f"- benchmark: {about['benchmark']}" in report and "S [95% CI]" in report
    first = (tmp_path / "episodes.jsonl").read_text().splitlines()
    evaluate(RandomPolicy(0), TASK, "seen", tmp_path, robot="franka", episodes=3)
    lines = (tmp_path / "episodes.jsonl").read_text().splitlines()
    assert lines[:2] == first and len(lines) == 3, "finished episodes are kept, not rerun"
    evaluate(RandomPolicy(0), TASK, "seen", tmp_path, robot="franka", episodes=3, version=7)
    rows = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    older = heldout.load_set(TASK, "franka", "seen", version=7)[:3]
    assert [r["seed"] for r in rows] == [spec.seed for spec in older], "other episodes rerun"


def test_oracle_beats_blind_and_its_config_reproduces_the_set(tmp_path, capsys):
    oracle = evaluate(
        ScriptedOraclePolicy(0), TASK, "seen", tmp_path / "a", robot="franka", episodes=4
    )
    config = tmp_path / "config.json"
    common = ["eval", "--task", TASK, "--robot", "franka", "--episodes", "4"]
    assert main([*common, "--write-config", str(config)]) == 0
    written = json.loads(config.read_text())
    assert written["env_info"]["env_id"] == TASK and len(written["episodes"]) == 4
    reset = written["episodes"][3]["reset_kwargs"]
    assert reset["options"]["episode"]["seed"] == reset["seed"]
    assert EvaluatorConfig.load(config) == EvaluatorConfig.load(tmp_path / "a" / "config.json")
    args = ["eval", "--config", str(config), "--policy", "scripted", "--out", str(tmp_path / "b")]
    assert main(args) == 0
    capsys.readouterr()
    for name in ("episodes.jsonl", "episode_results.json", "average_metrics.json"):
        assert (tmp_path / "a" / name).read_text() == (tmp_path / "b" / name).read_text(), name
    average = json.loads((tmp_path / "a" / "average_metrics.json").read_text())
    assert average["reach"] == oracle["groups"][0]["reach"]
    blind = evaluate(
        ScriptedBlindPolicy(1), TASK, "seen", tmp_path / "c", robot="franka", episodes=4
    )
    assert oracle["groups"][0]["reach"] > blind["groups"][0]["reach"]
    assert oracle["groups"][0]["reach"] >= 0.75


def test_visual_observations_reach_the_policy(tmp_path):
    class Recorder(RandomPolicy):
        def act(self, obs):
            self.images.append(obs["sensor_data"]["static_camera"]["rgb"].shape)
            return super().act(obs)

    policy = Recorder(0, obs_mode="rgb")
    policy.images = []
    evaluate(policy, TASK, "seen", tmp_path, robot="piperx", episodes=1)
    assert policy.images and policy.images[0] == (1, 90, 160, 3)


@pytest.mark.parametrize(
    ("backend", "error", "says"),
    [
        ("physx_cpu", ValueError, "needs the GPU sim backend"),
        ("auto", GpuPhysicsUnavailable, "GPU physics needs SAPIEN's PhysX GPU library"),
    ],
)
def test_several_envs_need_gpu_physics(tmp_path, monkeypatch, backend, error, says):
    """Two sub-scenes need GPU physics: the CPU backend is refused, and ``auto`` (the GPU for
    more than one env) stops before SAPIEN where its PhysX GPU library is missing (a home
    folder without it)."""
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    with pytest.raises(error, match=says):
        evaluate(RandomPolicy(0), TASK, "seen", tmp_path, num_envs=2, sim_backend=backend)
    assert not tmp_path.joinpath("episodes.jsonl").exists(), "fails before running anything"


def test_eval_cli_rejects_several_cpu_envs_and_missing_arguments(tmp_path, capsys):
    args = ["eval", "--task", TASK, "--policy", "random", "--out", str(tmp_path)]
    assert main([*args, "--num-envs", "3", "--sim-backend", "physx_cpu"]) == 2
    assert "num_envs=3 needs the GPU sim backend" in capsys.readouterr().err
    assert main(["eval", "--policy", "random", "--out", str(tmp_path)]) == 2
    assert "one of --task, --config or --traj" in capsys.readouterr().err
    assert main(["eval", "--task", TASK]) == 2
    assert "--policy and --out" in capsys.readouterr().err


class FakeVectorEnv:
    """Stands in for the GPU sim: sub-scene i, reset to episode e, succeeds from step
    SUCCEED_AT[e.seed] on (latched)."""

    def __init__(self, num_envs: int, succeed_at: dict[int, int]) -> None:
        self.num_envs, self.succeed_at = num_envs, succeed_at
        self.single_action_space = gym.spaces.Box(-1, 1, (8,))
        self.unwrapped, self.catalog, self.resets, self.steps = self, None, [], 0
        self.task = TASKS[TASK]

    def catalog_of(self, spec):
        return self.catalog

    def reset(self, seed, options):
        assert len(seed) == len(options["episode"]) == self.num_envs
        self.seeds, self.t = seed, 0
        self.targets = torch.tensor([spec["target"] for spec in options["episode"]])
        self.resets.append(list(seed))
        return torch.zeros(self.num_envs, 3), self._info()

    def step(self, action):
        assert tuple(np.shape(action)) == (self.num_envs, 8)
        self.t += 1
        self.steps += 1
        return torch.zeros(self.num_envs, 3), None, None, None, self._info()

    def _info(self) -> dict:
        done = torch.tensor([self.t >= self.succeed_at.get(s, 10**9) for s in self.seeds])
        first = torch.where(done, self.targets, -1)
        names = ("reach", "lift", "success", "success_now", "any_reach", "any_lift")
        flags = {k: done.clone() for k in names}
        return {**flags, "reached_object": first, "lifted_object": first, "stage_score": 1.0 * done}

    def close(self) -> None:
        pass


class BatchPolicy:
    """Zero actions for the whole batch; fails from step ``fail_at`` on."""

    def __init__(self, fail_at: int | None = None) -> None:
        self.fail_at, self.t = fail_at, 0

    def get_obs_mode(self) -> str:
        return "state"

    def get_control_mode(self) -> str:
        return "pd_joint_delta_pos"

    def reset(self, obs) -> None:
        pass

    def act(self, obs):
        self.t += 1
        if self.fail_at is not None and self.t >= self.fail_at:
            raise RuntimeError("lost the connection")
        return np.zeros((obs.shape[0], 8), dtype=np.float32)


def _rows(out) -> list[dict]:
    return [json.loads(line) for line in (out / "episodes.jsonl").read_text().splitlines()]


def test_vector_env_batches_episodes_and_latches_each_sub_scene(tmp_path, monkeypatch):
    config = heldout.evaluator_config(TASK, "franka", "seen", episodes=3)
    seeds = [e.seed for e in config.episodes]
    env = FakeVectorEnv(2, {seeds[0]: 2, seeds[2]: 1})
    monkeypatch.setattr(evaluation, "check_gpu_physics", lambda: None)  # a GPU machine
    monkeypatch.setattr(evaluation.gym, "make", lambda *args, **kwargs: env)
    summary = evaluate_config(BatchPolicy(), config, tmp_path / "a", num_envs=2)
    assert env.resets == [seeds[:2], [seeds[2]] * 2], "two sub-scenes a reset, the last padded"
    assert env.steps == 2 * config.max_episode_steps, "every batch runs the whole horizon"
    rows = _rows(tmp_path / "a")
    assert [r["success"] for r in rows] == [True, False, True] and summary["errors"] == 0
    assert [r["success_at_end"] for r in rows] == [True, False, True]
    env.steps = 0
    evaluate_config(BatchPolicy(fail_at=4), config, tmp_path / "b", num_envs=2)
    rows = _rows(tmp_path / "b")
    assert rows[0]["success"] and rows[0]["error"] is None, "latched before the failure"
    assert rows[0]["success_at_end"] is None, "the run did not reach the end"
    assert rows[1]["error"] == "act() raised RuntimeError: lost the connection"
    assert not rows[1]["success"] and rows[2]["error"] is not None
