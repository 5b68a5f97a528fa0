"""The PiperX agents: kinematics against the vendor table, reach, grasps, control modes, cameras."""

from __future__ import annotations

import math
from collections.abc import Sequence

import gymnasium as gym
import h5py
import numpy as np
import pytest
import sapien
import torch
from mani_skill.trajectory import replay_trajectory as replay
from mani_skill.utils.geometry.rotation_conversions import (
    matrix_to_euler_angles,
    quaternion_to_matrix,
)
from mani_skill.utils.wrappers import RecordEpisode

from conftest import hand_spec, make_env
from instructmove_ms.agents.contacts import ContactForces
from instructmove_ms.agents.piperx import joint_order, rest_qpos
from instructmove_ms.episode import EpisodeSpec

SIDES = ("left", "right")
BASE_Y = {"left": 0.3, "right": -0.3}
#: Vendor SDK modified-DH preset of PiperX: (d, a, alpha, theta_offset) per joint.
MDH = (
    (0.123, 0.0, 0.0, math.pi),
    (0.0, 0.0, math.pi / 2, 0.135787),
    (0.0, 0.28503, 0.0, 2.83808),
    (0.0, 0.27364, 0.0, 0.080634),
    (0.0, 0.07466, -math.pi / 2, math.pi / 2),
    (0.03526, 0.0, math.pi / 2, 0.0),
)
#: Joint limits of the table; joints 4 and 5 take the SDK's +-1.553 rad.
LIMITS = (
    (-2.618, 2.618),
    (0.0, math.pi),
    (-2.967, 0.0),
    (-1.553, 1.553),
    (-1.553, 1.553),
    (-2.0944, 2.0944),
)
ARM_ACTION_ORDER = [f"{s}_joint{j}" for s in SIDES for j in range(1, 7)]
OPEN, CLOSED = 0.1, 0.0


