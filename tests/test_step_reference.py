"""Planned demos checked against a recording made on another machine
(tests/data/step_reference.json: per case the seed, the planned ``pd_joint_pos`` actions, the
lengths of the motions the plan was made of, the first step a robot link touched an object,
and every step's info of the actions replayed). Two things are checked apart:

- **the plan**: the demo planned here from the same reset state. Its first motion is planned
  from the reset state alone, so on any machine it equals the recorded one within
  ``PLAN_ATOL``; later motions (a place, a relay) are planned from the state the physics left
  and follow that state, so only the demo's outcome (the generator keeps the same seed) is
  compared;
- **the physics**: the *recorded* actions replayed here. Until a robot link first touches an
  object, every step's flags are equal and distances and rewards within what a positional
  error of ``POSITION_ERROR`` in every body makes of them. From that step on, contact physics
  decides: PhysX's contact generation uses the CPU's approximate reciprocals (``rcpps``,
  ``rsqrtps``), whose last bits the x86 manuals leave to each vendor, and a grasp or a release
  carries such a difference up to centimetres and moves a latched flag by a few steps.
  Measured on an AMD EPYC (AVX-512) against the recording of an earlier CPU: the
  PlaceA2B/PiperX case lands its object up to 1.55 cm apart and latches place and success 13
  steps apart; nudging every object by one float32 ULP on one machine does the same. So on
  another CPU only the episode's score (the last step's latched flags, object indices, stage
  score and success at the end) must be equal; on the recording CPU every step is compared as
  before contact.

``tests/tools/record_step_reference.py CASE`` records a case again (only when a change of the
scene, the planner or the physics moves it, never to make a scoring change pass)."""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium as gym
import h5py
import numpy as np
import pytest
import torch

from contacts import robot_contacts
from instructmove_ms.demos.generate import generate
from instructmove_ms.floats import cpu_model
from instructmove_ms.tasks import TASKS

pytestmark = pytest.mark.portability  # recorded on one machine, checked on every other

RECORDING = json.loads((Path(__file__).parent / "data" / "step_reference.json").read_text())
REFERENCE: dict[str, dict] = RECORDING["cases"]
#: The sampler whose training seeds the cases were recorded on (InstructMove 1.0's).
RECORDED_SAMPLER = 1
#: Whether this machine's CPU is the one the reference was recorded on (then contact physics
#: lands the same bits, whatever BLAS or torch kernels run).
SAME_CPU = RECORDING["recorded_on"]["cpu"] == cpu_model()
#: How far any body's position may land from where the recording machine put it before
#: contact (m): 10 um is 2,000 times less than the reach threshold and about 100 times the
#: differences seen between machines there.
POSITION_ERROR = 5e-6
#: float32 resolution of a reward of about 10 (the env scores in float32).
FLOAT32_REWARD = 2e-6
#: How far a joint target of the first motion may land from the recorded one (rad): 40 times
#: the float32 spacing of an angle near pi, 0.01 mm at the end of a 1 m arm.
PLAN_ATOL = 1e-5
#: The info keys that make an episode's score (``metrics.score_episode`` reads them from the
#: last step: the flags are latched).
SCORE_KEYS = ("reached_object", "lifted_object", "any_reach", "any_lift", "stage_score")


def reward_slope(task: str) -> float:
    """The largest change of the dense reward per metre of any distance or rise: the
    approach term 1 - tanh(10 d) (10), the raise term 2 * rise / lift (2 / lift) and, for
    PlaceA2B, the carry term 2 * (1 - tanh(5 d)) (10); see ``compute_dense_reward``."""
    env_task = TASKS[task]
    carry = 10.0 if env_task.family == "PlaceA2B" else 0.0
    return 10.0 + 2.0 / env_task.thresholds.lift + carry


def tolerances(task: str) -> dict[str, float]:
    distance = 2 * POSITION_ERROR
    return {
        "target_distance": distance,
        "reward": reward_slope(task) * distance + FLOAT32_REWARD,
    }


