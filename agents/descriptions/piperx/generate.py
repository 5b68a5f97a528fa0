"""Writes the PiperX URDFs of this folder from the published numbers.

Run ``python agents/descriptions/piperx/generate.py`` after changing a number; the URDFs are
committed.
Geometry is boxes and cylinders sized like the real links, each link spanning from its joint
to the next joint; inertials are the published masses spread over that geometry.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

#: Joints 4 and 5 take the vendor SDK's limits (+-1.553 rad) rather than the published
#: description's +-1.5708, so simulated poses stay within what the SDK commands.
WRIST_LIMIT = 1.553
#: name, origin xyz, origin rpy, lower, upper (rad); every axis is z.
ARM_JOINTS = (
    ("joint1", (0, 0, 0.123), (0, 0, math.pi), -2.618, 2.618),
    ("joint2", (0, 0, 0), (-1.5708, -3.005806, -3.1416), 0.0, math.pi),
    ("joint3", (0.28503, 0, 0), (0, 0, 2.8380798), -2.967, 0.0),
    ("joint4", (0.27364, 0, 0), (0, 0, 0.0806342), -WRIST_LIMIT, WRIST_LIMIT),
    ("joint5", (0.07466, 0, 0), (-1.5708, 1.5708, 0), -WRIST_LIMIT, WRIST_LIMIT),
    ("joint6", (0, -0.035, 0), (1.5708, 0, 0), -2.0944, 2.0944),
)
#: Where each finger joint sits along link6's z, and the finger stroke (m).
FINGER_Z, FINGER_STROKE = 0.138, 0.05
#: Grasp centre along link6's z, 2 cm above the fingertips (the pads span 0.075..0.1515 m):
#: where a grasped object sits, so the TCP is within the 2 cm reach threshold of a flat object
#: grasped with the fingertips near the table (at 0.10 it would stay 5 cm above the table).
TCP_Z = 0.13
#: Base offsets of the dual rig (both arms face +x, bases on the table top).
RIG_ARMS = (("left_", 0.3), ("right_", -0.3))

LIGHT, DARK, BLACK = (0.82, 0.82, 0.84, 1.0), (0.22, 0.22, 0.24, 1.0), (0.08, 0.08, 0.09, 1.0)


@dataclass(frozen=True)
class Box:
    size: tuple[float, float, float]
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def volume(self) -> float:
        return float(np.prod(self.size))

    def inertia(self, mass: float) -> np.ndarray:
        x, y, z = self.size
        return mass / 12.0 * np.diag([y * y + z * z, x * x + z * z, x * x + y * y])

    def geometry(self) -> str:
        return '<box size="{:g} {:g} {:g}"/>'.format(*self.size)


@dataclass(frozen=True)
class Cylinder:
    """A cylinder along the link's z axis (the joint axis)."""

    radius: float
    length: float
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def volume(self) -> float:
        return math.pi * self.radius**2 * self.length

    def inertia(self, mass: float) -> np.ndarray:
        side = mass * (3 * self.radius**2 + self.length**2) / 12.0
        return np.diag([side, side, mass * self.radius**2 / 2.0])

    def geometry(self) -> str:
        return f'<cylinder radius="{self.radius:g}" length="{self.length:g}"/>'


@dataclass(frozen=True)
class Link:
    name: str
    mass: float
    shapes: tuple[Box | Cylinder, ...]
    color: tuple[float, float, float, float]


def _limb(to_x: float, width: float, height: float) -> Box:
    """A box from the link origin to the next joint along x."""
    return Box((to_x, width, height), (to_x / 2, 0.0, 0.0))


