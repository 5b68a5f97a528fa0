"""The shared InstructMove engine: every family is this env plus a declarative TaskSpec."""

from __future__ import annotations

import dataclasses
import math
from typing import Any, ClassVar

import numpy as np
import sapien
import torch
from mani_skill.envs.sapien_env import BaseEnv
from mani_skill.sensors.camera import CameraConfig
from mani_skill.utils import sapien_utils
from mani_skill.utils.structs.actor import Actor
from mani_skill.utils.structs.pose import Pose
from mani_skill.utils.structs.types import SimConfig

from instructmove_ms.assets import DEFAULT_SNAPSHOT, load_snapshot
from instructmove_ms.assets.catalog import Instance
from instructmove_ms.assets.sapien_builder import actor_builder
from instructmove_ms.episode import EpisodeSpec, ObjectSpec
from instructmove_ms.language import referring_expression, render
from instructmove_ms.layout import sample_layout
from instructmove_ms.sampler import SPLITS, resolve_roles
from instructmove_ms.stages import box_distance, first_index, latch_first
from instructmove_ms.validation import check_choice, check_range

from .scene import build_table
from .spec import TaskSpec

#: Objects spawn this far above the table and settle in the first physics steps.
SPAWN_LIFT = 0.002


class InstructMoveEnv(BaseEnv):
    """Shared engine; subclasses set ``task``. See each family for its docstring."""

    task: ClassVar[TaskSpec]
    SUPPORTED_REWARD_MODES = ("dense", "normalized_dense", "sparse", "none")

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if hasattr(cls, "task"):
            cls.SUPPORTED_ROBOTS = list(cls.task.supported_robots)

    def __init__(
        self,
        *args,
        robot_uids: str | None = None,
        split: str = "train",
        num_distractors: int | None = None,
        robot_init_qpos_noise: float = 0.02,
        snapshot: str = DEFAULT_SNAPSHOT,
        **kwargs,
    ):
        robot_uids = robot_uids or self.task.default_robot
        check_choice("robot_uids", robot_uids, self.task.supported_robots)
        check_choice("split", split, SPLITS)
        if num_distractors is None:
            num_distractors = self.task.role("distractor").count
        check_range("num_distractors", num_distractors, *self.task.count_limits["distractor"])
        if not robot_init_qpos_noise >= 0:
            raise ValueError(f"robot_init_qpos_noise must be >= 0, got {robot_init_qpos_noise!r}")
        self.split = split
        self.num_distractors = num_distractors
        self._roles = tuple(
            dataclasses.replace(r, count=num_distractors) if r.name == "distractor" else r
            for r in self.task.roles
        )
        self.robot_init_qpos_noise = float(robot_init_qpos_noise)
        self.catalog = load_snapshot(snapshot)
        self.episodes: list[EpisodeSpec] = []
        self.objects: list[Actor] = []
        self._requested: list[EpisodeSpec] | None = None
        kwargs.setdefault("reconfiguration_freq", 1)
        super().__init__(*args, robot_uids=robot_uids, **kwargs)

    # ManiSkill configuration ----------------------------------------------------------
    @property
    def _default_sim_config(self) -> SimConfig:
        return SimConfig(sim_freq=120, control_freq=30)

    @property
    def _default_sensor_configs(self) -> list[CameraConfig]:
        return []  # the robot carries the cameras

    @property
    def _default_human_render_camera_configs(self) -> CameraConfig:
        pose = sapien_utils.look_at(eye=[1.15, 0.45, 0.75], target=[0.3, 0.0, -0.05])
        return CameraConfig("render_camera", pose, 512, 512, 1.0, 0.01, 10.0)

    def _load_agent(self, options: dict) -> None:
        super()._load_agent(options, sapien.Pose())

    # Episodes -------------------------------------------------------------------------
    def reset(self, seed=None, options=None):
        """ManiSkill's reset; ``options={"episode": spec}`` rebuilds that episode exactly.

        ``spec`` is an :class:`EpisodeSpec`, its dict, or a list of either (one per
        sub-scene). Pass the dict form when recording so that the reset kwargs stay JSON.
        """
        options = dict(options or {})
        if "episode" in options:
            self._requested = self._coerce_episodes(options.pop("episode"))
            options["reconfigure"] = True
        return super().reset(seed=seed, options=options)

    def _coerce_episodes(self, value) -> list[EpisodeSpec]:
        items = value if isinstance(value, list | tuple) else [value]
        specs = [v if isinstance(v, EpisodeSpec) else EpisodeSpec.from_dict(v) for v in items]
        if len(specs) != self.num_envs:
            raise ValueError(f"got {len(specs)} episode specs for {self.num_envs} sub-scenes")
        for spec in specs:
            if spec.family != self.task.family:
                raise ValueError(
                    f"episode family {spec.family!r} does not match env family {self.task.family!r}"
                )
            if spec.robot != self.robot_uids:
                raise ValueError(
                    f"episode robot {spec.robot!r} does not match env robot {self.robot_uids!r}"
                )
            for obj in spec.objects:
                self.catalog[obj.uuid]  # raises with the unknown uuid
        if len({len(s.objects) for s in specs}) != 1:
            raise ValueError("all sub-scenes must hold the same number of objects")
        return specs

    def _sample_roles(self, seed: int) -> list[tuple[Instance, str]]:
        assigned = resolve_roles(self._roles, self.catalog, self.split, seed)
        return [(inst, role) for role, members in assigned.items() for inst in members]

    def _render_instruction(self, rng: np.random.Generator, target: Instance) -> str:
        return render(
            rng, self.task.templates, target=referring_expression(rng, target, self.split)
        )

    def sample_episode(self, seed: int) -> EpisodeSpec:
        """The episode of ``seed``: objects, layout, robot joints and instruction."""
        rng = np.random.default_rng(seed)
        roles = self._sample_roles(seed)
        roles = [roles[k] for k in rng.permutation(len(roles))]
        halves = []
        for inst, _ in roles:
            lo, hi = inst.bounds
            halves.append((float(hi[0] - lo[0]) / 2, float(hi[1] - lo[1]) / 2))
        places = sample_layout(rng, halves, self.task.workspace, self.task.clearance)
        objects = tuple(
            ObjectSpec(
                inst.uuid,
                inst.category,
                role,
                (p.x, p.y, SPAWN_LIFT, math.cos(p.yaw / 2), 0.0, 0.0, math.sin(p.yaw / 2)),
            )
            for (inst, role), p in zip(roles, places, strict=True)
        )
        target = next(k for k, (_, role) in enumerate(roles) if role == "target")
        qpos = self.agent.sample_init_qpos(rng, self.robot_init_qpos_noise)
        return EpisodeSpec(
            family=self.task.family,
            robot=self.robot_uids,
            snapshot=self.catalog.name,
            split=self.split,
            seed=int(seed),
            instruction=self._render_instruction(rng, roles[target][0]),
            objects=objects,
            target=target,
            candidates=tuple(range(len(objects))),
            robot_qpos=tuple(float(q) for q in qpos),
        )

    @property
    def episode(self) -> EpisodeSpec:
        """The current episode's spec (single sub-scene; see ``episodes`` otherwise)."""
        if self.num_envs != 1:
            raise AttributeError(f"{self.num_envs} sub-scenes: use env.unwrapped.episodes")
        return self.episodes[0]

    def get_language_instruction(self) -> list[str]:
        """The instruction of each sub-scene."""
        return [ep.instruction for ep in self.episodes]

    # Scene ----------------------------------------------------------------------------
    def _load_scene(self, options: dict) -> None:
        if self._requested is not None:
            self.episodes, self._requested = self._requested, None
        else:
            self.episodes = [self.sample_episode(int(s)) for s in self._episode_seed]
        build_table(self.scene)
        self.objects = []
        boxes = []
        for k in range(len(self.episodes[0].objects)):
            parts = []
            for i, ep in enumerate(self.episodes):
                obj = ep.objects[k]
                builder = actor_builder(self.scene, self.catalog[obj.uuid])
                builder.set_scene_idxs([i])
                builder.initial_pose = sapien.Pose(p=obj.pose[:3], q=obj.pose[3:])
                actor = builder.build(name=f"object_{k}_{i}")
                self.remove_from_state_dict_registry(actor)
                parts.append(actor)
            merged = Actor.merge(parts, name=f"object_{k}")
            self.add_to_state_dict_registry(merged)
            self.objects.append(merged)
        for ep in self.episodes:
            lo_hi = [self.catalog[o.uuid].bounds for o in ep.objects]
            boxes.append([np.concatenate([(lo + hi) / 2, (hi - lo) / 2]) for lo, hi in lo_hi])
        boxes_t = torch.tensor(np.asarray(boxes), dtype=torch.float32, device=self.device)
        self._box_center, self._box_half = boxes_t[..., :3], boxes_t[..., 3:]
        self._target = torch.tensor([ep.target for ep in self.episodes], device=self.device)
        n, k = self.num_envs, len(self.objects)
        self._z0 = torch.zeros((n, k), device=self.device)
        self._reach = torch.zeros(n, dtype=torch.bool, device=self.device)
        self._lift = torch.zeros_like(self._reach)
        self._reached_object = torch.full((n,), -1, dtype=torch.long, device=self.device)
        self._lifted_object = torch.full_like(self._reached_object, -1)

    def _initialize_episode(self, env_idx: torch.Tensor, options: dict) -> None:
        idx = [int(i) for i in env_idx]
        for k, obj in enumerate(self.objects):
            pose = torch.tensor(
                [self.episodes[i].objects[k].pose for i in idx],
                dtype=torch.float32,
                device=self.device,
            )
            obj.set_pose(Pose.create_from_pq(pose[:, :3], pose[:, 3:]))
            obj.set_linear_velocity(torch.zeros((len(idx), 3), device=self.device))
            obj.set_angular_velocity(torch.zeros((len(idx), 3), device=self.device))
            self._z0[env_idx, k] = pose[:, 2]
        qpos = torch.tensor(
            [self.episodes[i].robot_qpos for i in idx], dtype=torch.float32, device=self.device
        )
        self.agent.reset(qpos)
        self.agent.robot.set_pose(
            Pose.create_from_pq(torch.zeros((len(idx), 3), device=self.device))
        )
        self._reach[env_idx] = False
        self._lift[env_idx] = False
        self._reached_object[env_idx] = -1
        self._lifted_object[env_idx] = -1

    # Scoring --------------------------------------------------------------------------
    def _object_poses(self) -> tuple[torch.Tensor, torch.Tensor]:
        poses = torch.stack([obj.pose.raw_pose for obj in self.objects], dim=1)
        return poses[..., :3], poses[..., 3:]

    def _grasped(self, mask: torch.Tensor) -> torch.Tensor:
        """(N, K) grasp flags, computed only for objects where ``mask`` has any row set."""
        grasped = torch.zeros_like(mask)
        for k in torch.nonzero(mask.any(dim=0)).flatten().tolist():
            grasped[:, k] = self.agent.is_grasping(self.objects[k])
        return grasped

    def evaluate(self) -> dict:
        th = self.task.thresholds
        pos, quat = self._object_poses()
        dist = box_distance(
            self.agent.tcp_positions(), pos, quat, self._box_center, self._box_half
        ).amin(dim=1)
        rows = torch.arange(self.num_envs, device=self.device)
        within = dist < th.reach
        self._reached_object = latch_first(self._reached_object, first_index(within, dist))
        self._reach |= within[rows, self._target]
        raised = (pos[..., 2] - self._z0) > th.lift
        lifted = raised & self._grasped(raised)
        rise = pos[..., 2] - self._z0
        self._lifted_object = latch_first(self._lifted_object, first_index(lifted, -rise))
        self._lift |= lifted[rows, self._target] & self._reach
        return {
            "success": self._lift.clone(),
            "reach": self._reach.clone(),
            "lift": self._lift.clone(),
            "stage_score": 0.5 * self._reach.float() + 0.5 * self._lift.float(),
            "reached_object": self._reached_object.clone(),
            "lifted_object": self._lifted_object.clone(),
            "target_distance": dist[rows, self._target],
        }

    def _get_obs_extra(self, info: dict) -> dict:
        obs = dict(tcp_pose=self.agent.tcp_state())
        if "state" in self.obs_mode:
            pos, quat = self._object_poses()
            obs["obj_pose"] = torch.cat([pos, quat], dim=-1).flatten(1)
            obs["obj_half_size"] = self._box_half.flatten(1)
        return obs

    # Rewards --------------------------------------------------------------------------
    def compute_dense_reward(self, obs: Any, action: torch.Tensor, info: dict) -> torch.Tensor:
        """Approach the target, grasp it, raise it: 1 + 1 + 2, and 5 on success."""
        rows = torch.arange(self.num_envs, device=self.device)
        pos, _ = self._object_poses()
        rise = pos[rows, self._target, 2] - self._z0[rows, self._target]
        grasped = torch.zeros(self.num_envs, dtype=torch.bool, device=self.device)
        for k in torch.unique(self._target).tolist():
            grasped |= (self._target == k) & self.agent.is_grasping(self.objects[k])
        reward = 1.0 - torch.tanh(10.0 * info["target_distance"])
        reward = reward + grasped.float() * (
            1.0 + 2.0 * (rise / self.task.thresholds.lift).clamp(0, 1)
        )
        return torch.where(info["success"], torch.full_like(reward, 5.0), reward)

    def compute_normalized_dense_reward(self, obs: Any, action: torch.Tensor, info: dict):
        return self.compute_dense_reward(obs, action, info) / 5.0
