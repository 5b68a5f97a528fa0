"""GR00T's policy server as a channel of ``remote.RemotePolicy`` (``zmq://HOST:PORT``).

Isaac-GR00T N1.6/N1.7 (``gr00t/eval/run_gr00t_server.py``, default port 5555) serves a
policy over ZeroMQ REQ/REP: each request is a msgpack map ``{"endpoint": ..., "data": ...}``
(``ping`` and ``get_modality_config`` without data; ``reset`` with ``{"options": ...}``;
``get_action`` with ``{"observation": ..., "options": ...}``), numpy arrays travel as
``{"__ndarray_class__": True, "as_npy": <np.save bytes>}``, and ``get_action`` answers
``[actions, info]``; a map with ``error`` is the server's failure. The observation is the
``groot`` format's (``obs_formats``). GR00T N1.5's server differs: flat keys
(``video.<camera>``, ``state.<part>``, ``annotation.human.task_description``: [text]) in a
request without ``observation``, torch-serialised, and flat ``action.<part>`` replies
without the batch axis; it is not supported.

A server that does not answer within the timeout (REQ/REP cannot tell a dead server from a
busy one) counts as lost: the socket is dropped (a REQ socket that missed its reply cannot
send again) and the policy reconnects as over websocket.
"""

from __future__ import annotations

import io
from typing import Any

import msgpack
import numpy as np

from . import require

zmq = require("zmq", "groot", "a GR00T policy server")

CONNECT_TIMEOUT = 10.0  # seconds for the ping that opens a connection


def _encode(obj: Any) -> Any:
    if isinstance(obj, np.ndarray):
        buffer = io.BytesIO()
        np.save(buffer, obj, allow_pickle=False)
        return {"__ndarray_class__": True, "as_npy": buffer.getvalue()}
    if isinstance(obj, np.generic):
        return obj.item()
    raise TypeError(f"cannot send a {type(obj).__name__} to a GR00T server")


def _decode(obj: dict) -> Any:
    if "__ndarray_class__" in obj:
        return np.load(io.BytesIO(obj["as_npy"]), allow_pickle=False)
    return obj


def packb(obj: Any) -> bytes:
    return msgpack.packb(obj, default=_encode)


def unpackb(data: bytes) -> Any:
    return msgpack.unpackb(data, object_hook=_decode)


class ZmqChannel:
    """A REQ socket to GR00T's server at ``zmq://HOST:PORT``."""

    errors = (ConnectionError,)

    def __init__(self, uri: str, timeout: float) -> None:
        host, _, port = uri.removeprefix("zmq://").rpartition(":")
        if not host or not port.isdigit():
            raise ValueError(f"GR00T server address {uri!r}: expected zmq://HOST:PORT")
        self.uri, self.address, self.timeout = uri, f"tcp://{host}:{port}", timeout
        self.socket = None

    def open(self) -> dict:
        """Connect and ping; the server's answer (its status)."""
        self.close()
        self.socket = zmq.Context.instance().socket(zmq.REQ)
        self.socket.setsockopt(zmq.LINGER, 0)
        self.socket.connect(self.address)
        return self._call("ping", timeout=min(self.timeout, CONNECT_TIMEOUT))

    def request(self, request: dict) -> dict:
        actions, info = self._call("get_action", {"observation": request, "options": None})
        return {"actions": actions, "info": info}

    def reset(self) -> None:
        self._call("reset", {"options": None})

    def _call(self, endpoint: str, data: dict | None = None, timeout: float | None = None) -> Any:
        message: dict = {"endpoint": endpoint}
        if data is not None:
            message["data"] = data
        wait = int(1000 * (timeout or self.timeout))
        try:
            self.socket.send(packb(message), flags=zmq.NOBLOCK)
            if not self.socket.poll(wait, zmq.POLLIN):
                raise ConnectionError(f"no answer to {endpoint!r} within {wait / 1000:g} s")
            reply = self.socket.recv()
        except zmq.ZMQError as exc:
            self.close()
            raise ConnectionError(str(exc)) from exc
        except ConnectionError:
            self.close()
            raise
        if reply == b"ERROR":
            raise RuntimeError(f"GR00T server at {self.uri} failed ({endpoint})")
        answer = unpackb(reply)
        if isinstance(answer, dict) and "error" in answer:
            raise RuntimeError(f"GR00T server at {self.uri} failed: {answer['error']}")
        return answer

    def close(self) -> None:
        if self.socket is not None:
            self.socket.close(linger=0)
            self.socket = None
