"""Record tests/data/sampled_reference.json: the episodes a few training seeds compose, for
every family, robot and sampler (seeds 0-2 under the normal condition, seed 0 under every
other condition), which ``tests/test_portability.py`` expects every machine to compose again.

    python tests/tools/record_sampled_reference.py
"""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium as gym

import instructmove_ms  # noqa: F401
from instructmove_ms.episode import CONDITIONS
from instructmove_ms.files import write_text
from instructmove_ms.sampler import SAMPLERS
from instructmove_ms.tasks import TASKS

OUT = Path(__file__).resolve().parents[1] / "data" / "sampled_reference.json"
SEEDS = (0, 1, 2)


def sampled(env_id: str, robot: str, sampler: int) -> list[dict]:
    env = gym.make(
        env_id, robot_uids=robot, sampler=sampler, obs_mode="state", render_backend="none"
    )
    unwrapped = env.unwrapped
    draws = [(seed, "normal") for seed in SEEDS] + [(0, c) for c in CONDITIONS if c != "normal"]
    specs = [unwrapped.sample_episode(seed, condition).to_dict() for seed, condition in draws]
    env.close()
    return specs


def main() -> None:
    reference = {
        f"{env_id}/{robot}/{sampler}": sampled(env_id, robot, sampler)
        for env_id in sorted(TASKS)
        for robot in ("franka", "piperx")
        for sampler in SAMPLERS
    }
    print(write_text(OUT, json.dumps(reference, indent=1, sort_keys=True) + "\n"))


if __name__ == "__main__":
    main()
