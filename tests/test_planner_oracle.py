"""The planner-based oracle (the demo generator's plans as a policy) on the stored sets."""

from __future__ import annotations

import pytest

from instructmove_ms.evaluation import evaluate
from instructmove_ms.policies import PlannerOraclePolicy
from instructmove_ms.tasks import TASKS

EPISODES = 8


@pytest.mark.parametrize("env_id", sorted(TASKS))
def test_oracle_scores_on_the_stored_set(env_id, tmp_path):
    summary = evaluate(PlannerOraclePolicy(), env_id, "seen", tmp_path, episodes=EPISODES)
    (group,) = summary["groups"]
    assert group["robot"] == TASKS[env_id].default_robot and group["episodes"] == EPISODES
    assert summary["errors"] == 0
    assert group["stage_score"] >= 0.95 and group["grounding_error"] == 0.0


def test_oracle_without_a_target_holds_still(tmp_path):
    task = "PickCategory-InstructMove"
    policy = PlannerOraclePolicy()
    summary = evaluate(
        policy, task, "seen", tmp_path, robot="franka", condition="empty", episodes=2
    )
    (group,) = summary["groups"]
    assert group["any_reach"] == 0.0 and group["any_lift"] == 0.0