ARM_LINKS = (
    Link("base_link", 1.02, (Cylinder(0.05, 0.07, (0, 0, 0.035)),), DARK),
    Link("link1", 0.71, (Cylinder(0.045, 0.05, (0, 0, -0.028)),), LIGHT),
    Link("link2", 1.16, (Cylinder(0.045, 0.09), _limb(0.28503, 0.055, 0.06)), LIGHT),
    Link("link3", 0.67, (Cylinder(0.04, 0.08), _limb(0.27364, 0.045, 0.05)), LIGHT),
    Link("link4", 0.39, (Cylinder(0.035, 0.07), _limb(0.07466, 0.045, 0.045)), LIGHT),
    Link("link5", 0.35, (Cylinder(0.032, 0.065),), DARK),
    Link("link6", 0.007, (Cylinder(0.0285, 0.008, (0, 0, 0.004)),), DARK),
)
# The gripper frame is link6 turned +pi/2 about z: the fingers slide along its y (link6's x).
GRIPPER_BASE = Link("gripper_base", 0.45, (Box((0.075, 0.164, 0.067), (0, 0, 0.0415)),), BLACK)
_PAD = (0.056, 0.0265, 0.0765)  # x, y (closing direction), z; the inner face is at the joint
_PAD_Z = 0.075 + _PAD[2] / 2 - FINGER_Z  # pads hang from the gripper base (bottom z 0.075)
FINGERS = (
    Link("finger1", 0.025, (Box(_PAD, (0, _PAD[1] / 2, _PAD_Z)),), DARK),
    Link("finger2", 0.025, (Box(_PAD, (0, -_PAD[1] / 2, _PAD_Z)),), DARK),
)


#: Pairs of one arm's links the simulation never checks against each other (the SRDF):
#: links two joints apart, whose boxes and cylinders meet around the link between them
#: where the real links clear each other; and link2 with link5, which touch at the folded
#: rest pose. Without these the rest pose alone holds eight self-contacts per arm that the
#: solver works against every substep. The two fingers still collide with each other:
#: with that pair excluded, a relay set-down in a stored PlaceA2B scene topples a tall bottle.
IGNORED_PAIRS = (
    ("base_link", "link2"),
    ("link1", "link3"),
    ("link2", "link4"),
    ("link3", "link5"),
    ("link4", "link6"),
    ("link5", "gripper_base"),
    ("link6", "finger1"),
    ("link6", "finger2"),
    ("link2", "link5"),
)


def _fmt(values: Sequence[float]) -> str:
    return " ".join(f"{float(v):.10g}" for v in values)


def _inertial(link: Link) -> str:
    volumes = np.array([s.volume for s in link.shapes])
    masses = link.mass * volumes / volumes.sum()
    centers = np.array([s.xyz for s in link.shapes], dtype=float)
    com = masses @ centers / link.mass
    inertia = np.zeros((3, 3))
    for shape, m, c in zip(link.shapes, masses, centers, strict=True):
        d = c - com
        inertia += shape.inertia(m) + m * (d @ d * np.eye(3) - np.outer(d, d))
    ixx, ixy, ixz, iyy, iyz, izz = (
        inertia[i, j] for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    )
    return (
        f'    <inertial>\n      <origin xyz="{_fmt(com)}" rpy="0 0 0"/>\n'
        f'      <mass value="{link.mass:g}"/>\n'
        f'      <inertia ixx="{ixx:.6g}" ixy="{ixy:.6g}" ixz="{ixz:.6g}" iyy="{iyy:.6g}" '
        f'iyz="{iyz:.6g}" izz="{izz:.6g}"/>\n    </inertial>\n'
    )


def _link(prefix: str, link: Link) -> str:
    body = _inertial(link)
    for shape in link.shapes:
        origin = f'<origin xyz="{_fmt(shape.xyz)}" rpy="0 0 0"/>'
        body += (
            f"    <visual>\n      {origin}\n      <geometry>{shape.geometry()}</geometry>\n"
            f'      <material name="{prefix}{link.name}_color"><color rgba="{_fmt(link.color)}"/>'
            "</material>\n    </visual>\n"
            f"    <collision>\n      {origin}\n      <geometry>{shape.geometry()}</geometry>\n"
            "    </collision>\n"
        )
    return f'  <link name="{prefix}{link.name}">\n{body}  </link>\n'


