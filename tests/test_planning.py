"""Motion planning: FK/IK, the fcl collision world, OMPL plans and a planned pick in physics."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import fcl
import numpy as np
import pytest
import sapien
import torch

from conftest import hand_spec, make_env
from instructmove_ms.assets.affordances import grasp_affordances
from instructmove_ms.episode import EpisodeSpec, actor_name
from instructmove_ms.planning import (
    PlanningScene,
    cartesian_path,
    densify,
    plan_joint_path,
    time_parametrize,
)

OPEN, CLOSED = 1.0, -1.0
REST = (0.0, -0.569, 0.0, -1.97, 0.0, 1.5, 0.741, 0.04, 0.04)
LAYOUT = [  # category, x, y (robot frame)
    ("canned_coke", 0.45, -0.05),
    ("tomato", 0.30, 0.20),
    ("lemon", 0.30, -0.25),
    ("egg", 0.55, 0.22),
]


def _spec() -> EpisodeSpec:
    return hand_spec([(cat, (x, y)) for cat, x, y in LAYOUT], "franka", REST)


@pytest.fixture(scope="module")
def env():
    env = make_env(control_mode="pd_joint_pos", robot_init_qpos_noise=0.0)
    env.reset(options={"episode": _spec(), "verify": False})
    yield env
    env.close()


def to_actions(targets: np.ndarray, gripper: float) -> np.ndarray:
    """Franka ``pd_joint_pos`` actions: each row of joint targets, then the gripper value."""
    return np.hstack([targets, np.full((len(targets), 1), gripper)]).astype(np.float32)


def _settle(env, q: np.ndarray, gripper: float, steps: int) -> dict:
    info = {}
    for _ in range(steps):
        _, _, _, _, info = env.step(torch.from_numpy(to_actions(q[None], gripper)))
    return info


def test_fk_ik_round_trip(env):
    kin = PlanningScene.from_env(env).kinematics()
    rng = np.random.default_rng(1)
    rest = np.asarray(REST[:7])
    solved = 0
    for _ in range(20):
        goal = kin.fk(rng.uniform(kin.lower, kin.upper))
        q = kin.ik(goal, seeds=[rest], rng=rng)
        if q is None:
            continue
        solved += 1
        assert kin.within_limits(q)
        pose = kin.fk(q)
        assert np.allclose(pose.p, goal.p, atol=1e-3)
        assert abs(abs(float(np.dot(pose.q, goal.q))) - 1.0) < 1e-4
    assert solved >= 18
    far = sapien.Pose([2.0, 0.0, 0.5])
    assert kin.ik(far, seeds=[rest], num_random=2) is None


def test_table_collision(env):
    scene = PlanningScene.from_env(env)
    kin = scene.kinematics()
    world = scene.world(kin)
    rest = np.asarray(REST[:7])
    assert not world.in_collision(rest)
    down = rest.copy()
    down[1], down[3] = 1.5, -0.5  # leans forward: the hand ends below the table top
    assert kin.fk(down).p[2] < 0.0
    assert ("panda_hand", "table") in world.contacts(down)


def test_planned_path_avoids_obstacle(env):
    scene = PlanningScene.from_env(env)
    kin = scene.kinematics()
    world = scene.world(kin)
    start = kin.ik(sapien.Pose([0.45, 0.3, 0.25], [0, 1, 0, 0]), seeds=[np.asarray(REST[:7])])
    goal = kin.ik(sapien.Pose([0.45, -0.3, 0.25], [0, 1, 0, 0]), seeds=[np.asarray(REST[:7])])
    assert start is not None and goal is not None
    wall = [(fcl.Box(0.3, 0.04, 0.5), sapien.Pose())]
    world.add_obstacle("wall", wall, sapien.Pose([0.45, 0.0, 0.25]))
    line = densify(np.stack([start, goal]), 0.02)
    assert any(world.in_collision(q) for q in line), "the wall blocks the straight line"
    path = plan_joint_path(world, start, goal)
    assert path is not None
    assert np.allclose(path[0], start) and np.allclose(path[-1], goal)
    assert not any(world.in_collision(q) for q in densify(path, 0.005))
    limits = scene.robot.limits
    targets = time_parametrize(path, limits)
    assert np.allclose(targets[-1], goal)
    velocity = np.diff(np.vstack([start, targets]), axis=0) * 30
    assert np.all(np.abs(velocity) <= limits.velocity * 1.05)


def _grasp_pose(env, k: int, sign: float) -> sapien.Pose:
    """A top-down TCP pose at the first grasp affordance of object ``k``."""
    u = env.unwrapped
    inst = u.catalog[u.episode.objects[k].uuid]
    grasp = grasp_affordances(inst)[0]
    obj = u.objects[k].pose.sp
    rot = obj.to_transformation_matrix()[:3, :3]
    z = rot @ np.asarray(grasp.approach)
    y = sign * (rot @ np.asarray(grasp.closing))
    matrix = np.eye(4)
    matrix[:3, :3] = np.stack([np.cross(y, z), y, z], axis=1)
    matrix[:3, 3] = (obj * sapien.Pose(grasp.center)).p
    return sapien.Pose(matrix)


def test_planned_pick_lifts_target(env):
    u = env.unwrapped
    env.reset(options={"episode": _spec(), "verify": False})
    rest = np.asarray(REST[:7])
    _settle(env, rest, OPEN, 10)
    scene = PlanningScene.from_env(env)
    kin = scene.kinematics()
    world = scene.world(kin)
    z0 = float(u.objects[0].pose.p[0, 2])
    best = None
    for sign in (1.0, -1.0):
        grasp = _grasp_pose(env, 0, sign)
        pre = sapien.Pose(grasp.p + [0, 0, 0.1], grasp.q)
        q_pre = kin.ik(pre, seeds=[rest], accept=lambda q: not world.in_collision(q))
        if q_pre is not None and (best is None or np.abs(q_pre - rest).sum() < best[0]):
            best = (float(np.abs(q_pre - rest).sum()), grasp, pre, q_pre)
    assert best is not None
    _, grasp, pre, q_pre = best
    limits = scene.robot.limits
    to_pre = plan_joint_path(world, rest, q_pre)
    assert to_pre is not None
    for link in world.gripper_links:
        world.allow(link, actor_name(0))
    descend = cartesian_path(kin, q_pre, grasp, world)
    assert descend is not None
    world.attach(actor_name(0), descend[-1])
    world.allow("attached", "table")  # it stands on the table when the lift begins
    lift = cartesian_path(kin, descend[-1], sapien.Pose(grasp.p + [0, 0, 0.15], grasp.q), world)
    assert lift is not None
    actions = np.vstack(
        [
            to_actions(time_parametrize(to_pre, limits), OPEN),
            to_actions(time_parametrize(descend, limits), OPEN),
            to_actions(np.repeat(descend[-1:], 20, axis=0), OPEN),
            to_actions(np.repeat(descend[-1:], 20, axis=0), CLOSED),
            to_actions(time_parametrize(lift, limits), CLOSED),
            to_actions(np.repeat(lift[-1:], 15, axis=0), CLOSED),
        ]
    )
    table = u.scene.actors["table"]
    links = [link for link in u.agent.robot.get_links() if link.name != "panda_link0"]
    worst = 0.0
    info = {}
    for action in actions:
        _, _, _, _, info = env.step(torch.from_numpy(action)[None])
        for link in links:
            force = u.scene.get_pairwise_contact_forces(link, table)
            worst = max(worst, float(torch.linalg.norm(force, dim=-1).max()))
    rise = float(u.objects[0].pose.p[0, 2]) - z0
    assert worst < 1.0, f"robot pressed on the table with {worst:.1f} N"
    assert rise > 0.05, f"the can rose {rise:.3f} m"
    assert bool(info["lift"])


def test_cartesian_path_partial(env):
    kin = PlanningScene.from_env(env).kinematics()
    start = np.asarray(REST[:7])
    far = sapien.Pose(kin.fk(start).p + [0.0, 0.0, 1.5], kin.fk(start).q)
    assert cartesian_path(kin, start, far) is None
    rows = cartesian_path(kin, start, far, partial=True)
    assert len(rows) > 1 and kin.fk(rows[-1]).p[2] > kin.fk(start).p[2] + 0.1


def test_franka_rig_matches_to_actions(env):
    rig = PlanningScene.from_env(env).rig()
    targets = np.tile(rig.start, (4, 1))
    assert np.array_equal(rig.actions(targets, CLOSED), to_actions(targets, CLOSED))
    assert rig.gripper.open == OPEN and rig.gripper.value(0.04) == pytest.approx(0.2)


@pytest.fixture(scope="module")
def piperx():
    env = make_env(robot_uids="piperx", control_mode="pd_joint_pos")
    env.reset(seed=0)
    yield env
    env.close()


def test_piperx_arms_plan_separately(piperx):
    for arm in (0, 1):
        scene = PlanningScene.from_env(piperx)
        kin = scene.kinematics(arm)
        world = scene.world(kin)
        rest = kin.qpos[kin.arm]
        assert kin.dof == 6 and not world.in_collision(rest)
        goal = kin.ik(sapien.Pose(kin.fk(rest).p + [0.1, 0.0, -0.1], kin.fk(rest).q), [rest])
        assert goal is not None
        path = plan_joint_path(world, rest, goal)
        assert path is not None and not any(world.in_collision(q) for q in path)


def test_piperx_world_holds_the_other_arm_as_obstacle(piperx):
    scene = PlanningScene.from_env(piperx)
    kin = scene.kinematics(1)
    world = scene.world(kin)
    assert {f"left_link{k}" for k in range(1, 7)} | {"left_base_link"} <= set(world.obstacles)
    assert "right_base_link" in world.obstacles and "right_link1" in world.links
    assert world.gripper_links >= {"right_finger1", "right_finger2", "right_gripper_base"}
    rng = np.random.default_rng(0)
    pairs = set().union(*(world.contacts(rng.uniform(kin.lower, kin.upper)) for _ in range(300)))
    assert any(a.startswith("left_") for a, _ in pairs), "the right arm never meets the left"


def test_piperx_rig_actions_hold_the_other_arm(piperx):
    scene = PlanningScene.from_env(piperx)
    left, right = scene.rig(0), scene.rig(1)
    targets = np.tile(right.start + 0.1, (3, 1))
    actions = right.actions(targets, right.gripper.closed)
    assert actions.shape == (3, 14) and actions.dtype == np.float32
    assert np.allclose(actions[:, 6:12], targets) and np.allclose(actions[:, 13], 0.0)
    assert np.allclose(actions[:, :6], left.start) and np.allclose(actions[:, 12], 0.1)
    narrow = right.opened(0.04)
    assert np.allclose(narrow.kin.qpos[[14, 15]], [0.02, -0.02])
    assert np.allclose(right.kin.qpos[[14, 15]], [0.05, -0.05])  # the rig itself is unchanged


_WALL_PLAN = """
import sys, time
import fcl, numpy as np, sapien
from conftest import make_env
from instructmove_ms.planning import PlanningScene, plan_joint_path
env = make_env()
env.reset(seed=0)
scene = PlanningScene.from_env(env)
kin = scene.kinematics()
world = scene.world(kin)
rest = kin.qpos[kin.arm]
start = kin.ik(sapien.Pose([0.45, 0.3, 0.25], [0, 1, 0, 0]), seeds=[rest])
goal = kin.ik(sapien.Pose([0.45, -0.3, 0.25], [0, 1, 0, 0]), seeds=[rest])
world.add_obstacle("wall", [(fcl.Box(0.3, 0.04, 0.5), sapien.Pose())], sapien.Pose([0.45, 0, 0.25]))
if sys.argv[1] == "slow":  # a loaded machine: every collision check takes longer
    check = world.in_collision
    world.in_collision = lambda q: time.sleep(0.0005) or check(q)
path = plan_joint_path(world, start, goal)
assert np.array_equal(plan_joint_path(world, start, goal), path), "a replan differs"
np.save(sys.argv[2], path)
"""


def test_planning_does_not_depend_on_the_machine_speed(tmp_path):
    """OMPL stops on a budget of collision checks, not a clock: slowed checks plan the
    same path in a fresh process; planning the same problem again gives it again."""
    paths = []
    for speed in ("fast", "slow"):
        out = tmp_path / f"{speed}.npy"
        subprocess.run(
            [sys.executable, "-c", _WALL_PLAN, speed, str(out)],
            cwd=Path(__file__).parent,
            check=True,
            timeout=300,
        )
        paths.append(np.load(out))
    assert len(paths[0]) > 2, "the wall forces a planned path"
    assert np.array_equal(paths[0], paths[1])
