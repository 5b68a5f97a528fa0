"""Reliability from the outside: resumed evaluations equal uninterrupted ones, torn result
files are repaired, bad input gets one line and writes nothing, output folders are locked
and cleaned, a lost policy server stops the run without scoring its episodes."""

from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import torch
from websockets.sync.server import serve

from instructmove_ms import heldout
from instructmove_ms.demos.generate import generate
from instructmove_ms.evaluation import evaluate_config
from instructmove_ms.files import LOCK, PART, OutputLock, read_rows
from instructmove_ms.guard import ServerError
from instructmove_ms.policies import RandomPolicy
from instructmove_ms.remote import RemotePolicy, packb, unpackb

TASK = "PickCategory-InstructMove"
STEPS = 6  # a short horizon: these tests are about the bookkeeping


def _config(episodes: int = 4) -> heldout.EvaluatorConfig:
    config = heldout.evaluator_config(TASK, "franka", "seen", episodes=episodes)
    return dataclasses.replace(config, max_episode_steps=STEPS)


def _lines(folder: Path) -> list[dict]:
    return [json.loads(line) for line in (folder / "episodes.jsonl").read_text().splitlines()]


class Interrupted(RandomPolicy):
    """Random actions; Ctrl-C in the middle of episode ``stop_at`` (counted from 0)."""

    def __init__(self, stop_at: int) -> None:
        super().__init__(0)
        self.stop_at, self.episode = stop_at, -1

    def reset(self, obs, seed: int | None = None) -> None:
        super().reset(obs, seed)
        self.episode += 1

    def act(self, obs):
        if self.episode == self.stop_at:
            raise KeyboardInterrupt
        return super().act(obs)


def test_a_resumed_stochastic_evaluation_equals_an_uninterrupted_one(tmp_path):
    config = _config()
    evaluate_config(RandomPolicy(0), config, tmp_path / "whole")
    with pytest.raises(KeyboardInterrupt):
        evaluate_config(Interrupted(stop_at=2), config, tmp_path / "resumed")
    assert len(_lines(tmp_path / "resumed")) == 2
    evaluate_config(RandomPolicy(0), config, tmp_path / "resumed")  # a fresh process's policy
    assert _lines(tmp_path / "resumed") == _lines(tmp_path / "whole")
    whole = json.loads((tmp_path / "whole" / "summary.json").read_text())
    assert json.loads((tmp_path / "resumed" / "summary.json").read_text()) == whole


