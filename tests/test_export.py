"""MCAP export: round trip, Foxglove schemas, resume and bad inputs."""

from __future__ import annotations

import json
import shutil

import gymnasium as gym
import h5py
import numpy as np
import pytest
import torch
from foxglove_schemas_protobuf.JointState_pb2 import JointState
from foxglove_schemas_protobuf.JointStates_pb2 import JointStates
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from instructmove_ms.assets import load_snapshot
from instructmove_ms.cli import main
from instructmove_ms.demos.generate import generate
from instructmove_ms.export import (
    ExportSettings,
    TrajectoryError,
    export_trajectory,
    read_episode,
    score_inputs,
)
from instructmove_ms.export.replay import Frame, RobotParts
from instructmove_ms.export.writer import write_episode
from instructmove_ms.metrics import score_episode

TASK, ROBOT = "PickCategory-InstructMove", "franka"
STEM = f"{TASK}_{ROBOT}"
STEPS = 30  # the demos are cut to this many steps to keep rendering short
SIZE = 64


def _copy_rows(src: h5py.Group, dst: h5py.Group, rows: int) -> None:
    for key, value in src.items():
        if isinstance(value, h5py.Group):
            _copy_rows(value, dst.create_group(key), rows)
        else:
            dst[key] = value[:rows]


def _copy_trajectory(src, dst, steps: int):
    """Copy ``src``'s trajectory (h5 + json + sidecar) into ``dst``, cut to ``steps``."""
    dst.mkdir(parents=True, exist_ok=True)
    meta = json.loads((src / f"{STEM}.json").read_text())
    sidecar = json.loads((src / f"{STEM}.episodes.json").read_text())
    with h5py.File(src / f"{STEM}.h5") as fin, h5py.File(dst / f"{STEM}.h5", "w") as fout:
        for entry, extra in zip(meta["episodes"], sidecar, strict=True):
            name = f"traj_{entry['episode_id']}"
            fout[f"{name}/actions"] = fin[f"{name}/actions"][:steps]
            states = fout.create_group(f"{name}/env_states")
            _copy_rows(fin[f"{name}/env_states"], states, steps + 1)
            entry["elapsed_steps"] = steps
            extra["stages"] = {k: v[:steps] for k, v in extra["stages"].items()}
            entry["success"] = extra["stages"]["success"][-1]
    (dst / f"{STEM}.json").write_text(json.dumps(meta))
    (dst / f"{STEM}.episodes.json").write_text(json.dumps(sidecar))
    return dst / f"{STEM}.h5"


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    demos = tmp_path_factory.mktemp("demos")
    generate(TASK, ROBOT, 2, demos)
    return _copy_trajectory(demos, tmp_path_factory.mktemp("short"), STEPS)


@pytest.fixture(scope="module")
def exported(source, tmp_path_factory):
    out = tmp_path_factory.mktemp("mcap")
    report = export_trajectory(source, out, settings=ExportSettings(SIZE, SIZE))
    return out, report


def _messages(path):
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        return summary, list(reader.iter_decoded_messages())


def test_round_trip(source, exported):
    out, report = exported
    assert len(report.written) == 2 and not report.skipped
    sidecar = json.loads(source.with_name(f"{STEM}.episodes.json").read_text())
    with h5py.File(source) as f:
        for path, extra in zip(sorted(report.written), sidecar, strict=True):
            ep = read_episode(path)
            traj = f"traj_{extra['episode_id']}"
            assert ep.instruction == extra["spec"]["instruction"]
            assert ep.stages == extra["stages"]
            np.testing.assert_array_equal(ep.actions.astype(np.float32), f[f"{traj}/actions"][:])
            state = f[f"{traj}/env_states/articulations/{ROBOT}"][:]
            qpos = state[:, 13 : 13 + 9]
            assert ep.joint_names["arm"][0] == "panda_joint1"
            np.testing.assert_array_equal(ep.joint_positions["arm"].astype(np.float32), qpos)
            np.testing.assert_allclose(ep.timestamps, np.arange(STEPS + 1) / 30, atol=1e-9)
            np.testing.assert_allclose(ep.action_timestamps, ep.timestamps[:-1])
            assert set(ep.images) == {"ext1_camera", "ext2_camera", "wrist_camera"}
            for cam, images in ep.images.items():
                assert images.shape == (STEPS + 1, SIZE, SIZE, 3) and images.dtype == np.uint8
                assert ep.depth_mm[cam].shape == (STEPS + 1, SIZE, SIZE)
                assert ep.depth_mm[cam].dtype == np.uint16
            objects = [o["uuid"] for o in extra["spec"]["objects"]]
            assert [o["uuid"] for o in ep.metadata["objects"]] == objects
            assert ep.object_poses.shape == (STEPS + 1, len(objects), 7)
            assert ep.metadata["versions"]["mani-skill"]


