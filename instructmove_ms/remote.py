"""A policy served on another machine, over websocket with msgpack-numpy messages.

This is the protocol of openpi's policy server: on connection the server sends its metadata;
each request is a msgpack map of numpy arrays (the observation, with the instruction under
``prompt``) and each reply a map whose ``actions`` is one action or a chunk of them (the
client plays a chunk out before asking again). Arrays travel as maps with ``__ndarray__``,
``data``, ``dtype`` and ``shape``; a text frame from the server is an error report (the
policy's failure).

A server that cannot be reached, or a connection that closes or times out, is not the
policy's failure: the client reconnects with a bounded back-off (``RETRIES`` attempts,
waits doubling from ``BACKOFF`` seconds) and asks again, and raises ``guard.ServerError``
naming the server if it stays away.
"""

from __future__ import annotations

import time
from contextlib import ExitStack
from typing import Any

import msgpack
import numpy as np
import torch
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import ClientConnection, connect

from .guard import ServerError

RETRIES = 5  # connection attempts before the server counts as gone
BACKOFF = 0.5  # seconds before the second attempt; doubled for each further one
#: What a lost or unreachable server raises (refused, reset, closed, timed out).
NETWORK_ERRORS = (OSError, TimeoutError, ConnectionClosed)


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


def _unbatch(obs: Any) -> Any:
    """ManiSkill's batched observation (one sub-scene) as plain numpy arrays."""
    if isinstance(obs, dict):
        return {k: _unbatch(v) for k, v in obs.items()}
    return np.asarray(obs.detach().cpu().numpy() if isinstance(obs, torch.Tensor) else obs)[0]


class RemotePolicy:
    """Evaluator-convention policy that asks a websocket policy server for actions."""

    def __init__(
        self,
        uri: str,
        obs_mode: str = "rgb",
        control_mode: str = "pd_joint_pos",
        timeout: float = 60.0,
        retries: int = RETRIES,
        backoff: float = BACKOFF,
    ) -> None:
        self.uri, self.obs_mode, self.control_mode = uri, obs_mode, control_mode
        self.timeout, self.retries, self.backoff = timeout, retries, backoff
        self.socket: ClientConnection | None = None
        self._stack = ExitStack()
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
                self.socket = self._stack.enter_context(
                    connect(self.uri, max_size=None, open_timeout=self.timeout)
                )
                self.metadata = unpackb(self.socket.recv(timeout=self.timeout))
                return
            except NETWORK_ERRORS as exc:
                self.close()
                error = exc
        raise ServerError(
            f"policy server {self.uri} unreachable after {self.retries} attempts "
            f"({type(error).__name__}: {error})"
        )

    def _ask(self, request: bytes) -> bytes | str:
        """The server's reply to ``request``, reconnecting once per lost connection."""
        try:
            self.socket.send(request)
            return self.socket.recv(timeout=self.timeout)
        except NETWORK_ERRORS:
            self._reconnect()
            try:
                self.socket.send(request)
                return self.socket.recv(timeout=self.timeout)
            except NETWORK_ERRORS as exc:
                raise ServerError(f"policy server {self.uri} lost the connection ({exc})") from exc

    def get_obs_mode(self) -> str:
        return self.obs_mode

    def get_control_mode(self) -> str:
        return self.control_mode

    def bind(self, env) -> None:
        self.prompt = env.unwrapped.get_language_instruction()[0]

    def reset(self, obs) -> None:
        self.chunk = []

    def act(self, obs) -> np.ndarray:
        if not self.chunk:
            reply = self._ask(packb({"observation": _unbatch(obs), "prompt": self.prompt}))
            if isinstance(reply, str):
                raise RuntimeError(f"policy server at {self.uri} failed: {reply}")
            actions = np.asarray(unpackb(reply)["actions"], dtype=np.float32)
            self.chunk = list(actions.reshape(-1, actions.shape[-1]))
        return self.chunk.pop(0)[None]

    def close(self) -> None:
        self._stack.close()
        self.socket = None