def planned(case: str, folder: Path) -> tuple[int, np.ndarray]:
    """The seed and (steps, action dim) actions of the first demo of ``case`` ("<env
    id>/<robot>") the demo generator keeps, recorded in ``folder``."""
    task, robot = case.split("/")
    path = generate(task, robot, 1, folder, shard_size=1, sampler=RECORDED_SAMPLER).path
    (episode,) = json.loads(path.with_suffix(".json").read_text())["episodes"]
    with h5py.File(path) as f:
        actions = f[f"traj_{episode['episode_id']}/actions"][()]
    return episode["reset_kwargs"]["seed"], actions


def case_env(case: str, **kwargs) -> gym.Env:
    """A state env of ``case`` ("<env id>/<robot>") taking ``pd_joint_pos`` actions, whose
    seeds compose the recorded scenes (InstructMove 1.0's sampler)."""
    task, robot = case.split("/")
    return gym.make(
        task,
        robot_uids=robot,
        sampler=RECORDED_SAMPLER,
        obs_mode="state",
        control_mode="pd_joint_pos",
        render_backend="none",
        **kwargs,
    )


def replayed(case: str, seed: int, actions: np.ndarray, keys) -> dict:
    """``actions`` replayed in a fresh env of ``case`` reset to ``seed``: every step's
    ``keys`` of info (and ``reward``) and the first step after which a robot link touches one
    of the episode's objects (None: never)."""
    env = case_env(case, reward_mode="dense")
    env.reset(seed=seed)
    objects = {obj.name for obj in env.unwrapped.objects}
    seen: dict[str, list] = {key: [] for key in keys}
    contact = None
    for step, action in enumerate(actions):
        _, reward, _, _, info = env.step(torch.from_numpy(np.asarray(action, np.float32))[None])
        info = {**info, "reward": reward}
        for key in seen:
            seen[key].append(info[key][0].item())
        if contact is None and any(body in objects for _, body in robot_contacts(env)):
            contact = step
    env.close()
    return {"steps": seen, "first_contact": contact}


def assert_steps_match(task: str, got: dict, expected: dict, steps: slice) -> None:
    """Every key of ``expected`` over ``steps``: flags and indices equal, distances and
    rewards within ``tolerances``."""
    atol = tolerances(task)
    for key, values in expected.items():
        mine, theirs = got[key][steps], values[steps]
        if key in atol:
            np.testing.assert_allclose(mine, theirs, rtol=0, atol=atol[key], err_msg=key)
        else:
            assert mine == theirs, key


@pytest.mark.parametrize("case", sorted(REFERENCE))
def test_the_recorded_actions_replay_as_recorded(case):
    """The physics: the recorded actions, replayed here, give the recorded steps until the
    first contact and the recorded score at the end; on the recording CPU every step."""
    expected = REFERENCE[case]
    got = replayed(case, expected["seed"], np.asarray(expected["actions"]), expected["steps"])
    task = case.split("/")[0]
    assert got["first_contact"] == expected["first_contact"], "the same first touch"
    assert len(got["steps"]["reward"]) == len(expected["steps"]["reward"])
    contact = len(expected["actions"]) if SAME_CPU else expected["first_contact"]
    assert_steps_match(task, got["steps"], expected["steps"], slice(0, contact + 1))
    stages = TASKS[task].stages.names
    for key in (*stages, *SCORE_KEYS, "success", "success_now"):
        assert got["steps"][key][-1] == expected["steps"][key][-1], f"the score: {key}"
    assert expected["steps"]["success"][-1], "the demo succeeds: grasps were checked"


@pytest.mark.parametrize("case", sorted(REFERENCE))
def test_the_plan_from_the_reset_state_is_the_recorded_one(case, tmp_path):
    """The plan: the demo planned here is of the recorded scene (the generator keeps the same
    seed: the demo succeeds) and begins with the recorded first motion (planned from the
    reset state alone); on the recording CPU it is the recorded demo."""
    expected = REFERENCE[case]
    seed, actions = planned(case, tmp_path)
    assert seed == expected["seed"], "the same scene is kept"
    recorded = np.asarray(expected["actions"], dtype=np.float32)
    first = expected["motions"][0]
    np.testing.assert_allclose(actions[:first], recorded[:first], rtol=0, atol=PLAN_ATOL)
    if SAME_CPU:  # the same physics under every later motion: the same plan
        assert actions.shape == recorded.shape
        np.testing.assert_allclose(actions, recorded, rtol=0, atol=PLAN_ATOL)
