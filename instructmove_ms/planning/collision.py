"""A python-fcl collision world: one arm's robot posed by FK against the table and the objects.

Each world poses its own collision objects of the geometry the planning scene converted once
per episode (``geometry``). Poses are in the robot's base frame.
"""

from __future__ import annotations

from dataclasses import dataclass

import fcl
import numpy as np
import sapien

from .geometry import Geometry
from .kinematics import ArmKinematics
from .robot import RobotModel

_ATTACHED = "attached"


@dataclass
class Shape:
    """One fcl object, its geometry and its pose in its body's frame."""

    obj: fcl.CollisionObject
    geom: fcl.CollisionGeometry
    local: np.ndarray


Geoms = list[Shape]


def _objects(geometry: Geometry) -> Geoms:
    """Fresh collision objects of ``geometry`` (a world moves its own)."""
    return [
        Shape(fcl.CollisionObject(geom, fcl.Transform()), geom, local) for geom, local in geometry
    ]


def _place(geoms: Geoms, body: np.ndarray) -> None:
    for shape in geoms:
        m = body @ shape.local
        shape.obj.setTransform(fcl.Transform(m[:3, :3], m[:3, 3]))


class CollisionWorld:
    """The arm of ``kin`` against named static obstacles, with allowed-contact filtering.

    The links the arm's joints move form the robot; every other link with geometry (the
    base, a second arm at its ``kin.qpos`` configuration) becomes a static obstacle named
    after the link. ``in_collision(q)`` checks the moving links against each other and
    against the obstacles; parent-child and sibling links, and bodies already touching at
    ``kin.qpos``, are ignored. A grasped object can be attached to the end effector; it then
    moves with the arm and may touch the gripper.
    """

    def __init__(
        self,
        kin: ArmKinematics,
        robot: RobotModel,
        obstacles: dict[str, tuple[Geometry, np.ndarray]],
    ):
        self.kin = kin
        parent = robot.parent
        arm_joints = {kin.joints[i] for i in kin.arm}
        moved = {child for joint, child in robot.joint_child.items() if joint in arm_joints}
        moved = _subtree(moved, parent)
        rest = kin.link_poses(kin.qpos[kin.arm])
        static = {name: (_objects(geometry), pose) for name, (geometry, pose) in obstacles.items()}
        self.links: dict[str, Geoms] = {}
        for name, geometry in robot.geometry.items():
            geoms = _objects(geometry)
            if name in moved:
                self.links[name] = geoms
            else:
                pose = rest[kin.links.index(name)].to_transformation_matrix()
                static[name] = (geoms, pose)
        self.obstacles: dict[str, Geoms] = {}
        for name, (geoms, pose) in static.items():
            _place(geoms, pose)
            self.obstacles[name] = geoms
        self.attached: tuple[str, Geoms] | None = None
        self.allowed: set[frozenset[str]] = set()
        for child, par in parent.items():
            self.allow(child, par)
            for other, other_par in parent.items():
                if other_par == par and other != child:
                    self.allow(child, other)
        ee = kin.links[kin.ee_index]
        #: Links that may touch an attached object: the end effector's parent and its subtree.
        self.gripper_links = _subtree({parent.get(ee, ee)}, parent)
        self._rebuild()
        robot_links = set(kin.links)
        for a, b in self.contacts(kin.qpos[kin.arm]):
            if a in robot_links and b in robot_links:
                self.allow(a, b)

    def add_obstacle(
        self,
        name: str,
        geometry: list[tuple[fcl.CollisionGeometry, sapien.Pose]],
        pose: sapien.Pose,
    ) -> None:
        """Add (or replace) a static obstacle: fcl geometries posed in a body at ``pose``."""
        geoms = []
        for geom, local in geometry:
            obj = fcl.CollisionObject(geom, fcl.Transform())
            geoms.append(Shape(obj, geom, local.to_transformation_matrix()))
        _place(geoms, pose.to_transformation_matrix())
        self.obstacles[name] = geoms
        self._rebuild()

    def allow(self, a: str, b: str) -> None:
        """Let bodies ``a`` and ``b`` (link, obstacle or ``"attached"`` names) touch."""
        self.allowed.add(frozenset((a, b)))

    def forbid(self, a: str, b: str) -> None:
        self.allowed.discard(frozenset((a, b)))

    def _rebuild(self) -> None:
        self._names: dict[int, str] = {}
        robot_objs, obstacle_objs = [], []
        bodies = list(self.links.items())
        if self.attached is not None:
            bodies.append((_ATTACHED, self.attached[1]))
        for name, geoms in bodies:
            for shape in geoms:
                self._names[id(shape.geom)] = name
                robot_objs.append(shape.obj)
        for name, geoms in self.obstacles.items():
            for shape in geoms:
                self._names[id(shape.geom)] = name
                obstacle_objs.append(shape.obj)
        self._robot = fcl.DynamicAABBTreeCollisionManager()
        self._robot.registerObjects(robot_objs)
        self._robot.setup()
        self._static = fcl.DynamicAABBTreeCollisionManager()
        self._static.registerObjects(obstacle_objs)
        self._static.setup()

    def _pose_robot(self, q: np.ndarray) -> np.ndarray:
        """Move the robot's geometry to ``q``; returns the end-effector pose matrix."""
        poses = self.kin.link_poses(q)
        for i, name in enumerate(self.kin.links):
            if name in self.links:
                _place(self.links[name], poses[i].to_transformation_matrix())
        ee = poses[self.kin.ee_index].to_transformation_matrix()
        if self.attached is not None:
            _place(self.attached[1], ee)
        self._robot.update()
        return ee

    def contacts(self, q: np.ndarray) -> set[tuple[str, str]]:
        """Pairs of bodies in collision at arm configuration ``q``, allowed pairs left out."""
        self._pose_robot(q)
        pairs = set()
        for other in (None, self._static):
            request = fcl.CollisionRequest(num_max_contacts=100000, enable_contact=True)
            data = fcl.CollisionData(request=request)
            if other is None:
                self._robot.collide(data, fcl.defaultCollisionCallback)
            else:
                self._robot.collide(other, data, fcl.defaultCollisionCallback)
            for c in data.result.contacts:
                a, b = self._names[id(c.o1)], self._names[id(c.o2)]
                if a != b and frozenset((a, b)) not in self.allowed:
                    pairs.add((min(a, b), max(a, b)))
        return pairs

    def in_collision(self, q: np.ndarray) -> bool:
        return bool(self.contacts(q))

    def attach(self, name: str, q: np.ndarray) -> None:
        """Carry obstacle ``name`` with the end effector from configuration ``q`` on; it may
        touch the gripper links."""
        ee_inv = np.linalg.inv(self._pose_robot(q))
        geoms = self.obstacles.pop(name)
        self.attached = (name, [Shape(s.obj, s.geom, ee_inv @ _matrix(s.obj)) for s in geoms])
        for link in self.gripper_links:
            self.allow(_ATTACHED, link)
        self._rebuild()

    def detach(self, q: np.ndarray) -> str:
        """Leave the attached object where configuration ``q`` puts it; returns its name."""
        if self.attached is None:
            raise RuntimeError("nothing is attached")
        name, geoms = self.attached
        self._pose_robot(q)
        self.obstacles[name] = [Shape(s.obj, s.geom, _matrix(s.obj)) for s in geoms]
        self.attached = None
        self._rebuild()
        return name


def _subtree(roots: set[str], parent: dict[str, str]) -> set[str]:
    """``roots`` and every link below them (``parent``: child link -> parent link)."""
    out = set(roots)
    while True:
        more = {c for c, p in parent.items() if p in out} - out
        if not more:
            return out
        out |= more


def _matrix(obj: fcl.CollisionObject) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = obj.getRotation(), obj.getTranslation()
    return m