def test_images_match_maniskill_rgbd_render(source, exported):
    """Frames equal ManiSkill's own rgbd observation of the restored state: depth in mm
    exactly, colour within JPEG error."""
    ep = read_episode(sorted(exported[1].written)[0])
    meta = json.loads(source.with_suffix(".json").read_text())
    kwargs = dict(meta["env_info"]["env_kwargs"], obs_mode="rgbd")
    env = gym.make(TASK, **kwargs, sensor_configs=dict(width=SIZE, height=SIZE))
    env.reset(**meta["episodes"][0]["reset_kwargs"])
    with h5py.File(source) as f:
        states = f["traj_0/env_states"]
        for k in (0, STEPS):
            state = {
                group: {name: torch.from_numpy(d[k : k + 1]) for name, d in items.items()}
                for group, items in states.items()
            }
            env.unwrapped.set_state_dict(state)
            obs = env.unwrapped.get_obs()["sensor_data"]
            for cam, data in obs.items():
                depth = data["depth"][0, ..., 0].numpy()
                assert np.abs(ep.depth_mm[cam][k].astype(int) - depth).max() <= 1
                rgb = data["rgb"][0].numpy().astype(int)
                assert np.abs(ep.images[cam][k].astype(int) - rgb).mean() < 4
    env.close()
    seen = ep.depth_mm["ext1_camera"][0]
    assert 200 < np.median(seen[seen > 0]) < 2000  # the table, some 0.5 m to 1 m away


def test_files_decode_into_foxglove_schemas(exported):
    path = sorted(exported[1].written)[0]
    summary, messages = _messages(path)
    schemas = {ch.topic: summary.schemas[ch.schema_id].name for ch in summary.channels.values()}
    expected = {
        "/episode": "instructmove.Episode",
        "/robot/action": "instructmove.Action",
        "/robot/arm/joint_states": "foxglove.JointStates",
        "/tf": "foxglove.FrameTransforms",
        "/objects/poses": "foxglove.PosesInFrame",
        "/camera/ext1_camera/color": "foxglove.CompressedImage",
        "/camera/ext1_camera/depth": "foxglove.CompressedImage",
        "/camera/ext1_camera/calibration": "foxglove.CameraCalibration",
        "/camera/wrist_camera/pose": "foxglove.FrameTransform",
    }
    assert expected.items() <= schemas.items()
    assert all(ch.message_encoding == "protobuf" for ch in summary.channels.values())
    assert all(s.encoding == "protobuf" for s in summary.schemas.values())
    for schema, _, _, decoded in messages:
        assert decoded.DESCRIPTOR.full_name == schema.name
    joints = next(d for _, ch, _, d in messages if ch.topic == "/robot/arm/joint_states")
    generated = JointStates.FromString(joints.SerializeToString())
    assert isinstance(generated.joints[0], JointState) and generated.joints[0].name
    image = next(d for _, ch, _, d in messages if ch.topic == "/camera/ext1_camera/color")
    assert image.format == "jpeg" and image.frame_id == "ext1_camera_optical"
    calibration = next(d for _, ch, _, d in messages if ch.topic.endswith("calibration"))
    assert len(calibration.K) == 9 and len(calibration.P) == 12 and len(calibration.D) == 5
    assert (calibration.width, calibration.height) == (SIZE, SIZE)


