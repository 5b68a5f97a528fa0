"""Metrics: Wilson intervals, per-episode scoring, aggregation in the paper's format."""

from __future__ import annotations

import dataclasses

import gymnasium as gym
import numpy as np
import pytest
import torch

import instructmove_ms  # noqa: F401
import scripted
from instructmove_ms.metrics import (
    aggregate,
    comparison_table,
    markdown_table,
    score_episode,
    wilson,
)
from instructmove_ms.tasks import PICK_STAGES


def test_wilson_interval_matches_known_values():
    assert wilson(0, 10) == pytest.approx((0.0, 0.2775), abs=1e-4)
    assert wilson(5, 10) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    assert wilson(0, 0) == (0.0, 1.0)


def _info(**flags):
    base = dict(
        reach=False,
        lift=False,
        success=False,
        stage_score=0.0,
        reached_object=-1,
        lifted_object=-1,
        any_reach=False,
        any_lift=False,
    )
    base.update(flags)
    return {k: torch.tensor([v]) for k, v in base.items()}


@pytest.fixture(scope="module")
def attribute_spec():
    env = gym.make("PickAttribute-InstructMove", obs_mode="state", render_backend="none")
    spec = env.unwrapped.sample_episode(3)
    yield spec, env.unwrapped.catalog
    env.close()


def test_grounding_and_control_errors_are_told_apart(attribute_spec):
    spec, catalog = attribute_spec
    wrong = next(k for k in spec.candidates if k != spec.target)
    grounding = score_episode(
        spec, _info(reached_object=wrong, any_reach=True), PICK_STAGES, catalog
    )
    assert grounding.grounding_error and not grounding.control_error
    assert "category" in grounding.shared, "same-category distractor"
    control = score_episode(
        spec,
        _info(reach=True, reached_object=spec.target, stage_score=0.5, any_reach=True),
        PICK_STAGES,
        catalog,
    )
    assert control.control_error and not control.grounding_error
    done = score_episode(
        spec,
        _info(
            reach=True,
            lift=True,
            success=True,
            stage_score=1.0,
            reached_object=spec.target,
            lifted_object=spec.target,
        ),
        PICK_STAGES,
        catalog,
    )
    assert done.success and not done.control_error and not done.grounding_error
    rows = aggregate([grounding, control, done])
    assert len(rows) == 1 and rows[0]["episodes"] == 3
    assert rows[0]["reach"] == pytest.approx(2 / 3) and rows[0]["success"] == pytest.approx(1 / 3)
    assert rows[0]["chance"] == pytest.approx(1 / spec.num_goals)
    assert "0.67/0.33 (0.50)" in markdown_table(rows)
    side_by_side = comparison_table({"oracle": rows, "blind": aggregate([grounding])})
    header, _, line = side_by_side.splitlines()
    assert header.split(" | ")[-3:] == ["oracle", "blind", "chance (1/G) |"]
    assert "| 0.67/0.33 (0.50) | 0.00/0.00 (0.00) | " in line


def test_live_oracle_reach_scores_as_control_errors():
    """The reaching oracle never lifts: reach 1, lift 0, every episode a control error."""
    env = gym.make(
        "PickCategory-InstructMove",
        obs_mode="state",
        render_backend="none",
        control_mode="pd_ee_delta_pose",
        robot_uids="franka",
    )
    results = []
    rng = np.random.default_rng(0)
    for seed in range(3):
        env.reset(seed=seed)
        spec = env.unwrapped.episode
        info = scripted.reach_object(env, scripted.choose(spec, rng, True))
        results.append(score_episode(spec, info, PICK_STAGES, env.unwrapped.catalog))
    env.close()
    (row,) = aggregate(results)
    assert row["reach"] >= 2 / 3 and row["lift"] == 0.0
    assert row["control_error"] == row["reach"] and row["grounding_error"] == 0.0


def test_success_at_end_and_language_following(attribute_spec):
    """Under alternative_target the instruction names another candidate than the scene's
    own target: going for it is following the language, going for the scene's target not."""
    normal, catalog = attribute_spec
    original = normal.target
    named = next(k for k in normal.candidates if k != original)
    spec = dataclasses.replace(normal, target=named, condition="alternative_target")
    assert spec.objects[original].role == "target", "the scene's own target keeps its role"
    lift = {"reach": True, "lift": True, "success": True, "stage_score": 1.0}
    followed = score_episode(
        spec,
        _info(**lift, reached_object=named, lifted_object=named, success_now=False),
        PICK_STAGES,
        catalog,
    )
    assert followed.choice == "target" and followed.success and followed.success_at_end is False
    ignored = score_episode(spec, _info(reached_object=original), PICK_STAGES, catalog)
    assert ignored.choice == "original" and ignored.grounding_error
    idle = score_episode(spec, _info(success_now=False), PICK_STAGES, catalog)
    assert idle.choice == "none"
    (row,) = aggregate([followed, ignored, ignored, idle])
    assert row["language_following"] == pytest.approx(1 / 3), "idle episodes do not count"
    assert row["language_following_ci"] == pytest.approx(wilson(1, 3))
    assert row["success_at_end"] == 0.0 and row["success"] == 0.25
    (plain,) = aggregate([score_episode(normal, _info(), PICK_STAGES, catalog)])
    assert "language_following" not in plain and "success_at_end" not in plain
    assert markdown_table([plain]).endswith("| - | - |")