def _joint(
    name: str,
    kind: str,
    parent: str,
    child: str,
    xyz: Sequence[float],
    rpy: Sequence[float],
    limits: tuple[float, float, float] | None = None,
    axis: Sequence[float] | None = None,
) -> str:
    text = (
        f'  <joint name="{name}" type="{kind}">\n    <parent link="{parent}"/>\n'
        f'    <child link="{child}"/>\n    <origin xyz="{_fmt(xyz)}" rpy="{_fmt(rpy)}"/>\n'
    )
    if axis is not None:
        text += f'    <axis xyz="{_fmt(axis)}"/>\n'
    if limits is not None:
        lower, upper, velocity = limits
        text += (
            f'    <limit lower="{lower:.10g}" upper="{upper:.10g}" effort="100" '
            f'velocity="{velocity:g}"/>\n'
        )
    return text + "  </joint>\n"


def arm(prefix: str) -> str:
    """Links and joints of one arm, names prefixed; its root is ``{prefix}base_link``."""
    p = prefix
    text = "".join(_link(p, link) for link in (*ARM_LINKS, GRIPPER_BASE, *FINGERS))
    text += f'  <link name="{p}tcp"/>\n'
    for (name, xyz, rpy, lower, upper), parent, child in zip(
        ARM_JOINTS, ARM_LINKS[:-1], ARM_LINKS[1:], strict=True
    ):
        text += _joint(
            p + name,
            "revolute",
            p + parent.name,
            p + child.name,
            xyz,
            rpy,
            (lower, upper, 5.0),
            (0, 0, 1),
        )
    text += _joint(
        f"{p}gripper_joint",
        "fixed",
        f"{p}link6",
        f"{p}gripper_base",
        (0, 0, 0),
        (0, 0, math.pi / 2),
    )
    for k, (lower, upper) in enumerate(((0.0, FINGER_STROKE), (-FINGER_STROKE, 0.0)), start=1):
        text += _joint(
            f"{p}finger_joint{k}",
            "prismatic",
            f"{p}gripper_base",
            f"{p}finger{k}",
            (0, 0, FINGER_Z),
            (0, 0, 0),
            (lower, upper, 1.0),
            (0, 1, 0),
        )
    text += _joint(f"{p}tcp_joint", "fixed", f"{p}link6", f"{p}tcp", (0, 0, TCP_Z), (0, 0, 0))
    return text


def _robot(name: str, body: str) -> str:
    return (
        '<?xml version="1.0"?>\n<!-- Generated by generate.py from the published PiperX numbers;'
        " do not edit by hand. -->\n"
        f'<robot name="{name}">\n{body}</robot>\n'
    )


def srdf(name: str, prefixes: Sequence[str]) -> str:
    """The SRDF (SAPIEN reads ``disable_collisions`` with reason ``Default``) of the arms
    with these name prefixes."""
    body = "".join(
        f'  <disable_collisions link1="{p}{a}" link2="{p}{b}" reason="Default"/>\n'
        for p in prefixes
        for a, b in IGNORED_PAIRS
    )
    return _robot(name, body)


def single_arm_urdf() -> str:
    return _robot("piperx_arm", arm(""))


def dual_arm_urdf() -> str:
    body = '  <link name="rig"/>\n'
    for prefix, y in RIG_ARMS:
        body += arm(prefix)
        body += _joint(
            f"{prefix}mount_joint", "fixed", "rig", f"{prefix}base_link", (0, y, 0), (0, 0, 0)
        )
    return _robot("piperx_dual", body)


if __name__ == "__main__":
    (HERE / "piperx_arm.urdf").write_text(single_arm_urdf())
    (HERE / "piperx_dual.urdf").write_text(dual_arm_urdf())
    (HERE / "piperx_arm.srdf").write_text(srdf("piperx_arm", ("",)))
    (HERE / "piperx_dual.srdf").write_text(srdf("piperx_dual", [p for p, _ in RIG_ARMS]))
