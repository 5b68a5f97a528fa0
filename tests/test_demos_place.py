"""Planned PlaceA2B demos on the Franka: the target ends at rest in the goal receptacle,
released, within the horizon; a recorded demo replays to RGB under delta joint control."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import h5py
import numpy as np
import pytest
import sapien
import torch
from mani_skill.utils.wrappers import RecordEpisode

from conftest import make_env
from instructmove_ms.agents.contacts import ContactForces
from instructmove_ms.demos.place import goal_interior
from instructmove_ms.demos.synthesis import synthesize
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.planning import PlanningScene
from instructmove_ms.tasks import PLACE_STAGES

TASK, ROBOT = "PlaceA2B-InstructMove", "franka"
STEM = f"{TASK}_{ROBOT}"
SEEDS = (1, 3)
#: PiperX PlaceA2B scenes kept for the cases they show, by their index in the pre-release
#: sets' ``seen`` set, on the ``recognisable`` snapshot (the same categories, instance
#: indices and poses; tests/data/place_a2b_piperx_scenes.jsonl).
SCENES = dict(
    zip(
        (2, 7, 22, 84, 98),
        (
            EpisodeSpec.from_json(line)
            for line in (Path(__file__).parent / "data" / "place_a2b_piperx_scenes.jsonl")
            .read_text()
            .splitlines()
        ),
        strict=True,
    )
)


def _outcome(env, flags, reason) -> dict:
    """What the test checks of a finished episode, read off the scene itself."""
    u = env.unwrapped
    target = u.objects[u.episode.target]
    pose = u.agent.robot.pose.sp.inv() * target.pose.sp
    interior = goal_interior(PlanningScene.from_env(env))
    local = np.linalg.inv(interior.frame) @ np.append(pose.p, 1.0)
    held = u.catalog_of(u.episode)[u.episode.objects[u.episode.target].uuid]
    lo, hi = (np.asarray(b) for b in held.bounds)
    centre = np.linalg.inv(interior.frame) @ np.append((pose * sapien.Pose((lo + hi) / 2)).p, 1)
    fingers = [link for link in u.agent.robot.links if "finger" in link.name]
    touch = max(
        float(torch.linalg.norm(u.scene.get_pairwise_contact_forces(link, target)[0]))
        for link in fingers
    )
    return {
        "flags": flags,
        "reason": reason,
        "local": local[:3],  # the origin: the bottom of the upright box
        "centre": centre[:3],  # the box's centre (an egg lying turned)
        "half": interior.half,
        "speed": float(np.linalg.norm(target.linear_velocity[0].numpy())),
        "grasped": bool(u.agent.is_grasping(target)[0]),
        "finger_force": touch,
    }


def _watch_holders(env) -> list[list[bool]]:
    """A list that ``env``'s every step from now on appends to: whether each arm of the
    PiperX holds the target."""
    u = env.unwrapped
    target = u.objects[u.episode.target]
    holders, step = [], env.step

    def watch(action):
        out = step(action)
        holders.append(
            [bool(u.agent.grasping(target, ContactForces(u.scene), [k])[0]) for k in (0, 1)]
        )
        return out

    env.step = watch
    return holders


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """Synthesized demos of ``SEEDS``, recorded; returns the folder and each one's outcome."""
    out = tmp_path_factory.mktemp("place")
    env = gym.make(
        TASK, robot_uids=ROBOT, obs_mode="state", control_mode="pd_joint_pos", render_backend="cpu"
    )
    env = RecordEpisode(env, str(out), trajectory_name=STEM, save_video=False, save_on_reset=False)
    outcomes = []
    for seed in SEEDS:
        env.reset(seed=seed)
        flags, reason = synthesize(env)
        outcomes.append(_outcome(env, flags, reason))
        env.flush_trajectory(save=reason is None)
    env.close()
    return out, outcomes


