"""Observations on demand: while a policy holds actions, the evaluator steps the env without
rendering, and everything it scores is what a run that renders every step scores."""

from __future__ import annotations

import hashlib
import json

import numpy as np
import pytest
import torch
from mani_skill.envs.sapien_env import BaseEnv

from instructmove_ms import evaluation, heldout
from instructmove_ms.evaluation import evaluate_config
from instructmove_ms.policies import OraclePolicy

CHUNK = 5
STEP, RENDER = evaluation._Runner._step, BaseEnv._get_obs_with_sensor_data  # unpatched


class Chunked:
    """The oracle's actions ``CHUNK`` at a time, asked for at each query with that step's
    observation (a digest of which it keeps); it does not say it holds actions."""

    def __init__(self, obs_mode: str) -> None:
        self.inner, self.obs_mode = OraclePolicy(obs_mode=obs_mode), obs_mode
        self.seen: list[str] = []

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return "pd_joint_pos"

    def bind(self, env) -> None:
        self.inner.bind(env)

    def reset(self, obs, seed=None) -> None:
        self.inner.reset(obs, seed=seed)
        self.chunk: list[torch.Tensor] = []

    def act(self, obs) -> torch.Tensor:
        if not self.chunk:
            self.seen.append(_digest(obs))
            self.chunk = [self.inner.act(obs) for _ in range(CHUNK)]
        return self.chunk.pop(0)


class ChunkedOnDemand(Chunked):
    """The same policy, saying how many actions it holds."""

    def held_actions(self) -> int:
        return len(self.chunk)


def _digest(obs) -> str:
    """A digest of every array of an observation (images included)."""
    h = hashlib.sha256()
    stack = [obs]
    while stack:
        item = stack.pop()
        if isinstance(item, dict):
            stack.extend(item[k] for k in sorted(item, reverse=True))
        else:
            h.update(np.ascontiguousarray(torch.as_tensor(item).cpu().numpy()).tobytes())
    return h.hexdigest()


def _run(policy: Chunked, tmp_path, monkeypatch) -> tuple[list[dict], list[dict], int]:
    """Rows, per-step flags and renders of ``policy`` on a stored episode."""
    steps: list[dict] = []
    renders = [0]

    def recording_step(self, action, observe):
        obs, info = STEP(self, action, observe)
        steps.append({k: v.tolist() for k, v in info.items() if isinstance(v, torch.Tensor)})
        return obs, info

    def counted_render(self, *args, **kwargs):
        renders[0] += 1
        return RENDER(self, *args, **kwargs)

    monkeypatch.setattr(evaluation._Runner, "_step", recording_step)
    monkeypatch.setattr(BaseEnv, "_get_obs_with_sensor_data", counted_render)
    config = heldout.evaluator_config("PickCategory-InstructMove", "franka", "seen", episodes=1)
    evaluate_config(policy, config, tmp_path)
    rows = [json.loads(line) for line in (tmp_path / "episodes.jsonl").open()]
    return rows, steps, renders[0]


@pytest.mark.parametrize("obs_mode", ["state", "rgb"])
def test_rows_and_per_step_flags_match_a_run_that_renders_every_step(
    obs_mode, tmp_path, monkeypatch
):
    every, on_demand = Chunked(obs_mode), ChunkedOnDemand(obs_mode)
    rows, steps, renders = _run(every, tmp_path / "every", monkeypatch)
    rows_d, steps_d, renders_d = _run(on_demand, tmp_path / "on_demand", monkeypatch)
    assert rows_d == rows
    assert (
        steps_d == steps
        and len(steps)
        == heldout.evaluator_config(
            "PickCategory-InstructMove", "franka", "seen", episodes=1
        ).max_episode_steps
    )
    assert any(row["success"] for row in rows), "the oracle lifts: the flags move"
    assert on_demand.seen == every.seen, "each query saw the observation of the same step"
    fixed = renders - len(steps) + 1  # the env's first observation and the reset's
    if obs_mode == "rgb":
        assert fixed in (1, 2), renders  # every step renders but the episode's last
        assert renders_d == fixed + len(every.seen) - 1, "one render per query, no other"
    else:
        assert renders == renders_d == 0
