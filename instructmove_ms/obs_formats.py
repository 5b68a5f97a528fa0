"""Observation formats for a served policy: what a request holds and what its actions mean.

A policy server (openpi's websocket protocol) gets one observation per request and answers
with ``actions``, a chunk of them. Each format names the keys, shapes and units on both
sides, so that a model trained on one convention is served without a transform of its own:

- ``instructmove``: the keys of our LeRobot export (``export.lerobot``):
  ``observation.images.<camera>`` (H, W, 3 uint8, the export's 224 x 224 by default),
  ``observation.state`` (float32, the robot's joint-space policy interface), ``timestamp``
  (float32 (1,), seconds since the episode began, as the dataset's) and ``prompt``; actions
  are that interface (the ``pd_joint_pos`` action).
- ``droid`` (the Franka): openpi's DROID keys: ``observation/exterior_image_1_left``,
  ``observation/exterior_image_2_left``, ``observation/wrist_image_left`` (224 x 224 x 3
  uint8, the 16:9 cameras letterboxed as openpi's DROID example does),
  ``observation/joint_position`` (7, rad), ``observation/gripper_position`` (1, DROID's
  closedness: 0 open, 1 closed) and ``prompt``; actions are 8-D: 7 joint values (absolute
  positions under ``pd_joint_pos``, the default control mode) and the gripper's closedness.
- ``aloha`` (the PiperX): openpi's ALOHA keys: ``images`` with ``cam_high``,
  ``cam_left_wrist``, ``cam_right_wrist`` (3 x 224 x 224 uint8, channels first, letterboxed),
  ``state`` (14: left j1..j6, left gripper, right j1..j6, right gripper; grippers as the
  opening's fraction, 0 closed, 1 open) and ``prompt``; actions in that order and those units.
- ``maniskill``: the env's own nested observation under ``observation`` (as ManiSkill gives
  it, one sub-scene) and ``prompt``; actions are the env's.
- ``groot`` (GR00T N1.6/N1.7's policy server, ``integrations.groot``): ``video`` (camera ->
  (1, 1, H, W, 3) uint8 at the export's 224 x 224), ``state`` (part -> (1, 1, D) float32, the
  parts of the export's ``meta/modality.json``: ``arm``, ``gripper`` or ``left_arm`` ...
  ``right_gripper``) and ``language`` (``annotation.human.task_description`` -> [[text]]);
  the server answers part -> (1, horizon, D) in the same units, put back in the interface's
  order.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import cv2
import numpy as np
import torch

from .agents.interface import PolicyInterface

SIZE = 224  # pixels of every image the named formats send (square)
#: GR00T's language key for the instruction (the LeRobot export's annotation column).
GROOT_LANGUAGE = "annotation.human.task_description"
#: Camera resolution the letterboxed formats render at: the cameras' own 16:9.
WIDE = (320, 180)


def _numpy(x: Any) -> np.ndarray:
    return x.detach().cpu().numpy() if isinstance(x, torch.Tensor) else np.asarray(x)


def unbatch(obs: Any) -> Any:
    """ManiSkill's batched observation (one sub-scene) as plain numpy arrays."""
    if isinstance(obs, dict):
        return {k: unbatch(v) for k, v in obs.items()}
    return _numpy(obs)[0]


def letterbox(image: np.ndarray, size: int = SIZE) -> np.ndarray:
    """``image`` scaled to fit a ``size`` square, centred on black (openpi's resize_with_pad)."""
    h, w = image.shape[:2]
    scale = size / max(h, w)
    rh, rw = round(h * scale), round(w * scale)
    resized = cv2.resize(image, (rw, rh), interpolation=cv2.INTER_AREA)
    out = np.zeros((size, size, 3), dtype=np.uint8)
    top, left = (size - rh) // 2, (size - rw) // 2
    out[top : top + rh, left : left + rw] = resized
    return out


@dataclass(frozen=True)
class ObservationFormat:
    """A named format; subclasses encode observations and decode actions."""

    name: str
    robots: tuple[str, ...] = ()  # the robots it fits (empty: any)
    render: tuple[int, int] | None = None  # (width, height) the cameras render at

    def encode(self, obs: dict, prompt: str, interface: PolicyInterface, time: float) -> dict:
        """The request of ``obs`` (one sub-scene) ``time`` seconds into the episode."""
        raise NotImplementedError

    def decode(self, actions: np.ndarray, interface: PolicyInterface) -> np.ndarray:
        """(K, our action dim) from the server's (K, its dim)."""
        return actions

    def actions(self, reply: dict, interface: PolicyInterface) -> np.ndarray:
        """(K, our action dim) from the server's reply (its ``actions``: one or a chunk)."""
        actions = np.asarray(reply["actions"], dtype=np.float32)
        return self.decode(actions.reshape(-1, actions.shape[-1]), interface)

    @staticmethod
    def images(obs: dict) -> dict[str, np.ndarray]:
        return {cam: _numpy(d["rgb"])[0] for cam, d in obs["sensor_data"].items()}

    @staticmethod
    def state(obs: dict, interface: PolicyInterface) -> np.ndarray:
        """The robot's state in its joint-space policy interface."""
        return interface.state(_numpy(obs["agent"]["qpos"])[0]).astype(np.float32)


