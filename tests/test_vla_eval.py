"""vla-eval runs our stored episodes through its own orchestrator, websocket and model server.

A model server of ours (vla-eval's ``PredictModelServer``) plays the planner oracle's
recorded actions for the episode vla-eval says it is running; vla-eval's results must hold
the same success, success at the end, S and stage flags as ``instructmove eval`` of the
oracle on the same stored episodes, and every observation must carry the cameras, state and
instruction the benchmark declares.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from oracle_replay import COUNT, EPISODES, same_scores
from vla_eval.api import evaluate as vla_evaluate
from vla_eval.model_servers.predict import PredictModelServer

from instructmove_ms.heldout import load_set

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "integrations" / "vla_eval" / "instructmove_franka.yaml"
WIDTH, HEIGHT = 128, 96


class ReplayServer(PredictModelServer):
    """Answers each observation with the recorded action of the episode and step."""

    def __init__(self, plans: dict[int, np.ndarray]) -> None:
        super().__init__()
        self.plans, self.index, self.seen = plans, {}, []

    async def on_episode_start(self, config: dict, ctx) -> None:
        await super().on_episode_start(config, ctx)
        self.index[ctx.session_id] = int(config["task"]["episode_idx"])

    def predict(self, obs: dict, ctx) -> dict:
        k = self.index[ctx.session_id]
        self.seen.append((k, ctx.step, obs))
        plan = self.plans[k]
        return {"actions": plan[min(ctx.step, len(plan) - 1)]}


def test_vla_eval_scores_the_oracle_as_instructmove_eval(
    oracle_plans, oracle_reference, tmp_path
) -> None:
    server = ReplayServer(oracle_plans)
    overrides = {
        "episodes_per_task": COUNT,
        "params": {"tasks": [EPISODES.env_id], "image_size": [WIDTH, HEIGHT]},
    }
    [result] = vla_evaluate(
        server,
        str(CONFIG),
        docker=False,
        output_dir=tmp_path,
        no_save=True,
        benchmark_overrides=overrides,
    )
    [task] = result["tasks"]
    assert task["task"] == "PickCategory/franka/unseen_category"
    episodes = sorted(task["episodes"], key=lambda e: e["episode_id"])
    assert [e["episode_id"] for e in episodes] == list(range(COUNT))
    assert not [e for e in episodes if e.get("failure_reason")]
    for episode, row in zip(episodes, oracle_reference, strict=True):
        assert episode["steps"] == len(oracle_plans[row["episode_id"]])  # the whole horizon
        same_scores(episode["metrics"], row)
    assert any(row["success"] for row in oracle_reference)  # the comparison sees a success
    expected = np.mean([row["stage_score"] for row in oracle_reference])
    assert result["mean_stage_score"] == pytest.approx(expected)
    assert set(result["metric_keys"]) >= {"success", "success_at_end", "stage_score", "reach"}

    specs = load_set(EPISODES.env_id, "franka", EPISODES.split)
    first = {k: obs for k, step, obs in server.seen if step == 0}
    for k, obs in first.items():
        assert obs["task_description"] == specs[k].instruction
        assert set(obs["images"]) == {"ext1_camera", "ext2_camera", "wrist_camera"}
        for image in obs["images"].values():
            assert image.shape == (HEIGHT, WIDTH, 3) and image.dtype == np.uint8
        state = np.asarray(obs["state"])
        assert state.shape == (8,) and state.dtype == np.float32
    assert len(server.seen) == sum(len(p) for p in oracle_plans.values())  # one query per step


def test_benchmark_options_are_checked() -> None:
    from instructmove_ms.integrations.vla_eval import InstructMoveBenchmark

    with pytest.raises(ValueError, match="'PickNothing'"):
        InstructMoveBenchmark(tasks=["PickNothing"])
    with pytest.raises(ValueError, match="'sideways'"):
        InstructMoveBenchmark(conditions=["sideways"])
    with pytest.raises(ValueError, match="'train'"):
        InstructMoveBenchmark(split="train")
    with pytest.raises(ValueError, match="set version 1"):
        InstructMoveBenchmark(set_version=1)
    bench = InstructMoveBenchmark(conditions=["all"], send_wrist_image=False)
    names = [t["name"] for t in bench.get_tasks()]
    assert len(names) == len(set(names)) == 4 * 5
    assert bench.get_metadata()["max_episodes_per_task"] == 100
    assert {"reach_pick", "place", "lift"} <= set(bench.get_metric_keys())


def test_a_released_set_version_plays_its_own_stored_episodes() -> None:
    """Beside a newer benchmark version, ``set_version: 7`` reproduces results on 1.0: its
    tasks are named apart and play 1.0's stored episodes (which differ from the newer
    version's)."""
    from instructmove_ms import heldout
    from instructmove_ms.integrations.vla_eval import InstructMoveBenchmark

    env_id, split = "PickCategory-InstructMove", "unseen_category"
    played = {}
    for version in (7, None):
        bench = InstructMoveBenchmark(tasks=[env_id], robot="franka", set_version=version)
        (task,) = bench.get_tasks()
        assert task.get("set_version") == version and task["name"].endswith("/v7") == bool(version)
        episodes = bench._episodes(task["name"]).config.episodes
        played[version] = [e.spec.instruction for e in episodes]
    for version in (7, None):
        stored = heldout.load_set(env_id, "franka", split, version=version)
        assert played[version] == [s.instruction for s in stored]
    assert played[7] != played[None]