def test_a_torn_last_row_is_cut_before_the_resume_appends(tmp_path):
    config = _config(3)
    evaluate_config(RandomPolicy(0), config, tmp_path / "whole")
    rows = (tmp_path / "whole" / "episodes.jsonl").read_text().splitlines()
    out = tmp_path / "torn"
    out.mkdir()
    (out / "episodes.jsonl").write_text(rows[0] + "\n" + rows[1][: len(rows[1]) // 2])
    evaluate_config(RandomPolicy(0), config, out)
    assert _lines(out) == _lines(tmp_path / "whole"), "every line parses, none twice"


def test_read_rows_repairs_only_the_tail(tmp_path):
    path = tmp_path / "rows.jsonl"
    path.write_text('{"a": 1}\n{"a": 2}\n{"a"')
    assert read_rows(path) == [{"a": 1}, {"a": 2}]
    assert path.read_text() == '{"a": 1}\n{"a": 2}\n'
    path.write_text('{"a": 1}\n{"a": 2\n{"a": 3}\n')
    with pytest.raises(ValueError, match=r"rows.jsonl:2: not a JSON row"):
        read_rows(path)


def _cli(*argv: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "instructmove_ms.cli", *argv],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=600,
    )


@pytest.fixture(scope="module")
def demo(tmp_path_factory) -> Path:
    """A recorded demo trajectory (one episode) to feed converters broken copies of."""
    out = tmp_path_factory.mktemp("demo")
    return generate(TASK, "franka", 1, out, shard_size=1).path


def _bad_inputs(tmp_path: Path, demo: Path) -> dict[str, tuple[list[str], str]]:
    """name -> (arguments, what the one-line error names)."""
    truncated = tmp_path / "truncated" / demo.name
    truncated.parent.mkdir()
    for suffix in (".json", ".episodes.json"):
        name = demo.name.replace(".h5", suffix)
        (truncated.parent / name).write_bytes((demo.parent / name).read_bytes())
    truncated.write_bytes(demo.read_bytes()[:4000])
    malformed = tmp_path / "malformed" / demo.name
    malformed.parent.mkdir()
    malformed.write_bytes(demo.read_bytes())
    (malformed.parent / demo.name.replace(".h5", ".json")).write_text("{not json")
    config = heldout.evaluator_config(TASK, "franka", "seen", episodes=1).to_dict()
    lacking = json.loads(json.dumps(config))
    del lacking["episodes"][0]["reset_kwargs"]["options"]["episode"]["objects"]
    (tmp_path / "lacking.json").write_text(json.dumps(lacking))
    unknown = json.loads(json.dumps(config))
    unknown["episodes"][0]["reset_kwargs"]["options"]["episode"]["objects"][0]["uuid"] = "x-1"
    (tmp_path / "unknown.json").write_text(json.dumps(unknown))
    misnamed = json.loads(json.dumps(config))
    misnamed["episodes"][0]["reset_kwargs"]["options"]["episode"]["instruction"] = "pick it up"
    (tmp_path / "misnamed.json").write_text(json.dumps(misnamed))
    earlier = tmp_path / "earlier.pt"
    torch.save({"model": {"crop.0.weight": torch.zeros(1)}, "vocabulary": None}, earlier)
    out = ["--out", str(tmp_path / "out")]
    evaluate = ["eval", "--task", TASK, "--robot", "franka"]
    convert = ["demos", "convert", "--traj"]
    return {
        "unknown task": (["episode", "--task", "Nope"], "unknown task 'Nope'; allowed"),
        "no module": ([*evaluate, "--policy", "nosuchmodule:Cls", *out], "'nosuchmodule'"),
        "no class": ([*evaluate, "--policy", "json:NoSuchClass", *out], "no 'NoSuchClass'"),
        "no server": ([*evaluate, "--policy", "ws://127.0.0.1:1", *out], "ws://127.0.0.1:1"),
        "groot over websocket": (
            [*evaluate, "--policy", "ws://127.0.0.1:1", "--obs-format", "groot", *out],
            "speaks the groot format",
        ),
        "no checkpoint": (
            [*evaluate, "--policy", f"grounded:{tmp_path / 'none.pt'}", *out],
            f"no grounding checkpoint at {tmp_path / 'none.pt'}",
        ),
        "checkpoint of an earlier network": (
            [*evaluate, "--policy", f"grounded:{earlier}", *out],
            f"the grounding checkpoint at {earlier} does not fit this version's network",
        ),
        "held-out seeds of one": (
            ["train-grounding", "--held-out", "1", "--out", str(tmp_path / "g.pt")],
            "held_out must be 0 (none) or 2 or more, got 1",
        ),
        "no training scenes": (
            ["train-grounding", "--scenes", "0", "--out", str(tmp_path / "g.pt")],
            "training scenes must be 1 or more, got 0",
        ),
        "pixels without sets": (
            ["audit", "--sampler", "2", "--fresh-scenes", "1", "--pixel-scenes", "5", *out],
            "the pixel adversary judges stored sets",
        ),
        "zero episodes": ([*evaluate, "--policy", "random", "--episodes", "0", *out], "got 0"),
        "negative episodes": ([*evaluate, "--policy", "random", "--episodes", "-1", *out], "-1"),
        "spec lacks a field": (
            ["eval", "--config", str(tmp_path / "lacking.json"), "--policy", "random", *out],
            "lacks objects",
        ),
        "unknown uuid": (
            ["eval", "--config", str(tmp_path / "unknown.json"), "--policy", "random", *out],
            "'x-1'",
        ),
        "unverified episode": (
            ["eval", "--config", str(tmp_path / "misnamed.json"), "--policy", "random", *out],
            "config episode 0 fails the verifier: instruction 'pick it up' matches candidates []",
        ),
        "sheet of an unknown task": (
            ["episodes", "sheet", "--task", "Nope", *out],
            "unknown task 'Nope'; allowed",
        ),
        "truncated h5": ([*convert, str(truncated), *out], str(truncated)),
        "truncated h5 to lerobot": (
            ["export", "lerobot", "--traj", str(truncated), *out, "--repo-id", "me/x"],
            str(truncated),
        ),
        "malformed json": ([*convert, str(malformed), *out], str(malformed.parent)),
        "zero workers": (
            ["demos", "generate", "--task", TASK, "-n", "1", "--workers", "0", *out],
            "workers must be at least 1, got 0",
        ),
        "unknown axis": (
            [*evaluate, "--policy", "random", "--perturb", "lights:2", *out],
            "unknown perturbation axis 'lights'; axes: lighting,",
        ),
        "level out of range": (
            ["demos", "generate", "--task", TASK, "-n", "1", "--perturb", "layout:5", *out],
            "perturbation level 5 of 'layout' outside 0..3",
        ),
        "perturbed config": (
            [
                "eval",
                "--config",
                str(tmp_path / "unknown.json"),
                "--policy",
                "random",
                *out,
                "--perturb",
                "camera:1",
            ],
            "--perturb applies to the stored sets (--task)",
        ),
        "workers and ray": (
            [*evaluate, "--policy", "random", "--workers", "2", "--ray", "auto", *out],
            "--workers 2 with --ray",
        ),
    }


def test_every_bad_input_gets_one_line_a_failure_and_no_output(tmp_path, demo):
    for name, (argv, named) in _bad_inputs(tmp_path, demo).items():
        result = _cli(*argv, cwd=tmp_path)
        lines = result.stderr.strip().splitlines()
        assert result.returncode != 0, name
        assert len(lines) == 1 and lines[0].startswith("instructmove: error:"), (name, lines)
        assert named in lines[0], (name, lines[0])
        assert not (tmp_path / "out").exists(), f"{name}: output written"


def test_a_second_generator_on_the_same_folder_is_refused(tmp_path):
    held = rf"in use by process {os.getpid()} \(the first run"
    with OutputLock(tmp_path, "the first run"), pytest.raises(ValueError, match=held):
        generate(TASK, "franka", 1, tmp_path)
    first = subprocess.Popen(
        [sys.executable, "-c", _HOLD, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    assert first.stdout.readline().strip() == "locked"
    result = _cli(
        "demos", "generate", "--task", TASK, "-n", "1", "--out", str(tmp_path), cwd=tmp_path
    )
    first.kill()
    first.wait()
    assert result.returncode == 2
    assert f"in use by process {first.pid} (holder)" in result.stderr
    assert not (tmp_path / "shards").exists()


_HOLD = """
import sys, time
from instructmove_ms.files import OutputLock
with OutputLock(sys.argv[1], "holder"):
    print("locked", flush=True)
    time.sleep(600)
"""


def test_a_resumed_generator_removes_what_a_killed_one_left(tmp_path):
    stale = tmp_path / ".staging-abc123"
    stale.mkdir()
    (stale / "PickCategory-InstructMove_franka_00000.h5").write_bytes(b"partial")
    torn = tmp_path / f".ledger.json{PART}xyz.json"
    torn.write_text("{")
    report = generate(TASK, "franka", 1, tmp_path, shard_size=1)
    assert report.kept == 1 and not stale.exists() and not torn.exists()
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == [LOCK]


class HoldStillServer:
    """An openpi-style policy server on loopback that holds the Franka still; it can be
    told to die after ``die_after`` requests."""

    def __init__(self, die_after: int | None = None) -> None:
        self.requests, self.die_after = 0, die_after
        self.server = serve(self._handle, "127.0.0.1", 0)
        self.uri = f"ws://127.0.0.1:{self.server.socket.getsockname()[1]}"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def _handle(self, ws) -> None:
        ws.send(packb({"server": "hold"}))
        for message in ws:
            self.requests += 1
            if self.die_after is not None and self.requests > self.die_after:
                threading.Thread(target=self.server.shutdown, daemon=True).start()
                return
            qpos = unpackb(message)["observation"]["agent"]["qpos"][:8].astype(np.float32)
            ws.send(packb({"actions": qpos[None]}))

    def stop(self) -> None:
        self.server.shutdown()


def test_a_lost_policy_server_stops_the_run_and_a_resume_finishes_it(tmp_path):
    config = _config(3)
    whole = HoldStillServer()
    evaluate_config(
        RemotePolicy(whole.uri, "maniskill", obs_mode="state_dict"), config, tmp_path / "whole"
    )
    whole.stop()
    dying = HoldStillServer(die_after=STEPS + 2)  # dies in the second episode
    policy = RemotePolicy(dying.uri, "maniskill", obs_mode="state_dict", retries=2, backoff=0.05)
    start = time.perf_counter()
    with pytest.raises(ServerError, match=dying.uri):
        evaluate_config(policy, config, tmp_path / "resumed")
    assert time.perf_counter() - start < 60, "the back-off is bounded"
    rows = _lines(tmp_path / "resumed")
    assert [r["episode_id"] for r in rows] == [0] and rows[0]["error"] is None
    back = HoldStillServer()  # the server is back (at its new address)
    evaluate_config(
        RemotePolicy(back.uri, "maniskill", obs_mode="state_dict"), config, tmp_path / "resumed"
    )
    back.stop()
    assert _lines(tmp_path / "resumed") == _lines(tmp_path / "whole")
    assert all(r["error"] is None for r in _lines(tmp_path / "resumed"))


def test_a_brief_drop_of_the_connection_is_bridged():
    server = HoldStillServer()
    policy = RemotePolicy(server.uri, "maniskill", obs_mode="state_dict", retries=3, backoff=0.05)
    obs = {"agent": {"qpos": np.zeros((1, 9), dtype=np.float32)}}
    policy.act(obs)
    policy.channel.socket.close()  # the connection drops; the server is still there
    assert policy.act(obs).shape == (1, 8)
    policy.close()
    server.stop()
