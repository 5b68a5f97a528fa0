"""LeRobot v3.0 export: the dataset loads with the real ``lerobot`` (in the isolated
environment of scripts/lerobot_env.sh) and holds what the source trajectories recorded."""

from __future__ import annotations

import json
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import h5py
import imageio.v2 as imageio
import numpy as np
import pyarrow.parquet as pq
import pytest

from conftest import make_env
from instructmove_ms.cli import main
from instructmove_ms.demos.generate import generate
from instructmove_ms.export import lerobot
from instructmove_ms.export.lerobot import LeRobotSettings, export_lerobot

ROOT = Path(__file__).resolve().parent.parent
LEROBOT_PYTHON = ROOT / ".cache" / "lerobot-env" / "bin" / "python"
READER = Path(__file__).parent / "tools" / "lerobot_read.py"
WIDTH, HEIGHT = 128, 96  # not the default: the requested size must come out
REPO = "instructmove/test"


@pytest.fixture(scope="module")
def sources(tmp_path_factory) -> list[Path]:
    """Two families of Franka demos (one dataset: multi-task)."""
    out = tmp_path_factory.mktemp("demos")
    return [
        generate("PickCategory-InstructMove", "franka", 2, out, shard_size=2).path,
        generate("PlaceA2B-InstructMove", "franka", 1, out, shard_size=1).path,
    ]


