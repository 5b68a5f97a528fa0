"""The remote-policy client against a small openpi-style server on loopback."""

from __future__ import annotations

import threading

import numpy as np
from websockets.sync.server import serve

from instructmove_ms.evaluation import evaluate
from instructmove_ms.remote import RemotePolicy, packb, unpackb

CHUNK = 4


def test_arrays_round_trip_in_the_openpi_format():
    data = {"a": np.arange(6, dtype=np.float32).reshape(2, 3), "b": np.int64(7), "c": "text"}
    back = unpackb(packb(data))
    np.testing.assert_array_equal(back["a"], data["a"])
    assert back["a"].dtype == np.float32 and back["b"] == 7 and back["c"] == "text"


def test_evaluation_through_a_policy_server(tmp_path):
    seen = []

    def handler(ws):
        ws.send(packb({"server": "test"}))
        for message in ws:
            request = unpackb(message)
            seen.append((request["prompt"], sorted(request["observation"])))
            qpos = request["observation"]["agent"]["qpos"][:8].astype(np.float32)
            ws.send(packb({"actions": np.tile(qpos, (CHUNK, 1))}))  # hold still

    with serve(handler, "127.0.0.1", 0) as server:
        port = server.socket.getsockname()[1]
        thread = threading.Thread(target=server.serve_forever, daemon=True)
        thread.start()
        policy = RemotePolicy(f"ws://127.0.0.1:{port}", obs_mode="state_dict")
        assert policy.metadata == {"server": "test"}
        summary = evaluate(
            policy, "PickCategory-InstructMove", "seen", tmp_path, robot="franka", episodes=1
        )
        policy.close()
        server.shutdown()
    assert summary["episodes"] == 1 and summary["groups"][0]["reach"] == 0.0
    horizon = 300
    assert len(seen) == horizon // CHUNK + (horizon % CHUNK > 0), "one request per chunk"
    prompt, keys = seen[0]
    assert prompt.startswith(
        ("pick", "grab", "lift", "grasp", "take", "raise", "please", "can", "get")
    )
    assert {"agent", "extra"} <= set(keys)
