"""``instructmove eval --policy zmq://... --obs-format groot`` against a server that speaks
GR00T N1.6's framing (ZeroMQ REQ/REP, msgpack, arrays as ``np.save`` bytes) and replays the
planner oracle's recorded actions in chunks of GR00T's action horizon.

Every request is checked against the layout GR00T's policy reads (and the parts of our
export's ``meta/modality.json``); the replayed episodes score as ``instructmove eval`` of
the oracle; a server that stops answering stops the run and a resume finishes it.
"""

from __future__ import annotations

import threading

import numpy as np
import pytest
import zmq
from oracle_replay import COUNT, EPISODES, same_scores

from instructmove_ms.cli import main
from instructmove_ms.evaluation import evaluate_config
from instructmove_ms.export.groot import ACTION_HORIZON, modality
from instructmove_ms.guard import ServerError
from instructmove_ms.heldout import evaluator_config, load_set
from instructmove_ms.integrations.groot import packb, unpackb
from instructmove_ms.obs_formats import GROOT_LANGUAGE
from instructmove_ms.remote import RemotePolicy

CAMERAS = ("ext1_camera", "ext2_camera", "wrist_camera")
PARTS = {"arm": (0, 7), "gripper": (7, 8)}


class GrootReplayServer:
    """A REP socket answering like GR00T's ``PolicyServer``: each ``reset`` starts the next
    episode of ``order``, each ``get_action`` answers the next ``ACTION_HORIZON`` recorded
    actions as ``[{part: (1, horizon, D)}, {}]``. It stops answering after ``die_after``
    requests."""

    def __init__(self, plans: dict[int, np.ndarray], order: list[int], die_after=None) -> None:
        self.plans, self.order, self.die_after = plans, list(order), die_after
        self.socket = zmq.Context.instance().socket(zmq.REP)
        self.port = self.socket.bind_to_random_port("tcp://127.0.0.1")
        self.uri = f"zmq://127.0.0.1:{self.port}"
        self.requests, self.errors, self.prompts = 0, [], []
        self.plan, self.step = None, 0
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self) -> None:
        while True:
            request = unpackb(self.socket.recv())
            self.requests += 1
            if self.die_after is not None and self.requests > self.die_after:
                self.socket.close(linger=0)
                return
            self.socket.send(packb(self._answer(request)))
            if request["endpoint"] == "kill":
                self.socket.close(linger=0)
                return

    def _answer(self, request: dict):
        endpoint = request["endpoint"]
        if endpoint in ("ping", "kill"):
            return {"status": "ok", "message": "Server is running"}
        if endpoint == "reset":
            self.plan, self.step = self.plans[self.order.pop(0)], 0
            return {}
        if endpoint != "get_action":
            return {"error": f"Unknown endpoint: {endpoint}"}
        self._check(request["data"]["observation"])
        rows = np.arange(self.step, self.step + ACTION_HORIZON).clip(max=len(self.plan) - 1)
        self.step += ACTION_HORIZON
        chunk = self.plan[rows]
        return [{p: chunk[None, :, a:b] for p, (a, b) in PARTS.items()}, {}]

    def _check(self, obs: dict) -> None:
        """Record what differs from GR00T's layout (asserted by the test)."""
        try:
            assert set(obs) == {"video", "state", "language"}, sorted(obs)
            assert set(obs["video"]) == set(CAMERAS), sorted(obs["video"])
            for image in obs["video"].values():
                assert image.shape == (1, 1, 224, 224, 3) and image.dtype == np.uint8
            assert set(obs["state"]) == set(PARTS), sorted(obs["state"])
            for p, (a, b) in PARTS.items():
                state = obs["state"][p]
                assert state.shape == (1, 1, b - a) and state.dtype == np.float32
            # the arm's state is in its actions' units: near the last target played
            arm = obs["state"]["arm"][0, 0]
            assert np.allclose(arm, self.plan[max(self.step - 1, 0), :7], atol=0.2), arm
            [[prompt]] = obs["language"][GROOT_LANGUAGE]
            self.prompts.append(prompt)
        except AssertionError as exc:
            self.errors.append(str(exc))

    def stop(self) -> None:
        if self.thread.is_alive():
            with zmq.Context.instance().socket(zmq.REQ) as s:
                s.setsockopt(zmq.LINGER, 0)
                s.connect(f"tcp://127.0.0.1:{self.port}")
                s.send(packb({"endpoint": "kill"}))
                s.poll(2000)
        self.thread.join(5)


def _eval(uri: str, out, *extra: str) -> int:
    args = ["eval", "--task", EPISODES.env_id, "--robot", "franka", "--split", EPISODES.split]
    args += ["--policy", uri, "--obs-format", "groot", "--episodes", str(COUNT)]
    return main([*args, "--replan-steps", str(ACTION_HORIZON), "--out", str(out), *extra])


def test_the_groot_client_scores_the_replayed_oracle_as_instructmove_eval(
    oracle_plans, oracle_reference, tmp_path
):
    import json

    server = GrootReplayServer(oracle_plans, list(range(COUNT)))
    try:
        assert _eval(server.uri, tmp_path) == 0
    finally:
        server.stop()
    assert not server.errors, server.errors[:3]
    rows = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    for row, reference in zip(rows, oracle_reference, strict=True):
        assert row["error"] is None
        same_scores(row, reference)
    assert any(r["success"] for r in rows)
    specs = load_set(EPISODES.env_id, "franka", EPISODES.split)
    assert set(server.prompts) == {specs[k].instruction for k in range(COUNT)}
    # the parts the client sends are those the export's modality.json names
    record = {"parts": PARTS, "cameras": list(CAMERAS)}
    assert set(modality(record)["state"]) == set(PARTS)
    assert modality(record)["annotation"] == {GROOT_LANGUAGE.removeprefix("annotation."): {}}


def test_a_lost_groot_server_stops_the_run_and_a_resume_finishes_it(
    oracle_plans, oracle_reference, tmp_path
):
    import json

    config = evaluator_config(EPISODES.env_id, "franka", EPISODES.split, episodes=COUNT)
    steps = config.max_episode_steps // ACTION_HORIZON + 1  # requests per episode
    dying = GrootReplayServer(oracle_plans, list(range(COUNT)), die_after=steps + 6)
    policy = RemotePolicy(
        dying.uri, "groot", replan_steps=ACTION_HORIZON, timeout=2.0, retries=2, backoff=0.05
    )
    with pytest.raises(ServerError, match=dying.uri):
        evaluate_config(policy, config, tmp_path)
    dying.thread.join(5)
    rows = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    assert [r["episode_id"] for r in rows] == [0]
    back = GrootReplayServer(oracle_plans, [1])
    try:
        assert _eval(back.uri, tmp_path) == 0
    finally:
        back.stop()
    rows = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    for row, reference in zip(rows, oracle_reference, strict=True):
        same_scores(row, reference)


def test_groot_needs_its_server_and_an_unreachable_one_is_a_server_error():
    with pytest.raises(ValueError, match="groot"):
        RemotePolicy("ws://127.0.0.1:9", obs_format="groot")
    with pytest.raises(ValueError, match="groot"):
        RemotePolicy("zmq://127.0.0.1:9", obs_format="instructmove")
    with pytest.raises(ValueError, match="zmq://HOST:PORT"):
        RemotePolicy("zmq://nowhere", obs_format="groot")
    with pytest.raises(ServerError, match="zmq://127.0.0.1:9 unreachable after 2 attempts"):
        RemotePolicy("zmq://127.0.0.1:9", "groot", timeout=0.3, retries=2, backoff=0.05)
