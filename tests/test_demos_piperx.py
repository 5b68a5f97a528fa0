"""Planned picks on the PiperX rig (nearest arm first, the other as fallback) and the physics
check of planned picks on both robots: only the target is pushed, and it rises."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from conftest import make_env
from contacts import FORCE_LIMIT, collisions
from instructmove_ms.assets.affordances import enveloping_grasps, section_grasps
from instructmove_ms.demos import pick
from instructmove_ms.heldout import load_set
from instructmove_ms.planning import PlanningScene

TASK = "PickCategory-InstructMove"


@pytest.fixture(scope="module")
def envs():
    """One pd_joint_pos env per robot, made when first asked for."""
    made: dict[str, object] = {}

    def get(robot: str):
        if robot not in made:
            made[robot] = make_env(robot_uids=robot, control_mode="pd_joint_pos")
        return made[robot]

    yield get
    for env in made.values():
        env.close()


def _target_xyz(env) -> np.ndarray:
    u = env.unwrapped
    return u.objects[u.episode.target].pose.p[0].cpu().numpy()


def _checked_rollout(env, actions: np.ndarray) -> tuple[dict, float, dict]:
    """Step through ``actions``; returns the last info, the target's rise and, per robot
    link and body, the strongest contact force above the limit with anything but the
    target (at any step)."""
    z0 = _target_xyz(env)[2]
    worst: dict[tuple[str, str], float] = {}
    info = {}
    for action in actions:
        _, _, _, _, info = env.step(torch.from_numpy(action)[None])
        for pair, force in collisions(env).items():
            worst[pair] = max(force, worst.get(pair, 0.0))
    return info, float(_target_xyz(env)[2] - z0), worst


def _plan(env, **kwargs):
    return pick.plan_pick(PlanningScene.from_env(env), **kwargs)


def _moved_arm(env, actions: np.ndarray) -> int:
    """The PiperX arm whose joint targets change along ``actions``."""
    scene = PlanningScene.from_env(env)
    motion = [np.abs(np.diff(actions[:, scene.rig(k).arm_slots], axis=0)).sum() for k in (0, 1)]
    return int(np.argmax(motion))


@pytest.mark.parametrize(
    ("robot", "seed"), [("franka", 0), ("piperx", 0), ("piperx", 3), ("piperx", 6)]
)
def test_planned_pick_lifts_target_and_touches_nothing_else(envs, robot, seed):
    """PiperX seed 0: a box cutter 1.6 cm tall a finger's width from a peeler (the grasp is
    checked with the fingers at its own opening, not the rig's wider one)."""
    env = envs(robot)
    env.reset(seed=seed)
    actions = _plan(env)
    assert not isinstance(actions, str), actions
    assert actions.shape[1] == env.action_space.shape[-1]
    info, rise, worst = _checked_rollout(env, actions)
    assert not worst, f"robot pressed on more than {FORCE_LIMIT} N: {worst}"
    assert rise > 0.05, f"the target rose {rise:.3f} m"
    assert bool(info["success"][0])


def _target(env):
    u = env.unwrapped
    return u.catalog[u.episode.objects[u.episode.target].uuid]


def _lifts_opened_around(env, around) -> None:
    """Plans the pick and plays it: the hand opens wider than the narrowest of the target's
    ``around(instance, max_opening)`` grasps, and the target rises, held, the robot pressing
    on nothing else."""
    actions = _plan(env)
    assert not isinstance(actions, str), actions
    rig = PlanningScene.from_env(env).rig(_moved_arm(env, actions))
    narrowest = min(g.width for g in around(_target(env), rig.gripper.max_width))
    assert actions[0, rig.gripper_slot] > narrowest
    info, rise, worst = _checked_rollout(env, actions)
    env.close()
    assert bool(info["success"][0]) and rise > 0.05 and not worst, (rise, worst)


def test_a_cup_on_a_saucer_is_held_around_its_rim():
    """PickAttribute seed 168: a 0.32 kg ceramic cup on its saucer. A finger at one wall piece
    lets it turn out; the hand opens wider than the cup and closes around it."""
    env = make_env(
        robot_uids="piperx", control_mode="pd_joint_pos", env_id="PickAttribute-InstructMove"
    )
    env.reset(seed=168)
    assert _target(env).category == "coffee_cup"
    _lifts_opened_around(env, enveloping_grasps)


