"""Demo synthesis: planned pick rollouts recorded in ManiSkill's trajectory format."""

from .pick import PICK_TASKS, plan_pick, rollout

__all__ = ["PICK_TASKS", "plan_pick", "rollout"]