@pytest.mark.parametrize("k", range(len(SEEDS)))
def test_place_succeeds_within_the_horizon(recorded, k):
    flags, reason = recorded[1][k]["flags"], recorded[1][k]["reason"]
    assert reason is None and flags[-1]["success"]
    assert len(flags) <= 500 and set(flags[0]) == set(PLACE_STAGES.flags)
    first = [next(i for i, f in enumerate(flags) if f[s]) for s in PLACE_STAGES.names]
    assert first == sorted(first)  # reach_pick, lift_pick, reach_place, place in order


@pytest.mark.parametrize("k", range(len(SEEDS)))
def test_target_rests_in_the_goal_receptacle_released(recorded, k):
    outcome = recorded[1][k]
    local = outcome["local"]  # the target's bottom centre relative to the interior's floor
    assert np.all(np.abs(local[:2]) <= outcome["half"])
    assert -0.01 < local[2] < 0.03
    assert outcome["speed"] < 0.05
    assert not outcome["grasped"]
    assert outcome["finger_force"] < 1e-3  # the opened fingers stand clear of it


def test_replay_to_rgb_with_delta_control_reproduces_success(recorded):
    out, _ = recorded
    result = subprocess.run(
        [sys.executable, "-m", "mani_skill.trajectory.replay_trajectory"]
        + ["--traj-path", f"{STEM}.h5", "-o", "rgb", "-c", "pd_joint_delta_pos"]
        + ["--save-traj", "-b", "physx_cpu", "--count", "1"],
        cwd=out,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    converted = out / f"{STEM}.rgb.pd_joint_delta_pos.physx_cpu.h5"
    meta = json.loads(converted.with_suffix(".json").read_text())
    assert [e["reset_kwargs"]["seed"] for e in meta["episodes"]] == [SEEDS[0]]
    with h5py.File(converted) as f:
        assert bool(f["traj_0/success"][-1])
        assert f["traj_0/actions"].shape[1] == 8
        assert f["traj_0/obs/sensor_data/ext1_camera/rgb"].shape[0] > 0


def test_piperx_relays_a_far_goal_to_its_other_arm():
    """Seed 10: the left arm picks the target, cannot reach the goal on the far right, sets
    the target down between the arms and goes back to rest; the right arm places it."""
    env = make_env(TASK, robot_uids="piperx", control_mode="pd_joint_pos")
    env.reset(seed=10)
    grippers = _watch_holders(env)
    flags, reason = synthesize(env)
    outcome = _outcome(env, flags, reason)
    env.close()
    assert reason is None and len(flags) <= 500
    held_by = [arm for left, right in grippers for arm, held in ((0, left), (1, right)) if held]
    first, last = held_by[0], held_by[-1]
    assert first != last, "one arm carried the target all the way"
    assert {first, last} == {0, 1}
    switch = next(i for i, g in enumerate(grippers) if g[last])
    assert not any(g[first] for g in grippers[switch:]), "both arms held the target at once"
    assert np.all(np.abs(outcome["local"][:2]) <= outcome["half"])
    assert -0.01 < outcome["local"][2] < 0.03 and not outcome["grasped"]


def test_piperx_leans_its_hand_into_a_far_receptacle():
    """Scene 7: a figurine goes into a storage box beyond an upright hand's reach of
    either arm; the arm that picks it leans its hand away from its shoulder over the box
    (no relay) and lets go there."""
    spec = SCENES[7]
    env = make_env(TASK, robot_uids="piperx", control_mode="pd_joint_pos")
    env.reset(options={"episode": spec})
    u = env.unwrapped
    target = u.objects[u.episode.target]
    holds = []  # (arm, TCP's tilt off straight down in degrees) while held

    def watch(action):
        _, _, _, _, info = step(action)
        for arm, link in enumerate(u.agent.tcp_links):
            if bool(u.agent.grasping(target, ContactForces(u.scene), [arm])[0]):
                down = link.pose.sp.to_transformation_matrix()[:3, 2]
                holds.append((arm, float(np.degrees(np.arccos(np.clip(-down[2], -1.0, 1.0))))))
        return None, None, None, None, info

    step, env.step = env.step, watch
    flags, reason = synthesize(env)
    outcome = _outcome(env, flags, reason)
    env.close()
    assert reason is None
    assert len({arm for arm, _ in holds}) == 1, "the target was relayed"
    assert holds[-1][1] > 10.0, f"released with the hand {holds[-1][1]:.0f} deg off vertical"
    assert np.all(np.abs(outcome["local"][:2]) <= outcome["half"])
    assert -0.01 < outcome["local"][2] < 0.03 and not outcome["grasped"]


def test_an_object_resting_upside_down_in_the_receptacle_counts_as_placed():
    """The place check measures the object's lowest point, not its origin (the bottom of its
    upright box): the target dropped upside down into the goal receptacle is placed once it
    rests; the same drop next to the receptacle is not."""
    env = make_env(TASK, control_mode="pd_joint_pos")
    env.reset(seed=3)  # a target that rests upside down (a round one rolls over)
    u = env.unwrapped
    target = u.objects[u.episode.target]
    lo, hi = u.catalog_of(u.episode)[u.episode.objects[u.episode.target].uuid].bounds
    assert hi[2] - lo[2] > u.task.thresholds.place_height + 0.01  # the origin ends that high
    scene = PlanningScene.from_env(env)
    interior = goal_interior(scene)
    hold = torch.from_numpy(scene.rig().hold)[None]
    placed = []
    for shift in (0.0, 0.3):  # into the receptacle, then beside it on the table
        floor = interior.frame[:3, 3] + [0.0, shift, 0.0]
        floor[2] = floor[2] if shift == 0.0 else 0.0
        upside_down = sapien.Pose(floor + [0.0, 0.0, hi[2] + 0.02], [0.0, 1.0, 0.0, 0.0])
        target.set_pose(upside_down)
        for _ in range(60):
            env.step(hold)
        assert target.pose.sp.to_transformation_matrix()[2, 2] < -0.9, "it turned over"
        now = u._measured()
        grasped = torch.zeros(now.pos.shape[:2], dtype=torch.bool)  # nothing holds it
        placed.append(bool(u._goal_conditions(now, grasped)[1][0]))
    env.close()
    assert placed == [True, False]


@pytest.mark.parametrize("index", [84, 98])
def test_piperx_places_into_a_snug_receptacle_and_leaves_it_standing(index):
    """Scenes 84 (a strawberry dropped into a bucket ends lying tilted on its floor)
    and 98 (a tomato lowered deep into a pot): the fingers open just clear of the object, so
    they do not press on the walls and lift the receptacle on the way up, and the tilted
    strawberry counts as placed (its box dips below the floor, its centre does not)."""
    spec = SCENES[index]
    env = make_env(TASK, robot_uids="piperx", control_mode="pd_joint_pos")
    env.reset(options={"episode": spec})
    goal = env.unwrapped.objects[spec.goal_destination]
    start = goal.pose.sp
    flags, reason = synthesize(env)
    outcome = _outcome(env, flags, reason)
    end = goal.pose.sp
    env.close()
    assert reason is None
    assert abs(end.p[2] - start.p[2]) < 0.01, "the receptacle was lifted"
    assert end.to_transformation_matrix()[2, 2] > 0.99, "the receptacle tipped"
    assert np.all(np.abs(outcome["local"][:2]) <= outcome["half"]) and not outcome["grasped"]


@pytest.mark.parametrize("index", [2, 22])
def test_piperx_relay_episode_fits_the_horizon(index):
    """Scenes 2 and 22 need a relay (the picking arm has no release over the
    goal), and the pick, relay, second pick and place take more than the 500 steps at the
    default pace: the motions after the first pick hurry so that the target ends in the
    receptacle in time. In 22 the egg rolls over once set down: the second arm's grasp
    clears the turned egg's real top."""
    spec = SCENES[index]
    env = make_env(TASK, robot_uids="piperx", control_mode="pd_joint_pos")
    env.reset(options={"episode": spec})
    holders = _watch_holders(env)
    flags, reason = synthesize(env)
    outcome = _outcome(env, flags, reason)
    env.close()
    assert reason is None and len(flags) <= 500
    assert any(left for left, _ in holders) and any(right for _, right in holders), "no relay"
    assert np.all(np.abs(outcome["centre"][:2]) <= outcome["half"]) and not outcome["grasped"]
