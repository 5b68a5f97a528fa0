"""Importing registers everything; ManiSkill's own processes find our envs by themselves."""

from __future__ import annotations

import subprocess
import sys

import gymnasium as gym
from mani_skill.agents.registration import REGISTERED_AGENTS
from mani_skill.utils.registration import REGISTERED_ENVS

from instructmove_ms.tasks import TASKS


def test_import_registers_envs_and_robots():
    for env_id in TASKS:
        assert env_id in REGISTERED_ENVS
        assert env_id in gym.registry
    assert "franka" in REGISTERED_AGENTS


def _run(code: str) -> str:
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd="/"
    )
    return out.stdout.strip().splitlines()[-1]


def test_maniskill_process_sees_envs_without_importing_us():
    code = (
        "import mani_skill.envs\n"
        "from mani_skill.utils.registration import REGISTERED_ENVS\n"
        "print('PickCategory-InstructMove' in REGISTERED_ENVS)"
    )
    assert _run(code) == "True"


def test_plain_process_does_not_load_maniskill_or_us():
    code = (
        "import sys\n"
        "print(sorted(m for m in sys.modules if m.startswith(('mani_skill', 'instructmove_ms.'))))"
    )
    assert _run(code) == "[]"
