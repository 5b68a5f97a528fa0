"""The planning scene: everything the planners and the planned policies know of an episode.

Built once per episode from the env (``PlanningScene.from_env``): the robot model, the
collision geometry of the table and of every object with its catalog entry and actor name,
which object to move (``target``) and where (``destination``, -1 for none), the reach
threshold and the horizon. ``observe(env)`` reads the live state the next plan starts from
(robot configuration, object poses, TCP positions, whether the object is held, the steps
taken); nothing else of the env is read, so a planner can be aimed at any object by building
the scene for it. Poses are in the robot's base frame.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sapien
import sapien.physx as physx

from instructmove_ms.assets.catalog import Instance
from instructmove_ms.episode import actor_name

from .collision import CollisionWorld
from .geometry import Geometry, body_geometry
from .kinematics import ArmKinematics
from .rig import Rig
from .robot import RobotModel

TABLE = "table"  # the name of the table's actor and obstacle


@dataclass(frozen=True)
class SceneObject:
    """One object of the episode: its actor name, catalog entry and collision geometry."""

    name: str
    instance: Instance
    geometry: Geometry


@dataclass(frozen=True)
class SceneState:
    """The live state a plan starts from: the robot's full configuration, the table's and
    the objects' poses and every arm's TCP position (base frame), whether the
    object to move is in the hand and how many steps the episode has taken."""

    qpos: np.ndarray
    table: sapien.Pose
    poses: tuple[sapien.Pose, ...]
    tcps: np.ndarray
    held: bool
    elapsed: int


def _geometry(actor) -> Geometry:
    body = actor._objs[0].find_component_by_type(physx.PhysxRigidBaseComponent)
    return body_geometry(body.get_collision_shapes())


@dataclass
class PlanningScene:
    """See the module docstring; ``state`` is the last ``observe``-d one."""

    robot: RobotModel
    table: Geometry
    objects: tuple[SceneObject, ...]
    target: int
    destination: int
    reach: float
    horizon: int
    state: SceneState

    @classmethod
    def from_env(
        cls, env, target: int | None = None, destination: int | None = None
    ) -> PlanningScene:
        """The scene of the env's current episode (sub-scene 0), observed now, for moving
        object ``target`` to ``destination`` (default: the episode's own goal)."""
        u = env.unwrapped
        spec = u.episode
        catalog = u.catalog_of(spec)
        objects = tuple(
            SceneObject(actor_name(k), catalog[obj.uuid], _geometry(u.objects[k]))
            for k, obj in enumerate(spec.objects)
        )
        scene = cls(
            robot=RobotModel.from_agent(u.agent),
            table=_geometry(u.scene.actors[TABLE]),
            objects=objects,
            target=spec.target if target is None else target,
            destination=spec.goal_destination if destination is None else destination,
            reach=u.task.thresholds.reach,
            horizon=u.task.max_episode_steps,
            state=None,  # type: ignore[arg-type]  (observed just below)
        )
        scene.observe(env)
        return scene

    def observe(self, env) -> SceneState:
        """Read the env's live state into ``state`` (and return it)."""
        u = env.unwrapped
        base_inv = u.agent.robot.pose.sp.inv()
        held = self.target >= 0 and bool(u.agent.is_grasping(u.objects[self.target])[0])
        tcps = u.agent.tcp_positions()[0].cpu().numpy()
        self.state = SceneState(
            qpos=u.agent.robot.get_qpos()[0].cpu().numpy().astype(float),
            table=base_inv * u.scene.actors[TABLE].pose.sp,
            poses=tuple(base_inv * actor.pose.sp for actor in u.objects),
            tcps=np.array([(base_inv * sapien.Pose(p)).p for p in tcps]),
            held=held,
            elapsed=int(u.elapsed_steps[0]),
        )
        return self.state

    # What the planners ask ------------------------------------------------------------
    @property
    def arms(self) -> range:
        return range(len(self.robot.arms))

    @property
    def steps_left(self) -> int:
        """Steps left in the episode's horizon."""
        return self.horizon - self.state.elapsed

    def pose(self, k: int) -> sapien.Pose:
        """Object ``k``'s pose (base frame)."""
        return self.state.poses[k]

    def box(self, k: int) -> tuple[sapien.Pose, np.ndarray, np.ndarray]:
        """Object ``k``'s pose and its box's (lowest, highest) corners in its frame."""
        lo, hi = self.objects[k].instance.bounds
        return self.state.poses[k], lo, hi

    def rig(self, arm: int = 0) -> Rig:
        """Arm ``arm`` at the observed configuration."""
        return Rig.of(self.robot, arm, self.state.qpos)

    def kinematics(self, arm: int = 0) -> ArmKinematics:
        return ArmKinematics(self.robot, arm, self.state.qpos)

    def world(self, kin: ArmKinematics) -> CollisionWorld:
        """The collision world of ``kin``'s arm against the table and every object, at their
        observed poses (obstacles named ``table`` and after the objects' actors)."""
        obstacles = {TABLE: (self.table, self.state.table.to_transformation_matrix())}
        for obj, pose in zip(self.objects, self.state.poses, strict=True):
            obstacles[obj.name] = (obj.geometry, pose.to_transformation_matrix())
        return CollisionWorld(kin, self.robot, obstacles)

    def arm_order(self, point: Sequence[float]) -> list[int]:
        """The arms, the one whose shoulder is nearest ``point`` (base frame, in the table
        plane) first."""
        xy = np.asarray(point, dtype=float)[:2]
        distance = [float(np.linalg.norm(a.shoulder[:2] - xy)) for a in self.robot.arms]
        return sorted(range(len(distance)), key=distance.__getitem__)

    def holding_arm(self) -> int:
        """The arm whose TCP is nearest the object to move (the one that picked it)."""
        at = np.asarray(self.state.poses[self.target].p)
        return int(np.linalg.norm(self.state.tcps - at, axis=1).argmin())

    def other_arms(self) -> list[int]:
        """The arms not holding the object (none for a single arm)."""
        holder = self.holding_arm()
        return [k for k in self.arms if k != holder]