class InstructMove(ObservationFormat):
    def encode(self, obs: dict, prompt: str, interface: PolicyInterface, time: float) -> dict:
        request: dict[str, Any] = {
            f"observation.images.{cam}": image for cam, image in self.images(obs).items()
        }
        request.update(
            {
                "observation.state": self.state(obs, interface),
                "timestamp": np.array([time], dtype=np.float32),
                "prompt": prompt,
            }
        )
        return request


class Droid(ObservationFormat):
    KEYS = {
        "ext1_camera": "observation/exterior_image_1_left",
        "ext2_camera": "observation/exterior_image_2_left",
        "wrist_camera": "observation/wrist_image_left",
    }

    def encode(self, obs: dict, prompt: str, interface: PolicyInterface, time: float) -> dict:
        images = self.images(obs)
        state = self.state(obs, interface)
        request: dict[str, Any] = {key: letterbox(images[cam]) for cam, key in self.KEYS.items()}
        closed = 1.0 - _opening(state[-1:], interface)
        request.update(
            {
                "observation/joint_position": state[:7].astype(np.float32),
                "observation/gripper_position": closed.astype(np.float32),
                "prompt": prompt,
            }
        )
        return request

    def decode(self, actions: np.ndarray, interface: PolicyInterface) -> np.ndarray:
        gripper = interface.gripper
        value = gripper.value(gripper.max_width * (1.0 - np.clip(actions[:, 7:8], 0.0, 1.0)))
        return np.concatenate([actions[:, :7], value], axis=1).astype(np.float32)


class Aloha(ObservationFormat):
    KEYS = {
        "static_camera": "cam_high",
        "left_hand_camera": "cam_left_wrist",
        "right_hand_camera": "cam_right_wrist",
    }

    def encode(self, obs: dict, prompt: str, interface: PolicyInterface, time: float) -> dict:
        images = self.images(obs)
        state = self.state(obs, interface)  # left 6, right 6, left and right gripper values
        opening = _opening(state[12:], interface)
        aloha = np.concatenate([state[:6], opening[:1], state[6:12], opening[1:]])
        return {
            "images": {
                key: letterbox(images[cam]).transpose(2, 0, 1) for cam, key in self.KEYS.items()
            },
            "state": aloha.astype(np.float32),
            "prompt": prompt,
        }

    def decode(self, actions: np.ndarray, interface: PolicyInterface) -> np.ndarray:
        gripper = interface.gripper
        widths = gripper.max_width * np.clip(actions[:, [6, 13]], 0.0, 1.0)
        joints = np.concatenate([actions[:, :6], actions[:, 7:13]], axis=1)
        return np.concatenate([joints, gripper.value(widths)], axis=1).astype(np.float32)


class ManiSkill(ObservationFormat):
    def encode(self, obs: dict, prompt: str, interface: PolicyInterface, time: float) -> dict:
        return {"observation": unbatch(obs), "prompt": prompt}


class Groot(ObservationFormat):
    def encode(self, obs: dict, prompt: str, interface: PolicyInterface, time: float) -> dict:
        state = self.state(obs, interface)
        return {
            "video": {cam: image[None, None] for cam, image in self.images(obs).items()},
            "state": {p: state[None, None, a:b] for p, (a, b) in interface.parts().items()},
            "language": {GROOT_LANGUAGE: [[prompt]]},
        }

    def actions(self, reply: dict, interface: PolicyInterface) -> np.ndarray:
        chunk, parts = reply["actions"], interface.parts()
        missing = sorted(set(parts) - set(chunk))
        if missing:
            raise ValueError(f"the GR00T server's actions lack {missing}; it sent {sorted(chunk)}")
        arrays = {p: np.asarray(chunk[p], dtype=np.float32) for p in parts}
        horizon = arrays[next(iter(parts))].shape[1:2]
        out = np.zeros((*horizon, max(b for _, b in parts.values())), dtype=np.float32)
        for p, (a, b) in parts.items():
            if arrays[p].shape != (1, *horizon, b - a):
                raise ValueError(
                    f"GR00T action part {p!r} has shape {arrays[p].shape}; expected "
                    f"(1, {horizon[0] if horizon else 'horizon'}, {b - a})"
                )
            out[:, a:b] = arrays[p][0]
        return out


def _opening(values: np.ndarray, interface: PolicyInterface) -> np.ndarray:
    """Gripper action values as the fraction of the full opening (0 closed, 1 open)."""
    g = interface.gripper
    return np.clip((values - g.offset) / g.scale / g.max_width, 0.0, 1.0)


FORMATS: dict[str, ObservationFormat] = {
    f.name: f
    for f in (
        InstructMove("instructmove", render=(SIZE, SIZE)),
        Droid("droid", robots=("franka",), render=WIDE),
        Aloha("aloha", robots=("piperx",), render=WIDE),
        ManiSkill("maniskill"),
        Groot("groot", render=(SIZE, SIZE)),
    )
}
