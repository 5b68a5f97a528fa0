"""Reading an episode MCAP back into numpy arrays, and into the inputs of scoring."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.family import StageSchema
from instructmove_ms.tasks import TASKS

from . import schemas


@dataclass
class McapEpisode:
    """One episode: T actions and the T + 1 recorded states around them.

    Joint arrays are per arm (``left``/``right`` for a dual-arm robot, else ``arm``), in the
    order of ``joint_names[arm]``; camera arrays are per camera name. Poses are x, y, z, qw,
    qx, qy, qz in the world frame.
    """

    metadata: dict
    timestamps: np.ndarray  # (T + 1,) s, simulation time of the states and frames
    joint_names: dict[str, list[str]]
    joint_positions: dict[str, np.ndarray]  # (T + 1, J) rad or m
    joint_velocities: dict[str, np.ndarray]  # (T + 1, J) rad/s or m/s
    joint_efforts: dict[str, np.ndarray]  # (T + 1, J) N m or N
    action_timestamps: np.ndarray  # (T,) s
    actions: np.ndarray  # (T, action dim)
    images: dict[str, np.ndarray]  # (T + 1, H, W, 3) uint8 RGB
    depth_mm: dict[str, np.ndarray]  # (T + 1, H, W) uint16 millimetres
    intrinsics: dict[str, np.ndarray]  # (3, 3)
    camera_poses: dict[str, np.ndarray]  # (T + 1, 7) optical frame (x right, y down, z fwd)
    object_poses: np.ndarray  # (T + 1, K, 7) in the spec's object order

    @property
    def instruction(self) -> str:
        return self.metadata["instruction"]

    @property
    def stages(self) -> dict[str, list[bool]]:
        return self.metadata["stages"]


def _seconds(msg) -> float:
    return msg.timestamp.ToNanoseconds() / 1e9


def _pose(position, orientation) -> list[float]:
    p, q = position, orientation
    return [p.x, p.y, p.z, q.w, q.x, q.y, q.z]


def _decode(data: bytes, flags: int) -> np.ndarray:
    image = cv2.imdecode(np.frombuffer(data, np.uint8), flags)
    if image is None:
        raise ValueError("undecodable image")
    return image


def read_messages(path: str | Path) -> dict[str, list]:
    """Every decoded message of the MCAP ``path`` by topic, in log-time order."""
    by_topic: dict[str, list] = {}
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        for _, channel, _, msg in reader.iter_decoded_messages(log_time_order=True):
            by_topic.setdefault(channel.topic, []).append(msg)
    return by_topic


def read_episode(path: str | Path) -> McapEpisode:
    """Read an episode MCAP written by :func:`instructmove_ms.export.export_trajectory`."""
    msgs = read_messages(path)
    metadata = json.loads(msgs[schemas.EPISODE][0].json)
    arms = metadata["arms"]
    joints = {arm: msgs[schemas.joints_topic(arm)] for arm in arms}

    def joint_array(arm: str, key: str) -> np.ndarray:
        return np.array([[getattr(j, key) for j in m.joints] for m in joints[arm]])

    cams = metadata["cameras"]

    def topic(cam: str, kind: str) -> list:
        return msgs[schemas.camera_topic(cam, kind)]

    actions = msgs.get(schemas.ACTION, [])
    return McapEpisode(
        metadata=metadata,
        timestamps=np.array([_seconds(m) for m in joints[next(iter(arms))]]),
        joint_names=arms,
        joint_positions={arm: joint_array(arm, "position") for arm in arms},
        joint_velocities={arm: joint_array(arm, "velocity") for arm in arms},
        joint_efforts={arm: joint_array(arm, "effort") for arm in arms},
        action_timestamps=np.array([_seconds(m) for m in actions]),
        actions=np.array([list(m.values) for m in actions]),
        images={
            c: np.stack([_decode(m.data, cv2.IMREAD_COLOR)[..., ::-1] for m in topic(c, "color")])
            for c in cams
        },
        depth_mm={
            c: np.stack([_decode(m.data, cv2.IMREAD_UNCHANGED) for m in topic(c, "depth")])
            for c in cams
        },
        intrinsics={c: np.array(topic(c, "calibration")[0].K).reshape(3, 3) for c in cams},
        camera_poses={
            c: np.array([_pose(m.translation, m.rotation) for m in topic(c, "pose")]) for c in cams
        },
        object_poses=np.array(
            [[_pose(p.position, p.orientation) for p in m.poses] for m in msgs[schemas.OBJECTS]]
        ),
    )


def score_inputs(episode: McapEpisode) -> tuple[EpisodeSpec, dict, StageSchema]:
    """``(spec, info, stages)`` for :func:`instructmove_ms.metrics.score_episode`: the
    episode spec, the info of its last step as the replay during export computed it, and
    its family's stage schema."""
    spec = EpisodeSpec.from_dict(episode.metadata["spec"])
    return spec, episode.metadata["info"], TASKS[episode.metadata["env_id"]].stages
