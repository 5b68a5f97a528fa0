"""LeRobot export, both formats: v3.0 loads with the real ``lerobot`` 0.4.4 (the isolated
environment of scripts/lerobot_env.sh), v2.1 with lerobot 0.3.3 as openpi's data loader opens
it (scripts/lerobot_v21_env.sh); both hold what the source trajectories recorded, the same in
each, and GR00T's modality files name the state and action parts."""

from __future__ import annotations

import contextlib
import json
import os
import re
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import h5py
import imageio.v2 as imageio
import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from conftest import make_env
from instructmove_ms.cli import main
from instructmove_ms.demos.generate import generate
from instructmove_ms.export import groot, lerobot
from instructmove_ms.export.lerobot import LeRobotSettings, export_lerobot
from instructmove_ms.export.lerobot_formats import layout

ROOT = Path(__file__).resolve().parent.parent
LEROBOT_PYTHON = ROOT / ".cache" / "lerobot-env" / "bin" / "python"
LEROBOT_V21_PYTHON = ROOT / ".cache" / "lerobot-v21-env" / "bin" / "python"
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


def _export(sources: list[Path], out: Path, fmt: str) -> Path:
    report = export_lerobot(sources, out, LeRobotSettings(REPO, WIDTH, HEIGHT, fmt), workers=2)
    assert report.written == [0, 1, 2] and not report.skipped
    return out


@pytest.fixture(scope="module")
def dataset(sources, tmp_path_factory) -> Path:
    """The v3.0 export (the default format)."""
    return _export(sources, tmp_path_factory.mktemp("lerobot") / "dataset", "v3.0")


@pytest.fixture(scope="module")
def dataset_v21(sources, tmp_path_factory) -> Path:
    """The v2.1 export of the same trajectories, under ``$HF_LEROBOT_HOME/REPO`` as openpi
    keeps it."""
    return _export(sources, tmp_path_factory.mktemp("lerobot_home") / REPO, "v2.1")


def _read(dataset: Path, indices: list[int], out: Path, chunk: int = 0) -> dict:
    """What the real LeRobotDataset reads of ``indices``: lerobot 0.4.4 for v3.0; for v2.1
    lerobot 0.3.3 as openpi opens it, with ``chunk`` actions from each frame."""
    python, home = LEROBOT_PYTHON, os.environ.get("HF_LEROBOT_HOME", "")
    if chunk:
        python, home = LEROBOT_V21_PYTHON, str(dataset.parents[1])  # HOME/<org>/<name>
    assert python.is_file(), f"{python} missing: run scripts/lerobot_v21_env.sh (test.sh does)"
    argv = [str(python), str(READER), str(dataset), REPO, str(out), *map(str, indices)]
    env = {**os.environ, "HF_LEROBOT_HOME": home, "HF_HUB_OFFLINE": "1"}
    run = subprocess.run(
        [*argv, "--action-chunk", str(chunk)], capture_output=True, text=True, env=env, timeout=600
    )
    assert run.returncode == 0, run.stderr[-3000:]
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


CAMERAS = ("ext1_camera", "ext2_camera", "wrist_camera")
CHUNK = 50  # pi0's action horizon, as openpi's loader asks for it


