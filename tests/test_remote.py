"""The remote-policy client against a small openpi-style server on loopback."""

from __future__ import annotations

import dataclasses
import threading

import numpy as np
import pytest
from websockets.sync.server import serve

from instructmove_ms import heldout
from instructmove_ms.evaluation import evaluate, evaluate_config
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
        uri = f"ws://127.0.0.1:{port}"
        policy = RemotePolicy(uri, obs_format="maniskill", obs_mode="state_dict")
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


def _shapes(request: dict) -> dict:
    """Each key's (shape, dtype), nested dicts flattened with "/"."""
    out = {}
    for key, value in request.items():
        if isinstance(value, dict):
            out.update({f"{key}/{k}": v for k, v in _shapes(value).items()})
        elif isinstance(value, str):
            out[key] = "str"
        else:
            out[key] = (tuple(value.shape), str(value.dtype))
    return out


IMAGE = ((224, 224, 3), "uint8")
FORMATS = {
    ("franka", "instructmove"): {
        "observation.images.ext1_camera": IMAGE,
        "observation.images.ext2_camera": IMAGE,
        "observation.images.wrist_camera": IMAGE,
        "observation.state": ((8,), "float32"),
        "timestamp": ((1,), "float32"),
        "prompt": "str",
    },
    ("franka", "droid"): {
        "observation/exterior_image_1_left": IMAGE,
        "observation/exterior_image_2_left": IMAGE,
        "observation/wrist_image_left": IMAGE,
        "observation/joint_position": ((7,), "float32"),
        "observation/gripper_position": ((1,), "float32"),
        "prompt": "str",
    },
    ("piperx", "aloha"): {
        "images/cam_high": ((3, 224, 224), "uint8"),
        "images/cam_left_wrist": ((3, 224, 224), "uint8"),
        "images/cam_right_wrist": ((3, 224, 224), "uint8"),
        "state": ((14,), "float32"),
        "prompt": "str",
    },
    ("piperx", "instructmove"): {
        "observation.images.static_camera": IMAGE,
        "observation.images.left_hand_camera": IMAGE,
        "observation.images.right_hand_camera": IMAGE,
        "observation.state": ((14,), "float32"),
        "timestamp": ((1,), "float32"),
        "prompt": "str",
    },
}
#: Where each format keeps the robot's state, and how a held state becomes its action.
HOLD = {
    "instructmove": lambda r: r["observation.state"],
    "droid": lambda r: np.concatenate(
        [r["observation/joint_position"], r["observation/gripper_position"]]
    ),
    "aloha": lambda r: r["state"],
}


@pytest.mark.parametrize(("robot", "name"), sorted(FORMATS))
def test_formats_send_the_documented_keys_and_their_actions_hold_the_robot(robot, name, tmp_path):
    """A server that answers every request with the state it was sent, in its format's
    action layout: the robot holds still only if keys, order and units agree both ways."""
    requests = []

    def handler(ws):
        ws.send(packb({}))
        for message in ws:
            request = unpackb(message)
            requests.append(request)
            held = HOLD[name](request).astype(np.float32)
            ws.send(packb({"actions": held[None], "server_timing": {"infer_ms": 1.5}}))

    config = heldout.evaluator_config("PickCategory-InstructMove", robot, "seen", episodes=1)
    config = dataclasses.replace(config, max_episode_steps=12)
    with serve(handler, "127.0.0.1", 0) as server:
        threading.Thread(target=server.serve_forever, daemon=True).start()
        uri = f"ws://127.0.0.1:{server.socket.getsockname()[1]}"
        policy = RemotePolicy(uri, obs_format=name, replan_steps=1)
        summary = evaluate_config(policy, config, tmp_path)
        policy.close()
        server.shutdown()
    assert _shapes(requests[0]) == FORMATS[(robot, name)]
    assert requests[0]["prompt"] == config.episodes[0].spec.instruction
    first, last = HOLD[name](requests[0]), HOLD[name](requests[-1])
    assert len(requests) == 12 and np.abs(last - first).max() < 0.02, "the robot held still"
    assert summary["policy"]["requests"] == 12
    assert summary["policy"]["infer_ms"]["median"] == 1.5


def test_the_instructmove_format_renders_at_the_image_size_asked_for(tmp_path):
    """A model trained on an export of another size gets its cameras at that size."""
    requests = []

    def handler(ws):
        ws.send(packb({}))
        for message in ws:
            requests.append(unpackb(message))
            ws.send(packb({"actions": requests[-1]["observation.state"][None]}))

    config = heldout.evaluator_config("PickCategory-InstructMove", "franka", "seen", episodes=1)
    config = dataclasses.replace(config, max_episode_steps=2)
    with serve(handler, "127.0.0.1", 0) as server:
        threading.Thread(target=server.serve_forever, daemon=True).start()
        uri = f"ws://127.0.0.1:{server.socket.getsockname()[1]}"
        policy = RemotePolicy(uri, replan_steps=1, image_size=(128, 96))
        evaluate_config(policy, config, tmp_path)
        policy.close()
        server.shutdown()
    shapes = _shapes(requests[0])
    for camera in ("ext1_camera", "ext2_camera", "wrist_camera"):
        assert shapes[f"observation.images.{camera}"] == ((96, 128, 3), "uint8")
    assert requests[0]["observation.images.ext1_camera"].std() > 5, "an image, not a blank"


def test_an_image_size_is_refused_for_the_fixed_size_formats():
    refused = "instructmove and groot formats; droid sends openpi's 224"
    with pytest.raises(ValueError, match=refused):
        RemotePolicy("ws://127.0.0.1:9", obs_format="droid", image_size=(128, 96))
