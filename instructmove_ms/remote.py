"""A policy served on another machine, over websocket with msgpack-numpy messages.

This is the protocol of openpi's policy server: on connection the server sends its metadata;
each request is a msgpack map of numpy arrays (the observation, with the instruction under
``prompt``) and each reply a map whose ``actions`` is one action or a chunk of them (the
client plays a chunk out before asking again). Arrays travel as maps with ``__ndarray__``,
``data``, ``dtype`` and ``shape``; a text frame from the server is an error report (the
policy's failure). The observation's keys and units, and what the actions mean, follow a
named format (``obs_formats``); the client plays the first ``replan_steps`` actions of each
chunk before asking again (openpi's examples replan every 5 steps) and keeps the server's
own timing (its replies' ``server_timing``).

GR00T's policy server (``zmq://HOST:PORT``, the ``groot`` format) is reached through
``integrations.groot``'s channel instead; the rest is the same.

A server that cannot be reached, or a connection that closes or times out, is not the
policy's failure: the client reconnects with a bounded back-off (``RETRIES`` attempts,
waits doubling from ``BACKOFF`` seconds) and asks again, and raises ``guard.ServerError``
naming the server if it stays away.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from contextlib import ExitStack
from typing import Any

import msgpack
import numpy as np
import torch
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import ClientConnection, connect

from .agents.interface import PolicyInterface
from .guard import ServerError
from .obs_formats import FORMATS
from .validation import check_choice

REPLAN_STEPS = 5  # actions of a chunk played before asking again, as openpi's examples do
RETRIES = 5  # connection attempts before the server counts as gone
BACKOFF = 0.5  # seconds before the second attempt; doubled for each further one
#: What a lost or unreachable server raises (refused, reset, closed, timed out).
NETWORK_ERRORS = (OSError, TimeoutError, ConnectionClosed)
RESIZABLE = ("instructmove", "groot")  # the formats rendered at the export's size


def _encode(obj: Any) -> Any:
    if isinstance(obj, torch.Tensor):
        obj = obj.detach().cpu().numpy()
    if isinstance(obj, np.ndarray):
        return {
            b"__ndarray__": True,
            b"data": obj.tobytes(),
            b"dtype": obj.dtype.str,
            b"shape": obj.shape,
        }
    if isinstance(obj, np.generic):
        return {b"__npgeneric__": True, b"data": obj.item(), b"dtype": obj.dtype.str}
    raise TypeError(f"cannot send a {type(obj).__name__} to a policy server")


def _decode(obj: dict) -> Any:
    if b"__ndarray__" in obj:
        return np.ndarray(buffer=obj[b"data"], dtype=np.dtype(obj[b"dtype"]), shape=obj[b"shape"])
    if b"__npgeneric__" in obj:
        return np.dtype(obj[b"dtype"]).type(obj[b"data"])
    return obj


def packb(obj: Any) -> bytes:
    return msgpack.packb(obj, default=_encode)


def unpackb(data: bytes) -> Any:
    return msgpack.unpackb(data, object_hook=_decode)


class WebsocketChannel:
    """openpi's protocol: the server's metadata on connection, a msgpack map per request
    and per reply; a text frame is the policy's error report."""

    errors = NETWORK_ERRORS

    def __init__(self, uri: str, timeout: float) -> None:
        self.uri, self.timeout = uri, timeout
        self.socket: ClientConnection | None = None
        self._stack = ExitStack()

    def open(self) -> dict:
        """Connect; the server's metadata."""
        self.socket = self._stack.enter_context(
            connect(self.uri, max_size=None, open_timeout=self.timeout)
        )
        return unpackb(self.socket.recv(timeout=self.timeout))

    def request(self, request: dict) -> dict:
        self.socket.send(packb(request))
        reply = self.socket.recv(timeout=self.timeout)
        if isinstance(reply, str):
            raise RuntimeError(f"policy server at {self.uri} failed: {reply}")
        return unpackb(reply)

    def reset(self) -> None:
        """openpi's servers keep no episode state."""

    def close(self) -> None:
        self._stack.close()
        self.socket = None


def channel(uri: str, timeout: float):
    """The channel of a policy server's address: ``ws://``/``wss://`` (openpi's protocol)
    or ``zmq://`` (GR00T's)."""
    if uri.startswith(("ws://", "wss://")):
        return WebsocketChannel(uri, timeout)
    if uri.startswith("zmq://"):
        from .integrations import require

        groot = require("instructmove_ms.integrations.groot", "groot", "a GR00T policy server")
        return groot.ZmqChannel(uri, timeout)
    raise ValueError(f"policy server address {uri!r}: expected ws://, wss:// or zmq://HOST:PORT")