def _picks(episodes) -> tuple[list[int], np.ndarray]:
    """Frames to read (first, last, inner ones of every episode) and the episodes' starts."""
    lengths = [len(actions) for actions, _, _ in episodes]
    starts = np.concatenate([[0], np.cumsum(lengths)])
    picks = [0, starts[1] - 1, starts[1] + 7, starts[2] + lengths[2] // 2, starts[3] - 1]
    return [int(i) for i in picks], starts


def _check_read(read: dict, episodes, picks, starts, dataset: Path, fmt: str) -> None:
    """``read`` holds, at every pick, the source's state, action (or action chunk), task and
    the frame of every camera's video."""
    meta = read["meta"]
    assert meta["lerobot_format"] == fmt
    assert meta["length"] == starts[-1] and meta["episodes"] == 3
    assert meta["fps"] == 30 and meta["robot_type"] == "franka"
    assert meta["tasks"] == [instruction for _, _, instruction in episodes]
    assert {"instructmove/family", "instructmove/spec"} <= set(meta["episode_columns"])
    assert meta["cameras"] == [f"observation.images.{c}" for c in CAMERAS]
    env = make_env(control_mode="pd_joint_pos")
    interface = env.unwrapped.agent.policy_interface()
    env.close()
    for i, index in enumerate(picks):
        e = int(np.searchsorted(starts, index, side="right") - 1)
        actions, qpos, instruction = episodes[e]
        k = index - starts[e]
        assert int(read[f"{index}/episode_index"]) == e and int(read[f"{index}/frame_index"]) == k
        assert meta["frame_tasks"][i] == instruction
        action = read[f"{index}/action"]
        if action.ndim == 2:  # a chunk: the episode's next actions, its last one repeated
            rows = np.minimum(np.arange(k, k + len(action)), len(actions) - 1)
            np.testing.assert_array_equal(action, actions[rows].astype(np.float32))
            pad = read[f"{index}/action_is_pad"]
            np.testing.assert_array_equal(pad, np.arange(k, k + len(action)) >= len(actions))
        else:
            np.testing.assert_array_equal(action, actions[k].astype(np.float32))
        state = interface.state(qpos[k]).astype(np.float32)
        np.testing.assert_allclose(read[f"{index}/observation.state"], state, atol=1e-6)
        for camera in CAMERAS:
            key = f"observation.images.{camera}"
            image = read[f"{index}/{key}"]
            assert image.shape == (HEIGHT, WIDTH, 3)
            video = dataset / layout(fmt).video_file(e, key)
            with imageio.get_reader(video, format="FFMPEG") as frames:
                ours = frames.get_data(k)  # the k-th frame, by another decoder
            difference = np.abs(image.astype(int) - ours.astype(int)).mean()
            assert difference < 2.0, f"{camera} frame {k} of episode {e} is another frame"
            assert image.std() > 5, "an image, not a blank"


def test_lerobot_loads_what_the_trajectories_recorded(sources, dataset, tmp_path):
    episodes = _source_episodes(sources)
    picks, starts = _picks(episodes)
    read = _read(dataset, picks, tmp_path / "read.npz")
    _check_read(read, episodes, picks, starts, dataset, "v3.0")


def test_openpi_loads_the_v21_export_with_its_action_chunks(sources, dataset_v21, tmp_path):
    """lerobot 0.3.3 opens the v2.1 export by repo id under $HF_LEROBOT_HOME, metadata first,
    with pi0's 50-action ``delta_timestamps`` at the dataset's fps, as openpi's loader does."""
    episodes = _source_episodes(sources)
    picks, starts = _picks(episodes)
    read = _read(dataset_v21, picks, tmp_path / "read.npz", chunk=CHUNK)
    assert all(read[f"{i}/action"].shape == (CHUNK, 8) for i in picks)
    assert read[f"{picks[-1]}/action_is_pad"][1:].all(), "the last frame's chunk is padding"
    _check_read(read, episodes, picks, starts, dataset_v21, "v2.1")


def test_both_formats_hold_the_same_frames_states_actions_and_tasks(dataset, dataset_v21):
    v30, v21 = layout("v3.0"), layout("v2.1")
    for e in range(3):
        assert (dataset / v30.data_file(e)).read_bytes() == (
            dataset_v21 / v21.data_file(e)
        ).read_bytes()
        for camera in CAMERAS:
            key = f"observation.images.{camera}"
            ours, theirs = dataset / v30.video_file(e, key), dataset_v21 / v21.video_file(e, key)
            assert ours.read_bytes() == theirs.read_bytes(), f"{key} of episode {e}"
    table = pq.read_table(dataset / "meta/episodes/chunk-000/file-000.parquet").to_pylist()
    lines = (dataset_v21 / "meta/episodes.jsonl").read_text().splitlines()
    stats = (dataset_v21 / "meta/episodes_stats.jsonl").read_text().splitlines()
    for row, line, stat in zip(table, lines, stats, strict=True):
        episode, stat = json.loads(line), json.loads(stat)
        assert stat["episode_index"] == episode["episode_index"] == row["episode_index"]
        for key in ("tasks", "length", "instructmove/spec", "instructmove/seed"):
            assert episode[key] == row[key]
        for feature, values in stat["stats"].items():
            assert values == {k: row[f"stats/{feature}/{k}"] for k in values}, feature
            assert set(values) == {"min", "max", "mean", "std", "count"}
    tasks = [
        json.loads(line) for line in (dataset_v21 / "meta/tasks.jsonl").read_text().splitlines()
    ]
    assert [t["task"] for t in tasks] == list(pd.read_parquet(dataset / "meta/tasks.parquet").index)
    info30, info21 = (
        json.loads((d / "meta/info.json").read_text()) for d in (dataset, dataset_v21)
    )
    assert info30["features"] == info21["features"]
    assert (info21["codebase_version"], info21["total_videos"], info21["total_chunks"]) == (
        "v2.1",
        9,
        1,
    )
    for name in ("meta/stats.json", groot.MODALITY):
        assert (dataset / name).read_text() == (dataset_v21 / name).read_text()


def _files(root: Path) -> dict[str, bytes]:
    """Every file of a dataset (not our lock) by its path, with its bytes."""
    return {
        str(f.relative_to(root)): f.read_bytes()
        for f in sorted(root.rglob("*"))
        if f.is_file() and f.name != ".instructmove.lock"
    }


def test_a_killed_export_resumes_to_the_same_bytes(sources, dataset_v21, tmp_path, monkeypatch):
    """v2.1 (the v3.0 export shares the writer and its records; only ``meta/`` differs)."""
    out = tmp_path / "resumed"
    settings = LeRobotSettings(REPO, WIDTH, HEIGHT, "v2.1")
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
    resumed, uninterrupted = _files(out), _files(dataset_v21)
    assert sorted(resumed) == sorted(uninterrupted)
    changed = [name for name in resumed if resumed[name] != uninterrupted[name]]
    assert not changed, f"differ from the uninterrupted export: {changed}"


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


@contextlib.contextmanager
def _served(verb: list[str]):
    """``instructmove VERB ... --port P`` running until the block ends; yields its URI once
    openpi's server answers /healthz."""
    port = _free_port()
    server = subprocess.Popen(
        [sys.executable, "-m", "instructmove_ms.cli", *verb, "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        for _ in range(1200):
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/healthz", timeout=1):
                    break
            except OSError:
                assert server.poll() is None, server.stderr.read().decode()[-3000:]
                time.sleep(0.1)
        yield f"ws://127.0.0.1:{port}"
    finally:
        server.kill()
        server.wait()


def test_the_loop_export_serve_evaluate_scores_the_demos(sources, dataset_v21, tmp_path, capsys):
    """The demos, exported to LeRobot, replayed by openpi's own server from the dataset and
    evaluated through the websocket on the demos' own episodes, succeed as the demos did:
    the export's keys, state units and action order, the chunking and the timing agree."""
    with _served(["serve-replay", "--dataset", str(dataset_v21)]) as uri:
        for k, source in enumerate(sources):
            argv = ["eval", "--traj", str(source), "--policy", uri]
            assert main([*argv, "--out", str(tmp_path / f"eval{k}")]) == 0
            out = capsys.readouterr().out
            assert json.loads(out.split("policy: ")[1])["requests"] > 10
            (group,) = json.loads((tmp_path / f"eval{k}" / "summary.json").read_text())["groups"]
            assert group["success"] == 1.0 and group["success_at_end"] == 1.0, group


#: A small ACT (no pretrained backbone) that lerobot-train trains on 2 CPU cores in two minutes.
ACT = [
    "--policy.type=act",
    "--policy.pretrained_backbone_weights=null",
    "--policy.dim_model=128",
    "--policy.dim_feedforward=512",
    "--policy.n_heads=8",
    "--policy.n_encoder_layers=1",
    "--policy.n_decoder_layers=1",
    "--policy.chunk_size=10",
    "--policy.n_action_steps=10",
    "--policy.use_vae=false",
    "--policy.dropout=0",
    "--policy.optimizer_lr=5e-4",
    "--policy.optimizer_lr_backbone=5e-4",
    "--policy.device=cpu",
    "--policy.push_to_hub=false",
]
TRAIN_STEPS = 300
#: lerobot's processes: offline, and torch on one thread (the suite's other worker keeps the
#: second core busy; threads spinning against it slowed training several times over).
LEROBOT_ENV = {"HF_HUB_OFFLINE": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
#: The trained checkpoint's loss on a fixed batch, at most this fraction of a fresh policy's.
LEARNED = 0.75
FIXED_BATCH = Path(__file__).parent / "tools" / "lerobot_fixed_batch_loss.py"


def _fixed_batch_loss(checkpoint: Path, dataset: Path) -> dict:
    """The training loss of ``checkpoint`` and of a freshly initialised policy of its config
    on a fixed batch of ``dataset`` (tests/tools/lerobot_fixed_batch_loss.py, in the lerobot
    environment)."""
    argv = [str(LEROBOT_PYTHON), str(FIXED_BATCH), str(checkpoint), str(dataset), REPO]
    env = {**os.environ, **LEROBOT_ENV}
    run = subprocess.run(argv, capture_output=True, text=True, env=env, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    return json.loads(run.stdout.strip().splitlines()[-1])


def test_lerobot_trains_on_the_export_and_its_checkpoint_is_served_and_evaluated(
    dataset, tmp_path, capsys
):
    """The loop a user runs: lerobot-train on our v3.0 export (it learns: on a fixed batch its
    loss falls below ``LEARNED`` of a fresh policy's, under any CPU's torch kernels), the
    checkpoint served with openpi's protocol by ``instructmove serve-lerobot`` (lerobot's own
    pre/post-processors), and ``instructmove eval`` on a stored held-out episode: every row
    scored, none with an error (no success is expected of two minutes of CPU training)."""
    out = tmp_path / "train"
    argv = [str(LEROBOT_PYTHON.parent / "lerobot-train"), f"--dataset.repo_id={REPO}"]
    argv += [f"--dataset.root={dataset}", *ACT, f"--steps={TRAIN_STEPS}", "--batch_size=8"]
    argv += ["--num_workers=0", "--log_freq=10", f"--save_freq={TRAIN_STEPS}", "--eval_freq=0"]
    argv += ["--wandb.enable=false", f"--output_dir={out}"]
    env = {**os.environ, **LEROBOT_ENV}
    run = subprocess.run(argv, capture_output=True, text=True, env=env, timeout=1200)
    assert run.returncode == 0, run.stderr[-3000:]
    losses = [float(x) for x in re.findall(r"step:\S+ .*? loss:([0-9.]+)", run.stdout + run.stderr)]
    assert len(losses) == TRAIN_STEPS // 10, losses  # lerobot-train logged its progress
    checkpoint = out / "checkpoints" / "last" / "pretrained_model"
    fixed = _fixed_batch_loss(checkpoint, dataset)
    print(f"fixed-batch loss: {fixed}")
    assert fixed["trained"] < LEARNED * fixed["initial"], f"it did not learn: {fixed}"
    verb = ["serve-lerobot", "--checkpoint", str(checkpoint), "--python", str(LEROBOT_PYTHON)]
    with _served(verb) as uri:
        argv = ["eval", "--task", "PickCategory-InstructMove", "--robot", "franka"]
        argv += ["--split", "unseen_category", "--episodes", "1", "--policy", uri]
        argv += ["--image-size", f"{WIDTH}x{HEIGHT}", "--out", str(tmp_path / "eval")]
        assert main(argv) == 0
    served = json.loads(capsys.readouterr().out.split("policy: ")[1])
    assert served["requests"] >= 10, served
    rows = [json.loads(line) for line in (tmp_path / "eval" / "episodes.jsonl").open()]
    assert len(rows) == 1 and all(row["error"] is None for row in rows), rows


def _groot_read(root: Path, episode: int) -> dict:
    """A reader in the manner of GR00T's LeRobot loader: ``meta/modality.json`` slices
    ``observation.state`` and ``action`` into named parts, maps video keys to features and
    the annotation column to task strings through ``meta/tasks.jsonl``."""
    modality = json.loads((root / groot.MODALITY).read_text())
    info = json.loads((root / "meta" / "info.json").read_text())
    tasks = {
        t["task_index"]: t["task"]
        for t in map(json.loads, (root / "meta" / "tasks.jsonl").read_text().splitlines())
    }
    path = root / info["data_path"].format(episode_chunk=0, episode_index=episode)
    frame = pd.read_parquet(path)
    out = {"names": {}, "videos": {}}
    for group, column in (("state", "observation.state"), ("action", "action")):
        values, names = np.stack(frame[column].to_numpy()), info["features"][column]["names"]
        for part, span in modality[group].items():
            out[f"{group}.{part}"] = values[:, span["start"] : span["end"]]
            out["names"][f"{group}.{part}"] = names[span["start"] : span["end"]]
    for camera, spec in modality["video"].items():
        assert info["features"][spec["original_key"]]["dtype"] == "video"
        out["videos"][camera] = root / info["video_path"].format(
            episode_chunk=0, video_key=spec["original_key"], episode_index=episode
        )
    for key, spec in modality["annotation"].items():
        column = spec.get("original_key", f"annotation.{key}")
        out[f"annotation.{key}"] = [tasks[int(i)] for i in frame[column]]
    return out


def test_groot_modality_slices_name_the_state_and_action_parts(sources, dataset_v21):
    episodes = _source_episodes(sources)
    read = _groot_read(dataset_v21, 2)
    assert read["names"]["state.arm"] == [f"panda_joint{j}" for j in range(1, 8)]
    assert read["names"]["state.gripper"] == read["names"]["action.gripper"] == ["gripper"]
    actions, _, instruction = episodes[2]
    whole = np.concatenate([read["action.arm"], read["action.gripper"]], axis=1)
    np.testing.assert_array_equal(whole, actions.astype(np.float32))
    assert set(read["annotation.human.task_description"]) == {instruction}
    assert sorted(read["videos"]) == list(CAMERAS)
    assert all(path.is_file() for path in read["videos"].values())


@pytest.mark.parametrize("robot", ["franka", "piperx"])
def test_policy_interface_parts_cover_its_names_arm_by_arm(robot):
    env = make_env(robot_uids=robot, control_mode="pd_joint_pos")
    interface = env.unwrapped.agent.policy_interface()
    env.close()
    parts = interface.parts()
    covered = [i for start, end in parts.values() for i in range(start, end)]
    assert covered == list(range(len(interface.names))), "in order, each dimension once"
    for part, (start, end) in parts.items():
        names = interface.names[start:end]
        side = part.split("_")[0] if "_" in part else ""
        assert all(side in name for name in names), (part, names)
        assert ("gripper" in part) == all("gripper" in name for name in names), (part, names)
    expected = {"franka": ["arm", "gripper"], "piperx": ["left_arm", "right_arm"]}
    assert list(parts)[:2] == expected[robot]


def test_groot_modality_config_registers_the_datasets_keys(dataset_v21, monkeypatch):
    """The modality config file, run against stand-ins of the GR00T modules it imports
    (Isaac-GR00T is not on PyPI), registers the modality.json keys for a new embodiment."""
    import types

    registered = {}
    stand_ins = {
        "gr00t.configs.data.embodiment_configs": {
            "register_modality_config": lambda config, embodiment_tag: registered.update(
                config=config, tag=embodiment_tag
            )
        },
        "gr00t.data.embodiment_tags": {
            "EmbodimentTag": types.SimpleNamespace(NEW_EMBODIMENT="new_embodiment")
        },
        "gr00t.data.types": {
            "ModalityConfig": lambda **kw: kw,
            "ActionConfig": lambda **kw: kw,
            "ActionFormat": types.SimpleNamespace(DEFAULT="default"),
            "ActionRepresentation": types.SimpleNamespace(ABSOLUTE="absolute"),
            "ActionType": types.SimpleNamespace(NON_EEF="non_eef"),
        },
    }
    for name, attrs in stand_ins.items():
        monkeypatch.setitem(sys.modules, name, types.SimpleNamespace(**attrs))
    source = (dataset_v21 / groot.CONFIG).read_text()
    exec(compile(source, groot.CONFIG, "exec"), {"__name__": "instructmove_config"})
    config, modality = registered["config"], json.loads((dataset_v21 / groot.MODALITY).read_text())
    assert registered["tag"] == "new_embodiment"
    assert config["video"]["modality_keys"] == list(modality["video"])
    assert config["state"]["modality_keys"] == list(modality["state"]) == ["arm", "gripper"]
    assert config["action"]["modality_keys"] == list(modality["action"])
    assert len(config["action"]["action_configs"]) == len(modality["action"])
    assert config["action"]["delta_indices"] == list(range(groot.ACTION_HORIZON))
    language = config["language"]["modality_keys"]
    assert [key.removeprefix("annotation.") for key in language] == list(modality["annotation"])
