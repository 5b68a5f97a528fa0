"""Long jobs on local worker processes and on a Ray cluster: the same outputs as one process,
byte for byte, with a worker killed mid-shard; without Ray every command works as before."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import psutil
import pytest

from instructmove_ms.demos.generate import generate
from instructmove_ms.evaluation import evaluate
from instructmove_ms.executor import Workers
from instructmove_ms.policies import RandomPolicy

TASK, ROBOT = "PickCategory-InstructMove", "franka"
EPISODES = 4


class MarkedRandomPolicy(RandomPolicy):
    """Random actions, a little slowed, leaving a file named after the process that runs
    each episode (so a test can kill it mid-episode)."""

    def __init__(self, marks: Path) -> None:
        super().__init__()
        self.marks = marks

    def reset(self, obs, seed: int | None = None) -> None:
        (self.marks / f"{os.getpid()}-{seed}").touch()
        super().reset(obs, seed)

    def act(self, obs):
        time.sleep(0.004)
        return super().act(obs)


def _files(folder: Path) -> dict[str, bytes]:
    """Every result file of a run by name (the lock file and run logs aside)."""
    return {
        str(p.relative_to(folder)): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not p.name.startswith(".") and p.name != "errors.log"
    }


def _kill_once(find, killed: list[int], stop: threading.Event, after: float) -> None:
    """Kill (SIGKILL) the first process ``find()`` returns, ``after`` seconds after it
    appears; record its pid."""
    while not stop.is_set():
        pid = find()
        if pid is not None:
            time.sleep(after)
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)
            return
        time.sleep(0.05)


def _killing(find, after: float):
    killed: list[int] = []
    stop = threading.Event()
    thread = threading.Thread(target=_kill_once, args=(find, killed, stop, after), daemon=True)
    thread.start()
    return killed, stop, thread


def _eval(out: Path, policy, workers) -> dict:
    return evaluate(policy, TASK, "seen", out, ROBOT, episodes=EPISODES, workers=workers)


def test_local_workers_give_one_process_rows_with_a_worker_killed_mid_episode(tmp_path):
    """eval --workers 2: the rows and reports of one process, though a worker process was
    killed in the middle of an episode (its pool is rebuilt and the episode run again)."""
    one_marks, two_marks = tmp_path / "marks1", tmp_path / "marks2"
    one_marks.mkdir()
    two_marks.mkdir()
    _eval(tmp_path / "one", MarkedRandomPolicy(one_marks), 1)
    assert {m.name.split("-")[0] for m in one_marks.iterdir()} == {str(os.getpid())}

    def first_worker():
        marks = sorted(two_marks.iterdir(), key=lambda p: p.stat().st_mtime)
        return int(marks[0].name.split("-")[0]) if marks else None

    killed, stop, thread = _killing(first_worker, after=0.3)
    _eval(tmp_path / "two", MarkedRandomPolicy(two_marks), Workers(processes=2))
    stop.set()
    thread.join()
    assert len(killed) == 1, "no worker was killed: the test proved nothing"
    pids = {int(m.name.split("-")[0]) for m in two_marks.iterdir()}
    assert os.getpid() not in pids and killed[0] in pids and len(pids) >= 3  # a new pool
    assert _files(tmp_path / "two") == _files(tmp_path / "one")


@pytest.fixture(scope="module")
def ray_cluster():
    """A two-CPU Ray cluster on loopback for this module; its address."""
    ray = pytest.importorskip("ray")  # a dev dependency: installed by scripts/setup.sh --dev
    ray.init(
        num_cpus=2,
        _node_ip_address="127.0.0.1",
        include_dashboard=False,
        log_to_driver=False,
        logging_level="ERROR",
    )
    yield ray.get_runtime_context().gcs_address
    ray.shutdown()


def _cli(*args: str, hide_ray: bool = False) -> subprocess.CompletedProcess:
    """The instructmove command in a fresh interpreter (with Ray made unimportable)."""
    code = "import sys; from instructmove_ms.cli import main; sys.exit(main(sys.argv[1:]))"
    if hide_ray:
        code = "import sys; sys.modules['ray'] = None; " + code
    return subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=600
    )


def _ray_shard_worker() -> int | None:
    for proc in psutil.process_iter(["pid", "cmdline"]):
        cmdline = proc.info["cmdline"] or []
        if cmdline and cmdline[0] == "ray::_ray_shard":
            return proc.info["pid"]
    return None


def test_ray_demos_equal_one_process_with_a_worker_killed(ray_cluster, tmp_path):
    """demos generate --ray: the shards run as Ray tasks on the cluster, one of them is
    killed mid-shard and retried, and the merged trajectory, sidecar and ledger equal a
    one-process run's, byte for byte."""
    generate(TASK, ROBOT, 2, tmp_path / "one", workers=1, shard_size=1)
    killed, stop, thread = _killing(_ray_shard_worker, after=0.5)
    run = _cli(
        "demos", "generate", "--task", TASK, "--robot", ROBOT, "-n", "2", "--shard-size", "1",
        "--out", str(tmp_path / "ray"), "--ray", ray_cluster,
    )  # fmt: skip
    stop.set()
    thread.join()
    assert run.returncode == 0, run.stderr[-2000:]
    assert len(killed) == 1, "no Ray worker was killed: the test proved nothing"
    assert not list((tmp_path / "ray").rglob(".staging*")), "the killed shard's files remain"
    one, ray = _files(tmp_path / "one"), _files(tmp_path / "ray")
    assert sorted(ray) == sorted(one) and f"{TASK}_{ROBOT}.h5" in one
    assert ray == one


