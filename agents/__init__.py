"""Robots of InstructMove-MS; importing registers them with ManiSkill."""

from .franka import FRANKA_REST_QPOS, FrankaInstructMove
from .interface import InstructMoveAgent

ROBOTS = ("franka",)

__all__ = ["FRANKA_REST_QPOS", "ROBOTS", "FrankaInstructMove", "InstructMoveAgent"]
