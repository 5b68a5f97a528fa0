"""lerobot-eval's ``--env.type=instructmove``: importing this package registers InstructMove's
env config with LeRobot (``instructmove_ms.integrations.lerobot_env``).

lerobot >= 0.6 imports installed ``lerobot_env_*`` distributions at start; lerobot 0.4.4 needs
``--env.discover_packages_path=lerobot_env_instructmove``.
"""

from instructmove_ms.integrations import lerobot_env

if not hasattr(lerobot_env, "InstructMoveEnv"):
    raise ImportError(f"lerobot_env_instructmove: {lerobot_env.WHY_NO_CONFIG}")

InstructMoveEnv = lerobot_env.InstructMoveEnv
StoredEpisodesEnv = lerobot_env.StoredEpisodesEnv

__all__ = ["InstructMoveEnv", "StoredEpisodesEnv"]