@pytest.fixture(scope="module")
def dataset(sources, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("lerobot") / "dataset"
    settings = LeRobotSettings(REPO, WIDTH, HEIGHT)
    report = export_lerobot(sources, out, settings, workers=2)
    assert report.written == [0, 1, 2] and not report.skipped
    return out


def _read(dataset: Path, indices: list[int], out: Path) -> dict:
    """What the real LeRobotDataset reads of ``indices``."""
    assert LEROBOT_PYTHON.is_file(), "run scripts/lerobot_env.sh (scripts/test.sh does)"
    subprocess.run(
        [str(LEROBOT_PYTHON), str(READER), str(dataset), REPO, str(out), *map(str, indices)],
        check=True,
        capture_output=True,
        timeout=600,
    )
    data = np.load(out)
    return {**{k: data[k] for k in data.files}, "meta": json.loads(str(data["meta"]))}


def _source_episodes(sources: list[Path]) -> list[tuple[np.ndarray, np.ndarray, str]]:
    """(actions, qpos per state, instruction) of every source episode, in dataset order."""
    episodes = []
    for path in sources:
        meta = json.loads(path.with_suffix(".json").read_text())
        sidecar = json.loads(path.with_name(path.stem + ".episodes.json").read_text())
        with h5py.File(path) as f:
            for entry, extra in zip(meta["episodes"], sidecar, strict=True):
                group = f[f"traj_{entry['episode_id']}"]
                robot = group["env_states/articulations"]
                (state,) = (robot[k][()] for k in robot)  # root pose, velocity, qpos, qvel
                dof = (state.shape[1] - 13) // 2
                qpos = state[:, 13 : 13 + dof]
                episodes.append((group["actions"][()], qpos, extra["spec"]["instruction"]))
    return episodes


def test_lerobot_loads_what_the_trajectories_recorded(sources, dataset, tmp_path):
    episodes = _source_episodes(sources)
    lengths = [len(actions) for actions, _, _ in episodes]
    starts = np.concatenate([[0], np.cumsum(lengths)])
    picks = [0, starts[1] - 1, starts[1] + 7, starts[2] + lengths[2] // 2, starts[3] - 1]
    read = _read(dataset, picks, tmp_path / "read.npz")
    meta = read["meta"]
    assert meta["length"] == sum(lengths) and meta["episodes"] == 3
    assert meta["fps"] == 30 and meta["robot_type"] == "franka"
    assert meta["tasks"] == [instruction for _, _, instruction in episodes]
    assert {"instructmove/family", "instructmove/spec"} <= set(meta["episode_columns"])
    cameras = ("ext1_camera", "ext2_camera", "wrist_camera")
    assert meta["cameras"] == [f"observation.images.{c}" for c in cameras]
    env = make_env(control_mode="pd_joint_pos")
    interface = env.unwrapped.agent.policy_interface()
    env.close()
    for i, index in enumerate(picks):
        e = int(np.searchsorted(starts, index, side="right") - 1)
        actions, qpos, instruction = episodes[e]
        k = index - starts[e]
        assert int(read[f"{index}/episode_index"]) == e and int(read[f"{index}/frame_index"]) == k
        assert meta["frame_tasks"][i] == instruction
        np.testing.assert_array_equal(read[f"{index}/action"], actions[k].astype(np.float32))
        state = interface.state(qpos[k]).astype(np.float32)
        np.testing.assert_allclose(read[f"{index}/observation.state"], state, atol=1e-6)
        for camera in cameras:
            image = read[f"{index}/observation.images.{camera}"]
            assert image.shape == (HEIGHT, WIDTH, 3)
            video = dataset / lerobot.VIDEO_PATH.format(
                video_key=f"observation.images.{camera}", chunk_index=0, file_index=e
            )
            with imageio.get_reader(video, format="FFMPEG") as frames:
                ours = frames.get_data(k)  # the k-th frame, by another decoder
            difference = np.abs(image.astype(int) - ours.astype(int)).mean()
            assert difference < 2.0, f"{camera} frame {k} of episode {e} is another frame"
            assert image.std() > 5, "an image, not a blank"


def test_a_killed_export_resumes_to_the_same_dataset(sources, dataset, tmp_path, monkeypatch):
    out = tmp_path / "resumed"
    settings = LeRobotSettings(REPO, WIDTH, HEIGHT)
    convert = lerobot.EpisodeWriter.convert

    def killed_at_the_second(self, entry):
        if entry.index == 1:
            raise KeyboardInterrupt
        return convert(self, entry)

    monkeypatch.setattr(lerobot.EpisodeWriter, "convert", killed_at_the_second)
    with pytest.raises(KeyboardInterrupt):
        export_lerobot(sources, out, settings)
    assert not (out / "meta" / "info.json").exists(), "no dataset claims to be complete"
    monkeypatch.undo()
    report = export_lerobot(sources, out, settings)
    assert report.skipped == [0] and report.written == [1, 2]
    for name in ("meta/info.json", "meta/stats.json"):
        assert json.loads((out / name).read_text()) == json.loads((dataset / name).read_text())
    for name in ("meta/episodes/chunk-000/file-000.parquet", "meta/tasks.parquet"):
        assert pq.read_table(out / name).equals(pq.read_table(dataset / name))
    for e in range(3):
        name = lerobot.DATA_PATH.format(chunk_index=0, file_index=e)
        assert pq.read_table(out / name).equals(pq.read_table(dataset / name))


def test_cli_exports_and_refuses_other_settings_on_resume(sources, dataset, capsys):
    argv = ["export", "lerobot", "--traj", str(sources[0]), "--traj", str(sources[1])]
    argv += ["--out", str(dataset), "--repo-id", REPO, "--width", str(WIDTH)]
    assert main([*argv, "--height", str(HEIGHT)]) == 0
    assert "0 episodes written" in capsys.readouterr().out  # all there already
    assert main([*argv, "--height", "64"]) == 2
    assert "exported with" in capsys.readouterr().err


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_the_loop_export_serve_evaluate_scores_the_demos(sources, dataset, tmp_path, capsys):
    """The demos, exported to LeRobot, replayed by openpi's own server from the dataset and
    evaluated through the websocket on the demos' own episodes, succeed as the demos did:
    the export's keys, state units and action order, the chunking and the timing agree."""
    port = _free_port()
    server = subprocess.Popen(
        [sys.executable, "-m", "instructmove_ms.cli", "serve-replay", "--dataset", str(dataset)]
        + ["--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        for _ in range(300):  # openpi's server answers /healthz once it listens
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/healthz", timeout=1):
                    break
            except OSError:
                assert server.poll() is None, server.stderr.read().decode()
                time.sleep(0.1)
        for k, source in enumerate(sources):
            argv = ["eval", "--traj", str(source), "--policy", f"ws://127.0.0.1:{port}"]
            assert main([*argv, "--out", str(tmp_path / f"eval{k}")]) == 0
            out = capsys.readouterr().out
            assert json.loads(out.split("policy: ")[1])["requests"] > 10
            (group,) = json.loads((tmp_path / f"eval{k}" / "summary.json").read_text())["groups"]
            assert group["success"] == 1.0 and group["success_at_end"] == 1.0, group
    finally:
        server.kill()
        server.wait()