def test_the_piperx_lifts_string_cheese_around_the_pack():
    """Stored v8 episode (PickCategory, ``unseen_category``): three cheese sticks lying 7 mm
    apart. A 26.5 mm PiperX finger beside the front stick lands on the next one; the hand
    closes around the whole pack instead, and it rises."""
    spec = next(
        s for s in load_set(TASK, "piperx", "unseen_category", version=8) if s.seed == 1002000007
    )
    env = make_env(robot_uids="piperx", control_mode="pd_joint_pos", sampler=2)
    env.reset(options={"episode": spec})
    assert _target(env).category == "cheese_sticks"
    _lifts_opened_around(env, section_grasps)


def test_the_franka_lifts_a_metal_pencil_holder_by_its_rim():
    """Symmetric sampler, PickAttribute seed 10: a 0.46 kg metal pencil holder 8 cm across,
    wider than the Franka opens. Pinched along the rim it turned out of the fingers in every
    rollout; closing across the wall, a finger inside, it rises."""
    env = make_env(env_id="PickAttribute-InstructMove", control_mode="pd_joint_pos", sampler=2)
    env.reset(seed=10)
    holder = _target(env)
    assert holder.category == "pen_holder" and holder.mass > 0.4
    actions = _plan(env)
    assert not isinstance(actions, str), actions
    info, rise, worst = _checked_rollout(env, actions)
    env.close()
    assert bool(info["success"][0]) and rise > 0.05 and not worst, (rise, worst)


def test_piperx_picks_with_the_nearer_arm(envs):
    env = envs("piperx")
    for seed, arm in ((3, 1), (6, 0)):  # targets on the right and on the left
        env.reset(seed=seed)
        scene = PlanningScene.from_env(env)
        assert scene.arm_order(scene.pose(scene.target).p)[0] == arm
        actions = _plan(env)
        assert _moved_arm(env, actions) == arm
        hold = scene.rig(1 - arm)
        assert np.allclose(actions[:, hold.arm_slots], hold.start, atol=1e-6)


def test_piperx_falls_back_to_the_other_arm(envs, monkeypatch):
    env = envs("piperx")
    env.reset(seed=3)  # the right arm is nearer
    arm_plans = pick._arm_plans

    def left_only(e, rig, *args):
        return iter(()) if rig.arm == 1 else arm_plans(e, rig, *args)

    monkeypatch.setattr(pick, "_arm_plans", left_only)
    actions = _plan(env)
    assert not isinstance(actions, str), actions
    assert _moved_arm(env, actions) == 0
    info, rise, worst = _checked_rollout(env, actions)
    assert bool(info["success"][0]) and rise > 0.05 and not worst


def test_failure_reason_covers_both_arms(envs, monkeypatch):
    env = envs("piperx")
    env.reset(seed=3)
    monkeypatch.setattr(pick, "_arm_plans", lambda *args: iter(()))
    assert _plan(env) == "no_plan"  # grasp candidates, but no path to any
    monkeypatch.setattr(pick, "candidates", lambda *args: iter(()))
    assert _plan(env) == "no_ik"


def test_skip_passes_over_grasp_plans(envs):
    """The next grasp plan after one that slipped: another motion, and none left past the
    last plan of both arms."""
    env = envs("franka")
    env.reset(seed=0)
    first, second = _plan(env), _plan(env, skip=1)
    assert not isinstance(second, str), second
    assert first.shape != second.shape or not np.allclose(first, second)
    assert _plan(env, skip=10**6) == "no_plan"


def test_contact_check_sees_the_hand_pressed_on_the_table(envs):
    env = envs("franka")
    env.reset(seed=0)
    rig = PlanningScene.from_env(env).rig()
    down = rig.start.copy()
    down[1], down[3] = 1.5, -0.5  # leans forward: the hand ends below the table top
    seen: dict[tuple[str, str], float] = {}
    for action in rig.actions(np.repeat(down[None], 30, axis=0), rig.gripper.open):
        env.step(torch.from_numpy(action)[None])
        seen.update(collisions(env))
    assert any(body == "table" for _, body in seen), seen
