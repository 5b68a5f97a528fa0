"""A policy that fails an episode gets a per-episode error; the run goes on."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
import torch

from instructmove_ms import heldout
from instructmove_ms.evaluation import evaluate_config
from instructmove_ms.guard import PolicyError, check_action
from instructmove_ms.policies import RandomPolicy

TASK = "PickCategory-InstructMove"


class FlakyPolicy(RandomPolicy):
    """Fails its n-th episode in the n-th way of FAILURES; random actions after that."""

    FAILURES = ("act raises", "wrong shape", "nan", "inf", "reset raises")

    def __init__(self) -> None:
        super().__init__(0)
        self.episode = -1

    def reset(self, obs) -> None:
        self.episode += 1
        if self.mode == "reset raises":
            raise KeyError("no such camera")

    @property
    def mode(self) -> str | None:
        return self.FAILURES[self.episode] if self.episode < len(self.FAILURES) else None

    def act(self, obs):
        action = super().act(obs)
        if self.mode == "act raises":
            raise RuntimeError("out of memory")
        if self.mode == "wrong shape":
            return action[:3]
        if self.mode in ("nan", "inf"):
            action[1] = np.nan if self.mode == "nan" else np.inf
        return action


def test_bad_episodes_get_errors_and_count_as_failures(tmp_path):
    config = heldout.evaluator_config(TASK, "franka", "seen", episodes=6)
    config = dataclasses.replace(config, max_episode_steps=5)
    summary = evaluate_config(FlakyPolicy(), config, tmp_path)
    rows = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    assert [r["error"] for r in rows] == [
        "act() raised RuntimeError: out of memory",
        "act() returned shape (3,), expected (8,) or (1, 8)",
        "act() returned NaN or inf",
        "act() returned NaN or inf",
        "reset() raised KeyError: 'no such camera'",
        None,
    ]
    for row in rows[:5]:
        assert not row["success"] and not any(row["stages"].values()) and row["stage_score"] == 0
    assert summary["errors"] == 5 and summary["episodes"] == 6
    assert summary["groups"][0]["episodes"] == 6, "failed episodes stay in the rates"
    assert "RuntimeError: out of memory" in (tmp_path / "errors.log").read_text()
    assert "5 episode(s) ended in a policy error" in (tmp_path / "report.md").read_text()
    assert "error" in (tmp_path / "episodes.csv").read_text().splitlines()[0].split(",")
    results = json.loads((tmp_path / "episode_results.json").read_text())
    assert results["0"]["error"].startswith("act() raised") and "error" not in results["5"]
    average = json.loads((tmp_path / "average_metrics.json").read_text())
    assert average["success"] == 0.0 and "error" not in average


@pytest.mark.parametrize(
    "action",
    [np.zeros(8), np.zeros((1, 8)), torch.zeros(1, 8), [0.0] * 8],
    ids=["flat", "batched", "tensor", "list"],
)
def test_actions_of_the_right_shape_pass(action):
    assert tuple(np.shape(check_action(action, 8, 1))) in ((8,), (1, 8))


@pytest.mark.parametrize(
    ("action", "num_envs", "message"),
    [
        (np.zeros((2, 8)), 1, r"shape \(2, 8\), expected \(8,\) or \(1, 8\)"),
        (np.zeros(8), 2, r"shape \(8,\), expected \(2, 8\)"),
        (torch.tensor([[0.0] * 7 + [float("inf")]]), 1, "NaN or inf"),
        ("left", 1, "act\\(\\) returned a str"),
        ([[0.0] * 8, [0.0]], 1, "act\\(\\) returned a list"),
    ],
    ids=["batch", "unbatched", "inf tensor", "text", "ragged"],
)
def test_bad_actions_are_named(action, num_envs, message):
    with pytest.raises(PolicyError, match=message):
        check_action(action, 8, num_envs)
