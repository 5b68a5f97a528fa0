"""Writing one episode as an MCAP file of protobuf messages (channels: docs/mcap.md).

Message times are simulation time: recorded state / action ``k`` at ``k / control_freq`` s.
Files are written under a temporary name and renamed into place, so an interrupted or
failed conversion leaves no partial file.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path

import cv2
import numpy as np
from foxglove_schemas_protobuf.CameraCalibration_pb2 import CameraCalibration
from foxglove_schemas_protobuf.CompressedImage_pb2 import CompressedImage
from foxglove_schemas_protobuf.FrameTransform_pb2 import FrameTransform
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.JointState_pb2 import JointState
from foxglove_schemas_protobuf.JointStates_pb2 import JointStates
from foxglove_schemas_protobuf.Pose_pb2 import Pose
from foxglove_schemas_protobuf.PosesInFrame_pb2 import PosesInFrame
from foxglove_schemas_protobuf.Quaternion_pb2 import Quaternion
from foxglove_schemas_protobuf.Vector3_pb2 import Vector3
from mcap_protobuf.writer import Writer

from instructmove_ms.files import atomic_path

from . import schemas
from .replay import CameraFrame, Frame, RobotParts


def sim_time_ns(step: int, control_freq: float) -> int:
    return round(step * 1e9 / control_freq)


def _vector(p) -> Vector3:
    return Vector3(x=p[0], y=p[1], z=p[2])


def _quaternion(q) -> Quaternion:
    """From SAPIEN's (w, x, y, z)."""
    return Quaternion(w=q[0], x=q[1], y=q[2], z=q[3])


def _transform(ns: int, child: str, pose: np.ndarray) -> FrameTransform:
    msg = FrameTransform(
        parent_frame_id=schemas.WORLD,
        child_frame_id=child,
        translation=_vector(pose[:3]),
        rotation=_quaternion(pose[3:]),
    )
    msg.timestamp.FromNanoseconds(ns)
    return msg


def _image(ns: int, frame_id: str, data: bytes, fmt: str) -> CompressedImage:
    msg = CompressedImage(frame_id=frame_id, data=data, format=fmt)
    msg.timestamp.FromNanoseconds(ns)
    return msg


def _encode(ext: str, image: np.ndarray, params: list[int]) -> bytes:
    ok, buf = cv2.imencode(ext, image, params)
    if not ok:
        raise RuntimeError(f"could not encode a {image.shape} {image.dtype} image as {ext}")
    return buf.tobytes()


def _calibration(ns: int, frame_id: str, cam: CameraFrame) -> CameraCalibration:
    k = cam.intrinsic
    p = np.hstack([k, np.zeros((3, 1))])
    msg = CameraCalibration(
        frame_id=frame_id,
        width=cam.rgb.shape[1],
        height=cam.rgb.shape[0],
        distortion_model="plumb_bob",
        D=[0.0] * 5,
        K=k.reshape(-1).tolist(),
        R=np.eye(3).reshape(-1).tolist(),
        P=p.reshape(-1).tolist(),
    )
    msg.timestamp.FromNanoseconds(ns)
    return msg


def _camera_messages(ns: int, name: str, cam: CameraFrame, jpeg_quality: int):
    frame_id = schemas.optical_frame(name)
    color = _encode(".jpg", cam.rgb[..., ::-1], [cv2.IMWRITE_JPEG_QUALITY, jpeg_quality])
    yield schemas.camera_topic(name, "color"), _image(ns, frame_id, color, "jpeg")
    depth = _encode(".png", cam.depth_mm, [])
    yield schemas.camera_topic(name, "depth"), _image(ns, frame_id, depth, "png")
    yield schemas.camera_topic(name, "calibration"), _calibration(ns, frame_id, cam)
    yield schemas.camera_topic(name, "pose"), _transform(ns, frame_id, cam.pose)


def _frame_messages(frame: Frame, rig: RobotParts, ns: int, jpeg_quality: int):
    for arm, index in rig.arms.items():
        msg = JointStates(
            joints=[
                JointState(
                    name=rig.joint_names[i],
                    position=frame.qpos[i],
                    velocity=frame.qvel[i],
                    effort=frame.effort[i],
                )
                for i in index
            ]
        )
        msg.timestamp.FromNanoseconds(ns)
        yield schemas.joints_topic(arm), msg
    yield (
        schemas.LINKS,
        FrameTransforms(
            transforms=[
                _transform(ns, name, pose)
                for name, pose in zip(rig.link_names, frame.links, strict=True)
            ]
        ),
    )
    objects = PosesInFrame(
        frame_id=schemas.WORLD,
        poses=[
            Pose(position=_vector(pose[:3]), orientation=_quaternion(pose[3:]))
            for pose in frame.objects
        ],
    )
    objects.timestamp.FromNanoseconds(ns)
    yield schemas.OBJECTS, objects
    for name, cam in frame.cameras.items():
        yield from _camera_messages(ns, name, cam, jpeg_quality)


def _episode_message(metadata: dict):
    msg = schemas.Episode(
        env_id=metadata["env_id"],
        robot=metadata["spec"]["robot"],
        episode_id=metadata["episode_id"],
        seed=metadata["seed"],
        instruction=metadata["instruction"],
        success=metadata["success"],
        stage_score=metadata["score"],
        json=json.dumps(metadata),
    )
    msg.timestamp.FromNanoseconds(0)
    return msg


def write_episode(
    path: Path,
    metadata: dict,
    rig: RobotParts,
    actions: np.ndarray,
    frames: Iterable[Frame],
    jpeg_quality: int = 90,
) -> int:
    """Write the episode MCAP ``path`` atomically; returns its size in bytes."""
    with atomic_path(path) as tmp, open(tmp, "wb") as f:
        writer = Writer(f)
        writer.write_message(schemas.EPISODE, _episode_message(metadata), 0, 0)
        for frame in frames:
            ns = sim_time_ns(frame.step, rig.control_freq)
            for topic, msg in _frame_messages(frame, rig, ns, jpeg_quality):
                writer.write_message(topic, msg, ns, ns)
            if frame.step < len(actions):
                action = schemas.Action(
                    control_mode=metadata["control_mode"],
                    names=rig.action_names,
                    values=actions[frame.step].astype(np.float64).tolist(),
                )
                action.timestamp.FromNanoseconds(ns)
                writer.write_message(schemas.ACTION, action, ns, ns)
        writer.finish()
    return path.stat().st_size
