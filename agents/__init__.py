"""Robots of InstructMove-MS; importing registers them with ManiSkill."""

from .franka import FRANKA_REST_QPOS, FrankaInstructMove
from .interface import InstructMoveAgent
from .piperx import PiperX, PiperXSingle

ROBOTS = ("franka", "piperx", "piperx_single")

__all__ = [
    "FRANKA_REST_QPOS",
    "ROBOTS",
    "FrankaInstructMove",
    "InstructMoveAgent",
    "PiperX",
    "PiperXSingle",
]