def test_score_inputs_feed_the_metrics(exported):
    ep = read_episode(sorted(exported[1].written)[0])
    spec, info, stages = score_inputs(ep)
    result = score_episode(spec, info, stages, load_snapshot())
    assert result.stages == {k: ep.stages[k][-1] for k in ("reach", "lift")}
    assert result.success == ep.stages["success"][-1] == ep.metadata["success"]


def test_resume_skips_existing_files(source, exported, capsys):
    out, report = exported
    mtimes = [p.stat().st_mtime_ns for p in report.written]
    argv = ["export", "mcap", "--traj", str(source), "--out", str(out), "--width", str(SIZE)]
    assert main(argv) == 0
    assert "0 episodes written" in capsys.readouterr().out
    assert [p.stat().st_mtime_ns for p in report.written] == mtimes


@pytest.mark.parametrize("fault", ["truncated", "short_actions"])
def test_bad_input_names_the_file_and_writes_nothing(source, tmp_path, fault):
    bad = tmp_path / "in"
    bad.mkdir()
    for suffix in (".h5", ".json", ".episodes.json"):
        shutil.copy(source.with_name(f"{STEM}{suffix}"), bad / f"{STEM}{suffix}")
    h5 = bad / f"{STEM}.h5"
    if fault == "truncated":
        data = h5.read_bytes()
        h5.write_bytes(data[: len(data) // 2])
        reason = "truncated or corrupted"
    else:
        with h5py.File(h5, "a") as f:
            actions = f["traj_1/actions"][:-3]
            del f["traj_1/actions"]
            f["traj_1/actions"] = actions
        reason = "traj_1: actions of shape"
    out = tmp_path / "out"
    with pytest.raises(TrajectoryError, match=reason) as err:
        export_trajectory(h5, out, settings=ExportSettings(SIZE, SIZE))
    assert str(h5) in str(err.value)
    assert not out.exists() or not any(out.iterdir())
    assert main(["export", "mcap", "--traj", str(h5), "--out", str(out)]) == 2


def test_failed_conversion_leaves_no_partial_file(tmp_path):
    rig = RobotParts(("j",), {"arm": (0,)}, ("link",), ("arm[0]",), (), 30.0)
    metadata = {
        "env_id": TASK,
        "spec": {"robot": ROBOT},
        "episode_id": 0,
        "seed": 0,
        "instruction": "pick up the mug",
        "success": False,
        "score": 0.0,
        "control_mode": "pd_joint_pos",
    }

    def frames():
        one = np.zeros(1)
        yield Frame(0, one, one, one, np.zeros((1, 7)), np.zeros((0, 7)), {})
        raise RuntimeError("renderer died")

    path = tmp_path / "episode.mcap"
    with pytest.raises(RuntimeError, match="renderer died"):
        write_episode(path, metadata, rig, np.zeros((1, 1)), frames())
    assert list(tmp_path.iterdir()) == []


def test_exports_render_each_recorded_state_once_per_camera(source, tmp_path, monkeypatch):
    """MCAP (every state) and LeRobot (the state before each action) capture the cameras
    once per written frame; the replay that measures efforts renders nothing."""
    from mani_skill.envs.sapien_env import BaseEnv

    from instructmove_ms.export.lerobot import LeRobotSettings, export_lerobot

    captures, capture = [0], BaseEnv.capture_sensor_data

    def counted(self, *args, **kwargs):
        captures[0] += 1
        return capture(self, *args, **kwargs)

    monkeypatch.setattr(BaseEnv, "capture_sensor_data", counted)
    export_trajectory(source, tmp_path / "mcap", settings=ExportSettings(SIZE, SIZE))
    assert captures[0] == 2 * (STEPS + 1)  # two episodes of STEPS actions
    captures[0] = 0
    export_lerobot([source], tmp_path / "lerobot", LeRobotSettings("me/x", SIZE, SIZE))
    assert captures[0] == 2 * STEPS