class RemotePolicy:
    """Evaluator-convention policy that asks a policy server for actions, in the
    observation format ``obs_format`` (see ``obs_formats``): openpi's websocket protocol
    (``ws://``) or GR00T's ZeroMQ one (``zmq://``, the ``groot`` format); ``image_size``
    (width, height) renders the ``instructmove`` and ``groot`` formats' cameras at another
    size than 224 x 224 (a model trained on an export of that size)."""

    def __init__(
        self,
        uri: str,
        obs_format: str = "instructmove",
        control_mode: str = "pd_joint_pos",
        replan_steps: int = REPLAN_STEPS,
        obs_mode: str = "rgb",
        timeout: float = 60.0,
        retries: int = RETRIES,
        backoff: float = BACKOFF,
        image_size: tuple[int, int] | None = None,
    ) -> None:
        check_choice("observation format", obs_format, FORMATS)
        if replan_steps < 1:
            raise ValueError(f"replan_steps must be at least 1, got {replan_steps}")
        if (obs_format == "groot") != uri.startswith("zmq://"):
            raise ValueError(
                f"--obs-format {obs_format} with {uri}: GR00T's server (zmq://) speaks the "
                "groot format, and only it does"
            )
        self.uri, self.format, self.control_mode = uri, FORMATS[obs_format], control_mode
        if image_size is not None:
            if obs_format not in RESIZABLE:
                raise ValueError(
                    f"an image size is for the {' and '.join(RESIZABLE)} formats; "
                    f"{obs_format} sends openpi's 224 x 224"
                )
            if min(image_size) < 1:
                raise ValueError(f"image size must be positive, got {image_size}")
            self.format = dataclasses.replace(self.format, render=tuple(image_size))
        self.obs_mode = obs_mode if obs_format == "maniskill" else "rgb"
        self.replan_steps = replan_steps
        self.timeout, self.retries, self.backoff = timeout, retries, backoff
        self.interface: PolicyInterface | None = None
        self.steps, self.fps = 0, 30.0  # the episode's steps so far; bind reads the env's rate
        self.timing: list[dict] = []
        self.channel = channel(uri, timeout)
        self.metadata: dict = {}
        self.chunk: list[np.ndarray] = []
        self.prompt = ""
        self._reconnect()

    def _reconnect(self) -> None:
        """(Re)open the connection and read the server's metadata, retrying with the
        back-off; a ``ServerError`` naming the server when every attempt failed."""
        self.close()
        error: Exception | None = None
        for attempt in range(self.retries):
            if attempt:
                time.sleep(self.backoff * 2 ** (attempt - 1))
            try:
                self.metadata = self.channel.open()
                return
            except self.channel.errors as exc:
                self.close()
                error = exc
        raise ServerError(
            f"policy server {self.uri} unreachable after {self.retries} attempts "
            f"({type(error).__name__}: {error})"
        )

    def _ask(self, call: Callable[[], Any]) -> Any:
        """What ``call`` on the channel returns, reconnecting once per lost connection."""
        try:
            return call()
        except self.channel.errors:
            self._reconnect()
            try:
                return call()
            except self.channel.errors as exc:
                raise ServerError(f"policy server {self.uri} lost the connection ({exc})") from exc

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return self.control_mode

    def get_sensor_configs(self) -> dict | None:
        """The camera resolution the format's images come from (None: the robot's)."""
        if self.format.render is None:
            return None
        width, height = self.format.render
        return {"width": width, "height": height}

    def bind(self, env) -> None:
        u = env.unwrapped
        self.prompt = u.get_language_instruction()[0]
        self.interface = u.agent.policy_interface()
        self.fps = float(u.control_freq)

    def reset(self, obs) -> None:
        self.chunk, self.steps = [], 0
        self._ask(self.channel.reset)

    def held_actions(self) -> int:
        """Actions of the last chunk still to play: the next ``act`` reads no observation
        while there are any."""
        return len(self.chunk)

    def act(self, obs) -> np.ndarray:
        if not self.chunk:
            time_s = self.steps / self.fps
            request = self.format.encode(obs, self.prompt, self.interface, time_s)
            sent = time.perf_counter()
            reply = self._ask(lambda: self.channel.request(request))
            timing = {"round_trip_ms": 1000.0 * (time.perf_counter() - sent)}
            timing.update(reply.get("server_timing", {}))
            self.timing.append(timing)
            actions = self.format.actions(reply, self.interface)
            self.chunk = list(actions[: self.replan_steps])
        self.steps += 1
        return self.chunk.pop(0)[None]

    def stats(self) -> dict:
        """The requests made and the timing the server reported (ms: mean and median)."""
        out: dict = {"server": self.uri, "format": self.format.name, "requests": len(self.timing)}
        for key in sorted({k for t in self.timing for k in t}):
            values = [float(t[key]) for t in self.timing if key in t]
            out[key] = {"mean": float(np.mean(values)), "median": float(np.median(values))}
        return out

    def __getstate__(self) -> dict:
        """Pickled without its connection (for evaluation workers): the copy connects
        again and keeps its own timing."""
        state = {k: v for k, v in self.__dict__.items() if k != "channel"}
        return {**state, "timing": [], "chunk": []}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state, channel=channel(state["uri"], state["timeout"]))
        self._reconnect()

    def close(self) -> None:
        self.channel.close()
