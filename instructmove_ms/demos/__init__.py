"""Demo synthesis: planned rollouts recorded in ManiSkill's trajectory format."""

from .pick import plan_pick
from .script import MotionScript
from .synthesis import rollout, synthesize

__all__ = ["MotionScript", "plan_pick", "rollout", "synthesize"]
