"""One arm of a live env's robot as the planners see it: kinematics, joint limits, gripper
values and the ``pd_joint_pos`` action layout of the whole robot.

The other arm of a dual-arm rig holds the configuration it had when the rig was built.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
import sapien
import sapien.physx as physx

from .kinematics import ArmKinematics, arm_joint_names
from .planner import JointLimits


@dataclass(frozen=True)
class Gripper:
    """A parallel gripper: its ``pd_joint_pos`` action value is ``offset + scale * width``
    for fingers ``width`` metres apart (up to ``max_width``); ``closed`` squeezes whatever is
    between them. ``tcp_in_grasp`` is the TCP frame in a grasp frame whose y axis is the
    fingers' closing axis and whose z axis is the approach."""

    max_width: float
    scale: float
    offset: float
    closed: float
    tcp_in_grasp: sapien.Pose

    def value(self, width: float) -> float:
        """The action value that opens the fingers ``width`` metres apart."""
        return self.offset + self.scale * min(width, self.max_width)

    @property
    def open(self) -> float:
        return self.value(self.max_width)


#: Per robot uid: the gripper and the arm's joint limits.
ROBOTS: dict[str, tuple[Gripper, Callable[[], JointLimits]]] = {
    # ManiSkill's normalised Panda gripper: [-1, 1] spans finger targets -0.01..0.04 m; the
    # TCP's y axis is the fingers' axis.
    "franka": (Gripper(0.08, 20.0, -0.6, -1.0, sapien.Pose()), JointLimits.franka),
    # The width itself; the fingers slide along link6's (and the TCP's) x axis.
    "piperx": (
        Gripper(0.1, 1.0, 0.0, 0.0, sapien.Pose(q=[np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)])),
        JointLimits.piperx,
    ),
}
ROBOTS["piperx_single"] = ROBOTS["piperx"]


@dataclass(frozen=True)
class Rig:
    """Arm ``arm`` of the env's robot (the Franka's only arm; the PiperX's 0 left, 1 right).

    ``shoulder`` is the position (base frame) of the link the arm's first joint turns.
    ``hold`` is the full ``pd_joint_pos`` action that keeps the robot where it was at
    ``from_env``; ``arm_slots`` and ``gripper_slot`` say where this arm's joint targets and
    gripper value go in it. ``fingers`` lists (index in ``kin.qpos``, direction it opens)
    of the arm's finger joints; ``tip_depth`` is how far the fingertips reach beyond the TCP
    along the approach.
    """

    arm: int
    kin: ArmKinematics
    shoulder: np.ndarray
    limits: JointLimits
    gripper: Gripper
    hold: np.ndarray
    arm_slots: np.ndarray
    gripper_slot: int
    fingers: tuple[tuple[int, float], ...]
    tip_depth: float

    @classmethod
    def from_env(cls, env, arm: int = 0) -> Rig:
        """The rig of arm ``arm`` at the env's current state (``pd_joint_pos`` control)."""
        agent = env.unwrapped.agent
        if agent.control_mode != "pd_joint_pos":
            raise ValueError(f"planned actions need pd_joint_pos, not {agent.control_mode}")
        gripper, limits = ROBOTS[agent.uid]
        kin = ArmKinematics.from_env(env, arm)
        qlimits = agent.robot.get_qlimits()[0].cpu().numpy()
        index = {name: k for k, name in enumerate(kin.joints)}
        hold, grippers, arm_slots, offset = [], [], [], 0
        for key, controller in agent.controller.controllers.items():
            names = [j.name for j in controller.joints]
            if key == "arm":
                hold += [kin.qpos[index[n]] for n in names]
                arm_slots = [offset + names.index(kin.joints[i]) for i in kin.arm]
            else:  # one gripper per arm, in arm order; it keeps its opening
                finger = [(index[n], float(np.sign(qlimits[index[n]].sum()))) for n in names]
                tips = [agent.robot.joints_map[n].child_link for n in names]
                grippers.append((offset, tuple(finger), _reach_along(tips, agent.tcp_links[arm])))
                k, sign = finger[0]
                hold.append(gripper.value(2.0 * sign * kin.qpos[k]))
            offset += controller.action_space.shape[0]
        return cls(
            arm,
            kin,
            _shoulder(agent, arm),
            limits(),
            gripper,
            np.asarray(hold),
            np.asarray(arm_slots),
            *grippers[arm],
        )

    @property
    def start(self) -> np.ndarray:
        """The arm's configuration at ``from_env``."""
        return self.kin.qpos[self.kin.arm]

    @property
    def width(self) -> float:
        """How far apart the arm's fingers are in ``kin`` (metres)."""
        k, sign = self.fingers[0]
        return 2.0 * sign * float(self.kin.qpos[k])

    def opened(self, width: float) -> Rig:
        """This rig with its fingers ``width`` metres apart in ``kin`` (what collision checks
        see)."""
        qpos = self.kin.qpos.copy()
        for k, sign in self.fingers:
            qpos[k] = sign * 0.5 * min(width, self.gripper.max_width)
        return replace(self, kin=self.kin.with_qpos(qpos))

    def actions(self, targets: np.ndarray, gripper: float) -> np.ndarray:
        """``pd_joint_pos`` actions: each row of this arm's joint ``targets`` with its gripper
        action value ``gripper``; the rest of the robot holds still."""
        out = np.repeat(self.hold[None], len(targets), axis=0)
        out[:, self.arm_slots] = targets
        out[:, self.gripper_slot] = gripper
        return out.astype(np.float32)


def _reach_along(links, tcp) -> float:
    """How far the collision boxes and meshes of ``links`` reach along ``tcp``'s z axis."""
    frame = tcp.pose.sp.inv()
    reach = 0.0
    for link in links:
        for shape in link._objs[0].get_collision_shapes():
            if isinstance(shape, physx.PhysxCollisionShapeBox):
                corners = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)])
                points = corners * np.asarray(shape.half_size)
            else:
                points = np.asarray(shape.get_vertices()) * np.asarray(shape.get_scale())
            m = (frame * link.pose.sp * shape.get_local_pose()).to_transformation_matrix()
            reach = max(reach, float((points @ m[2, :3] + m[2, 3]).max()))
    return reach


def _shoulder(agent, arm: int) -> np.ndarray:
    """Position (base frame) of the link that arm ``arm``'s first joint turns."""
    link = agent.robot.joints_map[arm_joint_names(agent, arm)[0]].parent_link
    return np.asarray((agent.robot.pose.sp.inv() * link.pose.sp).p, dtype=float)


def arm_order(env, point: Sequence[float]) -> list[int]:
    """The robot's arms, the one whose shoulder is nearest ``point`` (base frame, in the table
    plane) first."""
    agent = env.unwrapped.agent
    xy = np.asarray(point, dtype=float)[:2]
    distance = [
        float(np.linalg.norm(_shoulder(agent, k)[:2] - xy)) for k in range(len(agent.tcp_links))
    ]
    return sorted(range(len(distance)), key=distance.__getitem__)
