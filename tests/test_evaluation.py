"""Batch evaluation: reports, resume after interruption, identical reruns."""

from __future__ import annotations

import json

from instructmove_ms.evaluation import evaluate
from instructmove_ms.policies import BlindPolicy, OraclePolicy, RandomPolicy

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
    ):
        assert (tmp_path / name).is_file()
    (group,) = json.loads((tmp_path / "summary.json").read_text())["groups"]
    assert 0.0 <= group["reach"] <= 1.0 and len(group["success_ci"]) == 2
    assert group["chance"] == 1 / 6
    first = (tmp_path / "episodes.jsonl").read_text().splitlines()
    evaluate(RandomPolicy(0), TASK, "seen", tmp_path, robot="franka", episodes=3)
    lines = (tmp_path / "episodes.jsonl").read_text().splitlines()
    assert lines[:2] == first and len(lines) == 3, "finished episodes are kept, not rerun"


def test_oracle_beats_blind_and_reruns_are_identical(tmp_path):
    oracle = evaluate(OraclePolicy(0), TASK, "seen", tmp_path / "a", robot="franka", episodes=4)
    evaluate(OraclePolicy(0), TASK, "seen", tmp_path / "b", robot="franka", episodes=4)
    assert (tmp_path / "a" / "episodes.jsonl").read_text() == (
        tmp_path / "b" / "episodes.jsonl"
    ).read_text()
    blind = evaluate(BlindPolicy(1), TASK, "seen", tmp_path / "c", robot="franka", episodes=4)
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
