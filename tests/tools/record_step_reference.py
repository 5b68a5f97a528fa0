"""Record cases of tests/data/step_reference.json again (only when a change of the scene, the
planner or the physics moves them, never to make a scoring change pass), on this machine,
whose CPU the file then names:

    python tests/tools/record_step_reference.py "PickSpatial-InstructMove/piperx" [...]

A case holds the demo the generator keeps for it (seed, actions), the lengths of the motions
its plan was made of (each planned from the state the last one left), the step of the first
touch and every step's info of the actions replayed.
"""

import json
import sys
import tempfile
from pathlib import Path

import numpy as np
import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from test_step_reference import (  # noqa: E402
    RECORDING,
    REFERENCE,
    case_env,
    planned,
    replayed,
)

import instructmove_ms  # noqa: E402,F401
from instructmove_ms.demos.script import MotionScript  # noqa: E402
from instructmove_ms.demos.synthesis import steps_left  # noqa: E402
from instructmove_ms.files import write_text  # noqa: E402
from instructmove_ms.floats import cpu_model, describe  # noqa: E402
from instructmove_ms.planning import PlanningScene  # noqa: E402

#: The info keys a case records (and ``reward``).
KEYS = {
    "pick": ["reach", "lift", "reached_object", "lifted_object", "any_reach", "any_lift"],
    "place": ["reach_pick", "lift_pick", "reach_place", "place"],
    "end": ["target_distance", "success", "success_now", "stage_score", "reward"],
}


def motions(case: str, seed: int, actions: np.ndarray) -> list[int]:
    """The lengths of the motions the episode's ``MotionScript`` plays in a fresh env (the
    first grasp plan), checked to be ``actions``."""
    env = case_env(case)
    env.reset(seed=seed)
    script, lengths, played = MotionScript(PlanningScene.from_env(env)), [], []
    while steps_left(env) > 0 and (motion := script.next(env)) is not None:
        assert not isinstance(motion, str), motion
        motion = motion[: steps_left(env)]
        lengths.append(len(motion))
        for action in motion:
            env.step(torch.from_numpy(action)[None])
            played.append(action)
    env.close()
    assert np.array_equal(np.asarray(played), actions), "the kept demo is the first grasp plan's"
    return lengths


def record(case: str) -> dict:
    task = case.split("/")[0]
    keys = KEYS["pick"] + (KEYS["place"] if task.startswith("PlaceA2B") else []) + KEYS["end"]
    with tempfile.TemporaryDirectory() as tmp:
        seed, actions = planned(case, Path(tmp))
    got = replayed(case, seed, actions, keys)
    return {
        "seed": seed,
        "motions": motions(case, seed, actions),
        "first_contact": got["first_contact"],
        "actions": actions.astype(np.float32).tolist(),
        "steps": got["steps"],
    }


if __name__ == "__main__":
    path = Path(__file__).resolve().parents[1] / "data" / "step_reference.json"
    cases = dict(REFERENCE)
    if cpu_model() != RECORDING["recorded_on"]["cpu"] and set(sys.argv[1:]) != set(cases):
        sys.exit(f"recorded on {RECORDING['recorded_on']['cpu']}: record every case here")
    for case in sys.argv[1:]:
        cases[case] = record(case)
        c = cases[case]
        print(f"{case}: seed {c['seed']}, motions {c['motions']}, first touch {c['first_contact']}")
    recorded_on = {"cpu": cpu_model(), "set_up": describe()}
    write_text(
        path, json.dumps({"recorded_on": recorded_on, "cases": cases}, separators=(",", ":"))
    )
