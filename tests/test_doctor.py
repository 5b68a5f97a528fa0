"""``instructmove doctor`` on this machine and with simulated faults, and GPU physics that
fails in one line where SAPIEN's PhysX GPU library is missing (no network call)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import gymnasium as gym
import pytest
import requests
import sapien.physx
import torch

from instructmove_ms import doctor, gpu_physics, heldout
from instructmove_ms.cli import main
from instructmove_ms.floats import cpu_model

CORE = [name for name, core, _ in doctor.CHECKS if core]


def _doctor(*args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    """``instructmove doctor ARGS`` in a fresh process (rendering starts once per process)."""
    argv = [sys.executable, "-m", "instructmove_ms.cli", "doctor", *args]
    return subprocess.run(
        argv, capture_output=True, text=True, env={**os.environ, **(env or {})}, timeout=600
    )


@pytest.fixture
def no_network(monkeypatch):
    """Fail a test where SAPIEN's download (or GPU start) would run."""

    def refuse(*_, **__):
        raise AssertionError("reached for the network or started GPU physics")

    monkeypatch.setattr(requests, "get", refuse)
    monkeypatch.setattr(sapien.physx, "enable_gpu", refuse)


@pytest.fixture
def bare_home(tmp_path, monkeypatch):
    """A home folder without SAPIEN's PhysX GPU library; the path the library would have."""
    monkeypatch.setenv("HOME", str(tmp_path))
    return tmp_path / ".sapien" / "physx" / sapien.physx.version() / "libPhysXGpu_64.so"


def test_a_healthy_machine_is_reported_line_by_line_and_exits_0(tmp_path):
    run = _doctor("--json", env={"HOME": str(tmp_path)})
    assert run.returncode == 0, run.stdout + run.stderr
    report = json.loads(run.stdout)
    found = {f["name"]: f for f in report["findings"]}
    assert report["ok"] and list(found) == [name for name, _, _ in doctor.CHECKS]
    assert all(found[name]["status"] == "ok" for name in CORE), found
    assert cpu_model() in found["floating point"]["detail"]
    assert "every hash matches" in found["asset library"]["detail"]
    assert found["rendering"]["detail"].endswith(" ms")
    gpu = found["gpu physics"]
    assert gpu["status"] == "warn" and str(tmp_path / ".sapien" / "physx") in gpu["detail"]
    text = _doctor(env={"HOME": str(tmp_path)})
    lines = text.stdout.splitlines()
    assert len(lines) == len(doctor.CHECKS) and lines[0].startswith("ok   packages: Python")


def test_a_machine_without_a_rendering_device_is_broken_and_says_why():
    run = _doctor(env={"VK_ICD_FILENAMES": "/nonexistent/icd.json"})
    assert run.returncode == 1
    (line,) = [x for x in run.stdout.splitlines() if x.startswith("fail rendering:")]
    assert "failed to find a rendering device" in line and "lavapipe" in line
    assert run.stdout.splitlines()[-1].startswith("broken: ") and "rendering" in line


def test_simulated_faults_each_give_their_line(tmp_path, monkeypatch):
    def stale(*_, **__):
        raise ValueError("snapshot 'recognisable' is stale: mug #5 (x) changed since it was frozen")

    monkeypatch.setattr("instructmove_ms.assets.load_snapshot", stale)
    monkeypatch.setattr(doctor, "CORE_PACKAGES", (*doctor.CORE_PACKAGES, "no-such-dist"))
    copy = tmp_path / "v5"
    shutil.copytree(heldout.default_folder(), copy)
    first = sorted(copy.glob("*/*/*.jsonl"))[0]
    first.write_text(first.read_text().replace('"seed": ', '"seed": 1', 1))
    monkeypatch.setattr(heldout, "default_folder", lambda version=None: copy)
    findings = doctor.run_checks(only=("packages", "asset library", "stored sets"))
    lines = [f.line() for f in findings]
    assert lines[0].startswith("fail packages: missing: no-such-dist"), lines
    assert lines[1].startswith("fail asset library: ValueError: snapshot 'recognisable' is stale")
    assert lines[2].startswith("fail stored sets: differ from their checksums: v")
    assert first.relative_to(copy).as_posix() in lines[2]
    assert [f.name for f in doctor.broken(findings)] == ["packages", "asset library", "stored sets"]


@pytest.mark.parametrize(
    ("backend", "num_envs", "gpu"),
    [("auto", 1, False), ("auto", 4, True), ("cpu", 1, False), ("physx_cpu", 1, False)]
    + [("physx_cuda", 1, True), ("gpu", 1, True), ("cuda:1", 2, True)],
)
def test_which_backends_start_gpu_physics(backend, num_envs, gpu):
    assert gpu_physics.uses_gpu_physics(backend, num_envs) is gpu


def test_eval_on_gpu_physics_without_its_library_is_one_line_and_writes_nothing(
    bare_home, no_network, tmp_path, capsys
):
    out = tmp_path / "eval"
    argv = ["eval", "--task", "PickCategory-InstructMove", "--policy", "oracle", "--episodes"]
    argv += ["1", "--num-envs", "4", "--sim-backend", "physx_cuda", "--out", str(out)]
    assert main(argv) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("instructmove: error: GPU physics needs SAPIEN's PhysX GPU library")
    assert f"libPhysXGpu_64.so (PhysX {sapien.physx.version()})" in line
    assert f"in {bare_home.parent}/, which is missing" in line
    assert not out.exists()


def test_an_env_on_gpu_physics_without_its_library_fails_before_sapien(bare_home, no_network):
    with pytest.raises(gpu_physics.GpuPhysicsUnavailable, match=str(bare_home.parent)):
        gym.make("PickCategory-InstructMove", sim_backend="physx_cuda", render_backend="none")


def test_with_the_library_present_cuda_is_asked_next(bare_home, no_network):
    bare_home.parent.mkdir(parents=True)
    bare_home.write_bytes(b"")  # present (never loaded here)
    expected = None if torch.cuda.is_available() else "GPU physics needs a CUDA device"
    found = gpu_physics.problem()
    assert (found and found.split(";")[0]) == expected
