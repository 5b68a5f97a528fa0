"""Serving a policy with openpi's own websocket server, and a reference policy to serve: the
replay of a LeRobot dataset of ours (v3.0 or v2.1).

``DatasetReplayPolicy`` answers each request (the ``instructmove`` observation format, see
``obs_formats``) with the recorded actions from the request's frame (its ``timestamp``) of
the episode of the prompt's task whose state at that frame is nearest the observed one: an
open-loop player of the demos that ``instructmove eval --traj DEMOS.h5 --policy ws://...``
must score as the demos did. It proves the whole chain
(export keys, state units, action order, chunking, timing) without a trained model.

Needs the ``serve`` extra (``pip install instructmove-ms[serve]``: openpi's server and client).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq

from .export.lerobot import ACTION, STATE
from .export.lerobot_formats import read_tasks

CHUNK = 50  # actions per answer, as pi0's action horizon


def _openpi():
    try:
        from openpi_client import base_policy
        from openpi_server import websocket_policy_server
    except ImportError as exc:
        raise ValueError(
            f"serving needs openpi's server and client ({exc}); "
            "install them with pip install 'instructmove-ms[serve]'"
        ) from None
    return base_policy, websocket_policy_server


class DatasetReplayPolicy:
    """The recorded actions of a LeRobot dataset at ``root``, ``chunk`` per answer (see the
    module docstring)."""

    def __init__(self, root: str | Path, chunk: int = CHUNK) -> None:
        root = Path(root)
        names = read_tasks(root)  # either format; refuses a folder without a dataset
        self.fps = float(json.loads((root / "meta" / "info.json").read_text())["fps"])
        table = pq.read_table(root / "data").to_pandas()  # every data file
        self.chunk = chunk
        self.episodes: dict[str, list[tuple[np.ndarray, np.ndarray]]] = {}
        for _, rows in table.groupby("episode_index"):
            rows = rows.sort_values("frame_index")
            states = np.stack(rows[STATE].to_numpy()).astype(np.float64)
            actions = np.stack(rows[ACTION].to_numpy()).astype(np.float32)
            task = names[int(rows["task_index"].iloc[0])]
            self.episodes.setdefault(task, []).append((states, actions))

    def infer(self, obs: dict) -> dict:
        """``actions`` (chunk, dim) from the request's frame of the prompt's episode."""
        task = obs["prompt"]
        if task not in self.episodes:
            raise ValueError(f"no episode of the task {task!r} in the dataset")
        state = np.asarray(obs[STATE], dtype=np.float64)
        frame = round(float(np.asarray(obs["timestamp"]).reshape(-1)[0]) * self.fps)
        gaps = [
            np.abs(states[min(frame, len(states) - 1)] - state).max()
            for states, _ in self.episodes[task]
        ]
        actions = self.episodes[task][int(np.argmin(gaps))][1][frame : frame + self.chunk]
        if not len(actions):  # past the recording's end: hold its last action
            actions = self.episodes[task][int(np.argmin(gaps))][1][-1:]
        pad = np.repeat(actions[-1:], self.chunk - len(actions), axis=0)
        return {"actions": np.concatenate([actions, pad])}

    def reset(self) -> None:
        pass


def serve(policy, host: str = "127.0.0.1", port: int = 8000, metadata: dict | None = None):
    """Serve ``policy`` (``infer(obs) -> {"actions": ...}``) with openpi's websocket server
    until the process is stopped."""
    base_policy, websocket_policy_server = _openpi()
    wrapped = type("Served", (base_policy.BasePolicy,), {"infer": lambda _, obs: policy.infer(obs)})
    server = websocket_policy_server.WebsocketPolicyServer(wrapped(), host, port, metadata or {})
    server.serve_forever()
