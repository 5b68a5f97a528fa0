"""What the shared task engine, the planners and the policies need from a robot, whatever
its number of arms."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import torch
from mani_skill.agents.controllers import PDEEPosController
from mani_skill.utils import common

from instructmove_ms.layout import Workspace

from .contacts import ContactForces
from .hardware import Gripper, JointLimits


@dataclass(frozen=True)
class ArmSlots:
    """Where one arm's commands go in the robot's action vector: ``command`` holds the
    slots of its joint targets (joint control modes, in ``arm_joint_names`` order) or of its
    end-effector command (end-effector modes); ``gripper`` the slot of its gripper value."""

    command: tuple[int, ...]
    gripper: int


@dataclass(frozen=True)
class PolicyInterface:
    """The joint-space policy interface, the layout of the ``pd_joint_pos`` action: every
    arm joint (``arm_joint_names`` order, rad) then one gripper value per arm (the gripper's
    action units). ``joints`` index the robot's active joints; ``fingers`` holds each arm's
    first finger joint (index, direction it opens); ``names`` names every dimension;
    ``sides`` names the arms (``""`` for a robot's only arm)."""

    joints: tuple[int, ...]
    fingers: tuple[tuple[int, float], ...]
    gripper: Gripper
    names: tuple[str, ...]
    sides: tuple[str, ...] = ("",)

    def parts(self) -> dict[str, tuple[int, int]]:
        """The named slices [start, end) of the interface's vector, in its order: each arm's
        joints (``arm``, or ``left_arm`` ... on a robot with sides), then each arm's gripper
        (``gripper``, ``left_gripper`` ...)."""
        if len(self.sides) != len(self.fingers):
            raise ValueError(f"{len(self.fingers)} arms but sides {self.sides}")
        per_arm = len(self.joints) // len(self.sides)
        prefixes = [f"{side}_" if side else "" for side in self.sides]
        out = {f"{p}arm": (k * per_arm, (k + 1) * per_arm) for k, p in enumerate(prefixes)}
        grippers = len(self.joints)
        out |= {f"{p}gripper": (grippers + k, grippers + k + 1) for k, p in enumerate(prefixes)}
        return out

    def state(self, qpos) -> np.ndarray:
        """The robot's configuration ``qpos`` (..., active joints) in this interface: the
        action that holds the robot where it is."""
        qpos = np.asarray(qpos, dtype=float)
        grippers = [self.gripper.value(2.0 * sign * qpos[..., k]) for k, sign in self.fingers]
        return np.concatenate([qpos[..., list(self.joints)], np.stack(grippers, axis=-1)], -1)


#: SAPIEN collision group 2 bit shared by a robot's mounting links and the table it stands
#: on: shapes that share a set bit of group 2 never collide.
MOUNT_BIT = 29


class InstructMoveAgent:
    """Mixin for ManiSkill agents used by InstructMove tasks.

    A subclass provides ``keyframes["rest"]``, ``arm_joint_names`` (every arm joint, arm by
    arm), ``tcp_links`` (one TCP link per arm), ``finger_pairs`` (for ``grasping``), and
    declares its hardware: ``gripper``, ``joint_limits`` (one arm's) and ``demo_pace`` (the
    fraction of those limits planned demos move at). Its controllers keep one controller
    per gripper, in arm order, besides the arm's.
    """

    #: Where objects may be placed: the reference workspace, narrowed to the robot's reach.
    workspace = Workspace()
    #: The static or exterior cameras that see the whole table (visibility is measured in
    #: them; wrist cameras are left out).
    scene_cameras: ClassVar[tuple[str, ...]]
    #: Links fixed to the robot's fixed base that stand on the table: their contacts with
    #: it move nothing, so the solver is kept off them (``mount``).
    mount_links: ClassVar[tuple[str, ...]] = ()
    gripper: ClassVar[Gripper]
    #: The arms' names, in arm order (one unnamed arm by default).
    sides: ClassVar[tuple[str, ...]] = ("",)
    joint_limits: ClassVar[JointLimits]
    demo_pace: ClassVar[float]

    @property
    def tcp_links(self) -> list:
        raise NotImplementedError

    @property
    def finger_pairs(self) -> list[tuple[tuple[object, float], tuple[object, float]]]:
        """Per arm, its two finger links, each with the sign that turns its y axis into
        the direction it opens."""
        raise NotImplementedError

    def mount(self, table) -> None:
        """Let ``table`` (an actor) and the ``mount_links`` ignore each other."""
        if self.mount_links:
            table.set_collision_group_bit(group=2, bit_idx=MOUNT_BIT, bit=1)
        for name in self.mount_links:
            self.robot.links_map[name].set_collision_group_bit(group=2, bit_idx=MOUNT_BIT, bit=1)

    def grasping(
        self,
        actor,
        forces: ContactForces,
        arms: Sequence[int] | None = None,
        min_force: float = 0.5,
        max_angle: float = 85.0,
    ) -> torch.Tensor:
        """(N,) true where both fingers of one of ``arms`` (default: all) push on ``actor``
        with at least ``min_force`` N, within ``max_angle`` deg of the direction they open
        (ManiSkill's Panda test), the contact forces read by ``forces(link, actor)``. A
        finger that does not touch ``actor`` ends its arm's test (no force or pose is read
        for it)."""
        pairs = self.finger_pairs if arms is None else [self.finger_pairs[k] for k in arms]
        flags = []
        for pair in pairs:
            flag = None
            for link, sign in pair:
                if not forces.touching(link, actor):
                    flag = torch.zeros(self.scene.num_envs, dtype=torch.bool, device=self.device)
                    break
                force = forces(link, actor)
                pushed = torch.linalg.norm(force, dim=1) >= min_force
                if not bool(pushed.any()):
                    flag = torch.zeros_like(pushed)
                    break
                opening = sign * link.pose.to_transformation_matrix()[..., :3, 1]
                angle = torch.rad2deg(common.compute_angle_between(opening, force))
                finger = pushed & (angle <= max_angle)
                flag = finger if flag is None else flag & finger
            flags.append(flag)
        return flags[0] if len(flags) == 1 else torch.stack(flags).any(dim=0)

    def is_grasping(self, actor, min_force: float = 0.5, max_angle: float = 85.0) -> torch.Tensor:
        """(N,) true where any arm grasps ``actor``."""
        return self.grasping(actor, ContactForces(self.scene), None, min_force, max_angle)

    def tcp_positions(self) -> torch.Tensor:
        """TCP positions of every arm, (N, arms, 3)."""
        return torch.stack([link.pose.p for link in self.tcp_links], dim=1)

    def arm_joints(self, arm: int) -> list[str]:
        """The joints of arm ``arm`` (0 for a single arm; the PiperX's 0 left, 1 right)."""
        names = list(self.arm_joint_names)
        per_arm = len(names) // len(self.tcp_links)
        return names[arm * per_arm : (arm + 1) * per_arm]

    def _gripper_controllers(self) -> dict:
        """The controllers of the current mode that drive no arm joint: one per arm."""
        arm = set(self.arm_joint_names)
        return {
            key: c
            for key, c in self.controller.controllers.items()
            if not arm & {j.name for j in c.joints}
        }

    def policy_interface(self) -> PolicyInterface:
        """The joint-space policy interface of this robot (see ``PolicyInterface``)."""
        names = [j.name for j in self.robot.get_active_joints()]
        limits = self.robot.get_qlimits()[0].cpu().numpy()
        grippers = self._gripper_controllers()
        fingers = []
        for controller in grippers.values():
            k = names.index(controller.joints[0].name)
            fingers.append((k, float(np.sign(limits[k].sum()))))
        return PolicyInterface(
            joints=tuple(names.index(n) for n in self.arm_joint_names),
            fingers=tuple(fingers),
            gripper=self.gripper,
            names=(*self.arm_joint_names, *grippers),
            sides=tuple(self.sides),
        )

    def action_layout(self) -> tuple[ArmSlots, ...]:
        """Per arm, where its commands go in the action of the current control mode."""
        commands: list[list[int]] = [[] for _ in self.tcp_links]
        grippers: list[int] = []
        arms = [set(self.arm_joints(k)) for k in range(len(self.tcp_links))]
        offset = 0
        for controller in self.controller.controllers.values():
            names = [j.name for j in controller.joints]
            size = controller.single_action_space.shape[0]
            owners = [k for k, joints in enumerate(arms) if joints & set(names)]
            if not owners:
                grippers.append(offset)
            elif isinstance(controller, PDEEPosController):
                commands[owners[0]] += range(offset, offset + size)
            else:
                for k in owners:
                    commands[k] += [offset + names.index(n) for n in self.arm_joints(k)]
            offset += size
        return tuple(ArmSlots(tuple(c), g) for c, g in zip(commands, grippers, strict=True))

    def sample_init_qpos(self, rng: np.random.Generator, noise: float) -> np.ndarray:
        """The rest keyframe with Gaussian noise (std ``noise`` rad) on the arm joints,
        clamped to the joint limits."""
        qpos = np.asarray(self.keyframes["rest"].qpos, dtype=float).copy()
        names = [j.name for j in self.robot.get_active_joints()]
        arm = [names.index(n) for n in self.arm_joint_names]
        qpos[arm] += rng.normal(0.0, noise, size=len(arm))
        limits = self.robot.get_qlimits()[0].cpu().numpy()
        return np.clip(qpos, limits[:, 0], limits[:, 1])