def mdh_flange(q: np.ndarray) -> np.ndarray:
    """link6 frame in the arm base frame from the vendor's modified-DH table."""
    frame = np.eye(4)
    for (d, a, alpha, offset), qi in zip(MDH, q, strict=True):
        ct, st = math.cos(qi + offset), math.sin(qi + offset)
        ca, sa = math.cos(alpha), math.sin(alpha)
        frame = frame @ np.array(
            [
                [ct, -st, 0.0, a],
                [st * ca, ct * ca, -sa, -sa * d],
                [st * sa, ct * sa, ca, ca * d],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
    return frame


def _rz(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _ry(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


#: TCP frame of a top-down grasp facing +x: z down, fingers closing along y.
TOP_DOWN = np.stack([[0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]], axis=1)


class Kinematics:
    """Pinocchio model of the rig with IK for one arm's TCP."""

    def __init__(self, robot) -> None:
        self.model = robot.create_pinocchio_model()
        self.joints = [j.name for j in robot.get_active_joints()]
        self.links = [link.name for link in robot.get_links()]
        self.limits = robot.get_qlimits()[0].cpu().numpy()

    def index(self, name: str) -> int:
        return self.joints.index(name)

    def ik(
        self, side: str, xyz: Sequence[float], q0: np.ndarray, tilt: float = 0.0
    ) -> np.ndarray | None:
        """Joints putting ``side``'s TCP at ``xyz`` (rig frame) pointing down, leaned ``tilt``
        rad away from its base, fingers closing across the radial direction; None if the
        solver fails or leaves the joint limits."""
        radial = math.atan2(xyz[1] - BASE_Y[side], xyz[0])
        pose = np.eye(4)
        pose[:3, :3] = _rz(radial) @ _ry(-tilt) @ TOP_DOWN
        pose[:3, 3] = xyz
        mask = np.array([n.startswith(f"{side}_joint") for n in self.joints])
        for seed in range(3):
            start = np.array(q0, dtype=float)
            if seed > 0:
                start[self.index(f"{side}_joint1")] = radial
            if seed > 1:
                start[self.index(f"{side}_joint4")] = 0.3
            q, ok, _ = self.model.compute_inverse_kinematics(
                self.links.index(f"{side}_tcp"),
                sapien.Pose(pose),
                initial_qpos=start,
                active_qmask=mask,
                max_iterations=200,
            )
            q = np.asarray(q)
            inside = np.all(q >= self.limits[:, 0] - 1e-6) & np.all(q <= self.limits[:, 1] + 1e-6)
            if ok and inside:
                return q
        return None


@pytest.fixture(scope="module")
def env():
    env = make_env(robot_uids="piperx")
    env.reset(seed=0)
    yield env
    env.close()


@pytest.fixture(scope="module")
def kin(env):
    return Kinematics(env.unwrapped.agent.robot)


def test_forward_kinematics_matches_vendor_dh(env):
    """Simulated link6 frames of both arms after set_qpos equal the vendor's modified-DH FK."""
    robot = env.unwrapped.agent.robot
    names = [j.name for j in robot.get_active_joints()]
    rng = np.random.default_rng(0)
    lo, hi = np.array(LIMITS).T
    worst_p, worst_r = 0.0, 0.0
    for _ in range(20):
        qpos = np.asarray(rest_qpos(SIDES), dtype=np.float32)
        arms = {s: rng.uniform(lo, hi) for s in SIDES}
        for side, q in arms.items():
            for j in range(6):
                qpos[names.index(f"{side}_joint{j + 1}")] = q[j]
        robot.set_qpos(torch.from_numpy(qpos)[None])
        for side, q in arms.items():
            base = robot.links_map[f"{side}_base_link"].pose.sp
            flange = robot.links_map[f"{side}_link6"].pose.sp
            sim = (base.inv() * flange).to_transformation_matrix()
            ref = mdh_flange(q)
            worst_p = max(worst_p, float(np.linalg.norm(sim[:3, 3] - ref[:3, 3])))
            cos = (np.trace(sim[:3, :3].T @ ref[:3, :3]) - 1) / 2
            worst_r = max(worst_r, math.acos(min(1.0, cos)))
    assert worst_p < 1e-3, f"flange position error {worst_p * 1e3:.2f} mm"
    assert worst_r < 1e-3, f"flange orientation error {worst_r:.2e} rad"


def test_joint_limits_and_order_match_the_table(env):
    agent = env.unwrapped.agent
    robot = agent.robot
    names = [j.name for j in robot.get_active_joints()]
    assert names == joint_order(SIDES)  # the keyframe's order
    limits = robot.get_qlimits()[0].cpu().numpy()
    for side in SIDES:
        for j, (lo, hi) in enumerate(LIMITS, start=1):
            np.testing.assert_allclose(limits[names.index(f"{side}_joint{j}")], (lo, hi), atol=1e-6)
        np.testing.assert_allclose(limits[names.index(f"{side}_finger_joint1")], (0, 0.05))
        np.testing.assert_allclose(limits[names.index(f"{side}_finger_joint2")], (-0.05, 0))
    assert agent.arm_joint_names == ARM_ACTION_ORDER
    assert env.action_space.shape == (14,)
    np.testing.assert_allclose(env.action_space.high[12:], (0.1, 0.1))  # gripper width, m


def test_rest_pose_has_no_self_contact_and_faces_the_workspace(env):
    env.reset(seed=0)
    agent = env.unwrapped.agent
    rest = agent.keyframes["rest"].qpos
    action = np.r_[[rest[joint_order(SIDES).index(n)] for n in ARM_ACTION_ORDER], OPEN, OPEN]
    for _ in range(10):
        env.step(torch.tensor(action, dtype=torch.float32)[None])
    links = {link.name for link in agent.robot.get_links()}
    pairs = []  # any pair the solver works on, touching or within the contact offset
    for contact in env.unwrapped.scene.get_contacts():
        a, b = (body.entity.name for body in contact.bodies)
        if a in links and b in links:
            pairs.append((a, b))
    assert not pairs, f"robot links in contact at rest (see the SRDF): {pairs}"
    assert bool(agent.is_static()[0])
    tcp = agent.tcp_positions()[0].cpu().numpy()
    assert tcp[0, 1] > 0 > tcp[1, 1]  # left arm on the left
    assert np.all(np.abs(tcp[:, 1]) < 0.3)  # both turned toward the middle
    assert np.all((tcp[:, 0] > 0.15) & (tcp[:, 2] > 0.25))  # above the front of the table


def test_workspace_is_reachable_by_one_arm(kin):
    """Every grid point of the workspace at grasp height can be reached pointing down, leaned
    at most 20 deg away from the arm's base; points within 0.52 m of a base straight down.

    A straight-down grasp needs link4 vertical, so the wrist (0.24 m above the TCP) limits its
    reach to about 0.54 m from the base: the far middle of the table needs a lean.
    """
    rest = np.asarray(rest_qpos(SIDES), dtype=float)
    z = 0.02
    missed, missed_down, down = [], [], 0
    for x in np.arange(0.25, 0.551, 0.05):
        for y in np.arange(-0.35, 0.351, 0.05):
            near = min(math.hypot(x, y - BASE_Y[s]) for s in SIDES)
            straight = any(kin.ik(s, (x, y, z), rest) is not None for s in SIDES)
            down += straight
            if near <= 0.52 and not straight:
                missed_down.append((round(x, 2), round(y, 2)))
            if not straight and all(
                kin.ik(s, (x, y, z), rest, math.radians(20)) is None for s in SIDES
            ):
                missed.append((round(x, 2), round(y, 2)))
    assert not missed_down, f"not reachable straight down: {missed_down}"
    assert not missed, f"not reachable within 20 deg: {missed}"
    assert all(kin.ik(s, (0.55, 0.0, z), rest) is None for s in SIDES)  # the measured limit
    assert down >= 80  # of 105 points


def _spec(category: str, side: str) -> EpisodeSpec:
    """One object in front of ``side``'s arm, its long axis radial (closing across it)."""
    x, y = 0.36, math.copysign(0.13, BASE_Y[side])
    yaw = math.atan2(y - BASE_Y[side], x)
    pose = (x, y, 0.002, math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
    return hand_spec([(category, pose)], "piperx", rest_qpos(SIDES))


def _act(env, kin: Kinematics, q: np.ndarray, grippers: dict) -> dict:
    arm = [q[kin.index(n)] for n in ARM_ACTION_ORDER]
    action = torch.tensor(np.r_[arm, grippers["left"], grippers["right"]], dtype=torch.float32)
    return env.step(action[None])[-1]


def _move(
    env, kin: Kinematics, q_from: np.ndarray, q_to: np.ndarray, grippers: dict, steps: int
) -> dict:
    info = {}
    for k in range(1, steps + 1):
        info = _act(env, kin, q_from + (q_to - q_from) * k / steps, grippers)
    return info


@pytest.mark.parametrize(
    "side, category, grasp_depth",  # depth: TCP below the object's top
    [("left", "canned_coke", 0.05), ("right", "marker", 0.0)],
)
def test_gripper_grasps_and_lifts(env, kin, side, category, grasp_depth):
    env.reset(options={"episode": _spec(category, side), "verify": False})
    u = env.unwrapped
    agent, obj = u.agent, u.objects[0]
    q = agent.robot.get_qpos()[0].cpu().numpy().astype(float)
    grippers = {s: OPEN for s in SIDES}
    for _ in range(5):  # settle
        _act(env, kin, q, grippers)
    p = obj.pose.p[0].cpu().numpy()
    z0 = float(p[2])
    # the fingertips reach 0.0215 m below the TCP: keep them 4 mm above the table
    top = z0 + u.catalog[u.episode.objects[0].uuid].height
    grasp_z = max(top - grasp_depth, 0.0255)
    # straight down from 6 cm above and back up: top-down poses higher up exceed joint4's range
    above = kin.ik(side, (p[0], p[1], grasp_z + 0.06), q)
    assert above is not None
    at = kin.ik(side, (p[0], p[1], grasp_z), above)
    assert at is not None
    _move(env, kin, q, above, grippers, 40)
    info = _move(env, kin, above, at, grippers, 25)
    assert bool(info["reach"])
    assert not bool(agent.is_grasping(obj)[0])
    grippers[side] = CLOSED
    _move(env, kin, at, at, grippers, 15)
    info = _move(env, kin, at, above, grippers, 30)
    info = _move(env, kin, above, above, grippers, 15)  # hold: it must not slip out
    rise = float(obj.pose.p[0, 2]) - z0
    assert rise > 0.04, f"{category} rose {rise:.3f} m"
    arm = SIDES.index(side)
    assert bool(agent.grasping(obj, ContactForces(agent.scene), [arm])[0])
    assert not bool(agent.grasping(obj, ContactForces(agent.scene), [1 - arm])[0])
    assert bool(agent.is_grasping(obj)[0])
    assert bool(info["lift"]) and bool(info["success"])


@pytest.mark.parametrize(
    "mode",
    ["pd_ee_delta_pose", "pd_ee_delta_pos", "pd_ee_target_delta_pos", "pd_ee_target_delta_pose"],
)
def test_end_effector_modes_move_one_arm(mode):
    """ManiSkill's Panda end-effector modes (its env tests ask for pd_ee_delta_pos), one
    controller per arm: a +x command moves the left TCP forward and the right one not."""
    env = make_env(robot_uids="piperx", control_mode=mode)
    env.reset(seed=0)
    agent = env.unwrapped.agent
    assert list(agent.controller.controllers) == [
        "arm_left",
        "arm_right",
        "gripper_left",
        "gripper_right",
    ]
    left, right = agent.action_layout()
    assert env.action_space.shape == (2 * len(left.command) + 2,)
    start = agent.tcp_positions()[0].cpu().numpy()
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    # left TCP +x by 0.03 m per step from where it is, or 0.01 m from the last target
    action[left.command[0]] = 0.1 if "target" in mode else 0.3
    action[[left.gripper, right.gripper]] = OPEN
    for _ in range(15):
        env.step(torch.from_numpy(action)[None])
    moved = agent.tcp_positions()[0].cpu().numpy() - start
    env.close()
    assert moved[0, 0] > 0.05 and np.all(np.abs(moved[0, 1:]) < 0.1 * moved[0, 0])
    assert np.linalg.norm(moved[1]) < 0.001


def test_absolute_end_effector_pose_mode_reaches_its_target():
    env = make_env(robot_uids="piperx", control_mode="pd_ee_pose")
    env.reset(seed=0)
    agent = env.unwrapped.agent
    left, right = agent.action_layout()
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    for arm, slots in enumerate((left, right)):  # every TCP where it is, the left 5 cm ahead
        tcp = agent.tcp_links[arm].pose
        euler = matrix_to_euler_angles(quaternion_to_matrix(tcp.q), "XYZ")[0].numpy()
        action[list(slots.command)] = np.r_[tcp.p[0].numpy() + [0.05 * (arm == 0), 0, 0], euler]
        action[slots.gripper] = OPEN
    goal = action[list(left.command[:3])]
    for _ in range(40):
        env.step(torch.from_numpy(action)[None])
    reached = agent.tcp_positions()[0, 0].cpu().numpy()
    env.close()
    assert np.linalg.norm(reached - goal) < 0.01, (reached, goal)


@pytest.mark.parametrize("mode", ["pd_joint_target_delta_pos", "pd_joint_vel"])
def test_joint_modes_turn_the_commanded_joint(mode):
    env = make_env(robot_uids="piperx", control_mode=mode)
    env.reset(seed=0)
    agent = env.unwrapped.agent
    left, right = agent.action_layout()
    start = agent.robot.get_qpos()[0].cpu().numpy()
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    action[left.command[0]] = 0.5  # left j1
    action[[left.gripper, right.gripper]] = OPEN
    for _ in range(10):
        env.step(torch.from_numpy(action)[None])
    turned = agent.robot.get_qpos()[0].cpu().numpy() - start
    env.close()
    names = [j.name for j in agent.robot.get_active_joints()]
    assert turned[names.index("left_joint1")] > 0.05
    assert abs(turned[names.index("right_joint1")]) < 0.01


def test_single_arm_variant():
    env = gym.make("Empty-v1", robot_uids="piperx_single", obs_mode="state")
    env.reset(seed=0)
    agent = env.unwrapped.agent
    assert env.action_space.shape == (7,)
    assert list(agent.controller.controllers) == ["arm", "gripper"]
    assert len(agent.tcp_links) == 1 and agent.tcp_links[0].name == "tcp"
    robot = agent.robot
    for q in np.random.default_rng(1).uniform(*np.array(LIMITS).T, size=(5, 6)):
        robot.set_qpos(torch.tensor(np.r_[q, 0.05, -0.05], dtype=torch.float32)[None])
        sim = robot.links_map["link6"].pose.sp.to_transformation_matrix()
        assert np.linalg.norm(sim[:3, 3] - mdh_flange(q)[:3, 3]) < 1e-3
    env.close()


def test_state_obs_mode(env):
    obs, _ = env.reset(seed=1)
    assert obs.shape[0] == 1 and torch.isfinite(obs).all()
    obs, *_ = env.step(torch.from_numpy(env.action_space.sample())[None])
    assert torch.isfinite(obs).all()
    assert env.unwrapped.get_language_instruction()[0]


def test_rgb_obs_mode_and_cameras_look_where_the_real_ones_do():
    """rgb at a configured resolution keeps the published focal lengths; the static camera
    sees the table and the whole workspace, each hand camera its own fingers."""
    w, h = 320, 180
    env = make_env(
        robot_uids="piperx",
        obs_mode="rgb",
        render_backend="cpu",
        sensor_configs=dict(width=w, height=h),
    )
    env.reset(seed=0)
    obs, *_ = env.step(torch.from_numpy(env.action_space.sample())[None])
    u = env.unwrapped
    params = u.get_sensor_params()
    for cam, (fx, fy) in {
        "static_camera": (640.0, 565.1),
        "left_hand_camera": (710.8, 649.5),
        "right_hand_camera": (710.8, 649.5),
    }.items():
        rgb = obs["sensor_data"][cam]["rgb"][0].numpy()
        assert rgb.shape == (h, w, 3) and rgb.std() > 5, f"{cam} image is blank"
        k = params[cam]["intrinsic_cv"][0].numpy()
        np.testing.assert_allclose((k[0, 0], k[1, 1]), (fx / 4, fy / 4), rtol=1e-4)
    images = {
        cam: u.scene.sensors[cam].get_obs(rgb=False, depth=True, segmentation=True)
        for cam in ("static_camera", "left_hand_camera", "right_hand_camera")
    }
    # the static camera sees the table 0.5..1.0 m away, and the whole workspace
    depth = images["static_camera"]["depth"][0, ..., 0].numpy() / 1000.0
    assert 0.5 < np.median(depth[h // 3 : 2 * h // 3, w // 3 : 2 * w // 3]) < 1.0
    k = params["static_camera"]["intrinsic_cv"][0].numpy()
    ext = params["static_camera"]["extrinsic_cv"][0].numpy()
    for x in (0.25, 0.55):
        for y in (-0.35, 0.35):
            cam = ext @ np.array([x, y, 0.0, 1.0])
            u_px, v_px = (k @ cam)[:2] / cam[2]
            assert cam[2] > 0 and 0 < u_px < w and 0 < v_px < h, (x, y, u_px, v_px)
    # each hand camera sees its own fingers, in the bottom half of the image
    ids = {link.name: int(link.per_scene_id[0]) for link in u.agent.robot.get_links()}
    for side in SIDES:
        seg = images[f"{side}_hand_camera"]["segmentation"][0, ..., 0].numpy()
        own = np.isin(seg, [ids[f"{side}_finger1"], ids[f"{side}_finger2"]])
        assert own.mean() > 0.03 and own[h // 2 :].sum() > 0.9 * own.sum()
    env.close()


def test_replay_converts_joint_positions_to_deltas(tmp_path):
    """ManiSkill's replay turns a pd_joint_pos recording into pd_joint_delta_pos actions
    that drive the rig through the same joints."""
    env = RecordEpisode(
        make_env(robot_uids="piperx", control_mode="pd_joint_pos"),
        str(tmp_path),
        save_video=False,
        trajectory_name="demo",
        save_on_reset=True,
    )
    env.reset(seed=0)
    rest = env.unwrapped.agent.keyframes["rest"].qpos
    arm = np.array([rest[joint_order(SIDES).index(n)] for n in ARM_ACTION_ORDER])
    sweep = np.tile([0.3, 0.2, -0.2, -0.3, 0.2, 0.3], 2)
    for k in range(30):  # sweep every arm joint for 8 steps, then hold and close one gripper
        action = np.r_[arm + sweep * min(k + 1, 8) / 8, OPEN, CLOSED if k > 7 else OPEN]
        env.step(torch.tensor(action, dtype=torch.float32)[None])
    env.close()
    replay.main(
        replay.Args(
            traj_path=str(tmp_path / "demo.h5"),
            target_control_mode="pd_joint_delta_pos",
            save_traj=True,
            sim_backend="physx_cpu",
            allow_failure=True,
        )
    )
    with (
        h5py.File(tmp_path / "demo.h5") as src,
        h5py.File(tmp_path / "demo.state.pd_joint_delta_pos.physx_cpu.h5") as dst,
    ):
        actions = dst["traj_0/actions"][()]
        recorded = src["traj_0/env_states/articulations/piperx"][()]
        replayed = dst["traj_0/env_states/articulations/piperx"][()]
    # the converter may split a step into several delta steps until the joints arrive
    assert actions.shape[0] >= 30 and actions.shape[1] == 14
    assert np.abs(actions[:, :12]).max() <= 1.0
    np.testing.assert_allclose(replayed[-1, 13:29], recorded[-1, 13:29], atol=0.01)


def test_base_links_stand_on_the_table_without_contacts():
    """The mounting links and the table ignore each other (no contact for the solver); the
    objects still rest on the table."""
    env = make_env(robot_uids="piperx")
    env.reset(seed=0)
    u = env.unwrapped
    z0 = u.objects[0].pose.p[0, 2].item()
    for _ in range(10):
        env.step(None)
    pairs = {
        frozenset(body.entity.name.split("_", 1)[1] for body in contact.bodies)
        for contact in u.scene.get_contacts()
    }
    z = u.objects[0].pose.p[0, 2].item()
    env.close()
    assert not any("base_link" in name for pair in pairs for name in pair)
    assert any("table" in pair for pair in pairs), "the objects touch the table"
    assert abs(z - z0) < 0.01, "the object rests where it was placed"