def test_ray_eval_equals_one_process_with_a_worker_killed(ray_cluster, tmp_path):
    """eval --ray: a Ray worker killed in the middle of an episode is retried by Ray, and
    the rows and reports equal a one-process run's."""
    _eval(tmp_path / "one", RandomPolicy(), 1)
    killed, stop, thread = _killing(_ray_shard_worker, after=1.0)
    run = _cli(
        "eval", "--task", TASK, "--robot", ROBOT, "--policy", "random",
        "--episodes", str(EPISODES), "--out", str(tmp_path / "ray"), "--ray", ray_cluster,
    )  # fmt: skip
    stop.set()
    thread.join()
    assert run.returncode == 0, run.stderr[-2000:]
    assert len(killed) == 1, "no Ray worker was killed: the test proved nothing"
    assert _files(tmp_path / "ray") == _files(tmp_path / "one")


def test_without_ray_local_workers_run_and_ray_says_how_to_install(tmp_path):
    """With Ray unimportable, --workers runs as before and never imports Ray; --ray fails
    with the install command and writes nothing."""
    out = tmp_path / "eval"
    run = _cli(
        "eval", "--task", TASK, "--robot", ROBOT, "--policy", "random", "--episodes", "2",
        "--out", str(out), "--workers", "2", hide_ray=True,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-2000:]
    assert len((out / "episodes.jsonl").read_text().splitlines()) == 2
    for command in (
        ["demos", "generate", "--task", TASK, "-n", "1", "--out", str(tmp_path / "d")],
        ["eval", "--task", TASK, "--policy", "random", "--out", str(tmp_path / "e")],
    ):
        run = _cli(*command, "--ray", hide_ray=True)
        assert run.returncode == 2
        assert "pip install 'instructmove-ms[ray]'" in run.stderr
    assert not (tmp_path / "d").exists() and not (tmp_path / "e").exists()


def _stateful_shard(shard: int, tick) -> int:
    """A shard that builds its process's job object once (``worker_state``)."""
    from instructmove_ms.executor import worker_state

    worker_state("log test", lambda: object())
    return shard


def test_the_worker_log_times_each_workers_start_env_and_shards(tmp_path, monkeypatch):
    from instructmove_ms import worker_log

    log = tmp_path / "workers.jsonl"
    monkeypatch.setenv(worker_log.VARIABLE, str(log))
    assert sorted(r for _, r in Workers(2).run(_stateful_shard, list(range(6)))) == list(range(6))
    events = worker_log.read(str(log))
    kinds = [e["event"] for e in events]
    assert kinds.count("pool") == 1 and kinds.count("shard_start") == kinds.count("shard_end") == 6
    workers = {e["pid"] for e in events if e["event"] == "start"}
    assert workers and os.getpid() not in workers
    pool = next(e["t"] for e in events if e["event"] == "pool")
    for pid in {e["pid"] for e in events if e["event"] == "shard_start"}:
        mine = [e for e in events if e["pid"] == pid]
        times = [e["t"] for e in mine]
        assert mine[0]["event"] == "start" and pool <= times[0] and times == sorted(times)
        assert [e["event"] for e in mine].count("env") == 1, "its job object built once"
