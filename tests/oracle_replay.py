"""The planner oracle's actions on a stored episode, recorded for a test's model server.

A harness test serves these actions from a model server of its own (vla-eval's, GR00T's
framing) and checks that the harness's run of the same episode scores what the oracle scores
under ``instructmove eval``: the replay is played in a fresh env of the same episode, which
the CPU simulation makes the same physics.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from instructmove_ms import heldout
from instructmove_ms.integrations.stored import CONTROL_MODE, EpisodeSet
from instructmove_ms.policies import OraclePolicy

#: The stored episodes the harness tests replay the oracle on, and how many of them.
EPISODES = EpisodeSet("PickCategory-InstructMove", "franka", "unseen_category")
COUNT = 2


def oracle_actions(episodes: EpisodeSet, indices: list[int]) -> dict[int, np.ndarray]:
    """Stored episode index -> the oracle's (horizon, action dim) actions."""
    config = heldout.evaluator_config(
        episodes.env_id, episodes.robot, episodes.split, episodes.condition
    )
    env = gym.make(
        config.env_id,
        **config.env_kwargs,
        obs_mode="state",
        control_mode=CONTROL_MODE,
        render_backend="none",
    )
    out = {}
    try:
        for index in indices:
            episode = config.episodes[index]
            obs, _ = env.reset(seed=episode.seed, options={"episode": episode.spec.to_dict()})
            policy = OraclePolicy()
            policy.bind(env)
            policy.reset(obs, seed=episode.seed)
            actions = []
            for _ in range(config.max_episode_steps):
                action = policy.act(obs)
                obs, *_ = env.step(action)
                actions.append(np.asarray(action, dtype=np.float32)[0])
            out[index] = np.stack(actions)
    finally:
        env.close()
    return out


def oracle_rows(episodes: EpisodeSet, count: int, out) -> list[dict]:
    """``instructmove eval``'s rows for the oracle on the set's first ``count`` episodes."""
    import json

    from instructmove_ms.cli import main

    args = ["eval", "--task", episodes.env_id, "--robot", episodes.robot, "--split"]
    args += [episodes.split, "--policy", "oracle", "--episodes", str(count), "--out", str(out)]
    assert main(args) == 0
    return [json.loads(line) for line in (out / "episodes.jsonl").read_text().splitlines()]


def same_scores(theirs: dict, ours: dict) -> None:
    """Assert a harness's episode score (a row, or flat metrics with the stage flags beside
    the scores) equals ``instructmove eval``'s row."""
    for key in ("success", "success_at_end", "stage_score", "choice"):
        assert theirs[key] == ours[key], (key, theirs[key], ours[key])
    stages = theirs.get("stages", theirs)
    assert {k: stages[k] for k in ours["stages"]} == ours["stages"]
