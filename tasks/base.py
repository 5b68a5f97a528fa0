"""The shared InstructMove engine: every family is this env plus its declarative TaskSpec.

The engine builds the episode's scene, tracks the family's stages and computes the shared
reward for reaching, grasping and lifting the object to move. A family whose task goes on
after the lift (PlaceA2B) overrides the goal hooks: ``_watched`` (objects whose grasp is
checked), ``_goal_conditions`` (its stages after lift), ``_goal_reward`` and
``goal_reward`` (what they add to the dense reward).
"""

from __future__ import annotations

import dataclasses
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

from instructmove_ms.assets import (
    DEFAULT_SNAPSHOT,
    load_snapshot,
    photometry,  # noqa: F401  (renders colours not stored)
)
from instructmove_ms.assets.catalog import Catalog
from instructmove_ms.assets.sapien_builder import actor_builder
from instructmove_ms.composer import compose, rephrase, variant
from instructmove_ms.episode import CONDITIONS, EpisodeSpec, actor_name
from instructmove_ms.family import TaskSpec
from instructmove_ms.gpu_physics import check_gpu_physics, uses_gpu_physics
from instructmove_ms.perturbation import Context, parse_levels, perturb
from instructmove_ms.sampler import SAMPLER, SAMPLERS
from instructmove_ms.splits import SPLITS
from instructmove_ms.validation import check_choice, check_range
from instructmove_ms.verify import certify, verify

from .measure import Measured, SceneReader
from .scene import build_room
from .scenery import backdrop, light, move_cameras
from .stages import StageTracker, box_distance, select


class InstructMoveEnv(BaseEnv):
    """Shared engine; subclasses set ``task``. See each family for its docstring."""

    task: ClassVar[TaskSpec]
    SUPPORTED_REWARD_MODES = ("dense", "normalized_dense", "sparse", "none")
    #: Dense reward for approaching (1), grasping (1) and raising (2) the object, plus 1 at
    #: success; ``goal_reward`` is what a family's goal after the lift adds.
    PICK_REWARD: ClassVar[float] = 5.0
    goal_reward: ClassVar[float] = 0.0

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
        condition: str = "normal",
        perturbation: dict | str | None = None,
        sampler: int = SAMPLER,
        **kwargs,
    ):
        robot_uids = robot_uids or self.task.default_robot
        check_choice("robot_uids", robot_uids, self.task.supported_robots)
        if uses_gpu_physics(kwargs.get("sim_backend", "auto"), kwargs.get("num_envs", 1)):
            check_gpu_physics()  # before SAPIEN reaches for the network
        check_choice("split", split, SPLITS)
        check_choice("condition", condition, CONDITIONS)
        check_choice("sampler", sampler, SAMPLERS)
        if num_distractors is None:
            num_distractors = self.task.role("distractor").count
        check_range("num_distractors", num_distractors, *self.task.count_limits["distractor"])
        if not robot_init_qpos_noise >= 0:
            raise ValueError(f"robot_init_qpos_noise must be >= 0, got {robot_init_qpos_noise!r}")
        self.split = split
        self.sampler = sampler
        self.condition = condition
        self.perturbation = parse_levels(perturbation)
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
        self._now: Measured | None = None
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
        """ManiSkill's reset; ``options={"episode": spec}`` rebuilds that episode exactly
        once the verifier passes it (``verify.VerificationError`` otherwise);
        ``"verify": False`` beside it builds a hand-made scene the verifier would refuse
        (one object for a physics test), its certificate saying ``unverified``.

        ``spec`` is an :class:`EpisodeSpec`, its dict, or a list of either (one per
        sub-scene). Pass the dict form when recording so that the reset kwargs stay JSON.
        """
        options = dict(options or {})
        if "condition" in options:
            check_choice("condition", options["condition"], CONDITIONS)
            self.condition = options.pop("condition")
            options["reconfigure"] = True
        if "perturbation" in options:
            self.perturbation = parse_levels(options.pop("perturbation"))
            options["reconfigure"] = True
        if "episode" in options:
            checked = options.pop("verify", True)
            self._requested = self._coerce_episodes(options.pop("episode"), checked)
            options["reconfigure"] = True
        return super().reset(seed=seed, options=options)

    def _coerce_episodes(self, value, checked: bool = True) -> list[EpisodeSpec]:
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
            catalog = load_snapshot(spec.snapshot)  # raises with the unknown snapshot
            for obj in spec.objects:
                catalog[obj.uuid]  # raises with the unknown uuid
        if len({len(s.objects) for s in specs}) != 1:
            raise ValueError("all sub-scenes must hold the same number of objects")
        if not checked:  # a hand-made scene for a physics test: marked as such
            return [dataclasses.replace(s, certificate={"unverified": True}) for s in specs]
        return [self.certified(s) for s in specs]

    def sample_episode(
        self, seed: int, condition: str | None = None, perturbation=None
    ) -> EpisodeSpec:
        """The episode of ``seed`` under ``condition`` and ``perturbation`` (default: the
        env's); see ``composer.compose`` and ``perturbation.perturb``."""
        spec = compose(
            self.task,
            self._roles,
            self.catalog,
            self.split,
            seed,
            self.robot_uids,
            lambda rng: self.agent.sample_init_qpos(rng, self.robot_init_qpos_noise),
            self.certified,
            condition or self.condition,
            self.agent.workspace,
            self.sampler,
        )
        return self.perturbed(spec, self.perturbation if perturbation is None else perturbation)

    def under_condition(self, spec: EpisodeSpec, condition: str) -> EpisodeSpec:
        """The normal episode ``spec`` (stored or sampled) under ``condition``: the same
        scene, the condition's instruction and goal (see ``composer.variant``)."""
        return variant(self.task, spec, self.catalog_of(spec), condition, self.certified)

    def certified(self, spec: EpisodeSpec) -> EpisodeSpec:
        """``spec`` with the verifier's certificate for this env's robot, judged on the
        snapshot the spec names; a ``verify.VerificationError`` names its problems (see
        ``verify.certify``)."""
        return certify(spec, self.catalog_of(spec), self.task, self.agent.gripper.max_width)

    def catalog_of(self, spec: EpisodeSpec) -> Catalog:
        """The snapshot ``spec`` was made on (a stored episode names its own, and plays on
        it in an env made on any snapshot)."""
        return self.catalog if spec.snapshot == self.catalog.name else load_snapshot(spec.snapshot)

    def perturbed(self, spec: EpisodeSpec, levels) -> EpisodeSpec:
        """``spec`` at the perturbation ``levels`` (``{axis: level}`` or ``"axis:level,..."``),
        certified again; a spec that carries a perturbation already is returned as it is
        stored."""
        levels = parse_levels(levels)
        if not levels or spec.perturbation:
            return spec
        unmeasured = dataclasses.replace(spec, certificate={})  # the scene's look changes
        return self.certified(perturb(unmeasured, levels, self._perturbation_context(spec)))

    def _perturbation_context(self, spec: EpisodeSpec) -> Context:
        names = [j.name for j in self.agent.robot.get_active_joints()]
        opening = self.agent.gripper.max_width
        catalog = self.catalog_of(spec)
        return Context(
            task=self.task,
            catalog=catalog,
            arm=tuple(names.index(n) for n in self.agent.arm_joint_names),
            limits=self.agent.robot.get_qlimits()[0].cpu().numpy(),
            cameras=tuple(c.uid for c in self.agent._sensor_configs),
            workspace=self.agent.workspace,
            problems=lambda s: verify(s, catalog, self.task, opening),
            rephrase=lambda s, rng, unseen, synonyms: rephrase(
                self.task, catalog, s, rng, unseen, synonyms
            ),
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
            requested, self._requested = self._requested, None
            self.episodes = [self.perturbed(ep, self.perturbation) for ep in requested]
        else:
            self.episodes = [self.sample_episode(int(s)) for s in self._episode_seed]
        floor = build_room(self.scene, self._perturbed_values("table"))
        self.agent.mount(self.scene.actors["table"])
        backdrop(self.scene, self._perturbed_values("background"), floor)
        self.objects = []
        boxes = []
        for k in range(len(self.episodes[0].objects)):
            parts = []
            for i, ep in enumerate(self.episodes):
                obj = ep.objects[k]
                builder = actor_builder(self.scene, self.catalog_of(ep)[obj.uuid])
                builder.set_scene_idxs([i])
                builder.initial_pose = sapien.Pose(p=obj.pose[:3], q=obj.pose[3:])
                actor = builder.build(name=f"{actor_name(k)}_{i}")
                self.remove_from_state_dict_registry(actor)
                parts.append(actor)
            merged = Actor.merge(parts, name=actor_name(k))
            self.add_to_state_dict_registry(merged)
            self.objects.append(merged)
        for ep in self.episodes:
            lo_hi = [self.catalog_of(ep)[o.uuid].bounds for o in ep.objects]
            boxes.append([np.concatenate([(lo + hi) / 2, (hi - lo) / 2]) for lo, hi in lo_hi])
        boxes_t = torch.tensor(np.asarray(boxes), dtype=torch.float32, device=self.device)
        self._box_center, self._box_half = boxes_t[..., :3], boxes_t[..., 3:]
        self._target = torch.tensor([ep.target for ep in self.episodes], device=self.device)
        self._no_target = self._target < 0
        self._target_column = self._target.clamp(min=0)[:, None]  # (N, 1) for gathers
        self._target_pair = self._target_column[:, :, None].expand(-1, 2, 1)
        self._has_target = ~self._no_target[:, None]
        # (N, 1, K): the candidate objects, the only ones whose reach or lift a policy chose
        # (a receptacle or a reference object touched on the way is no choice)
        candidates = torch.zeros((self.num_envs, 1, len(self.objects)), dtype=torch.bool)
        for i, ep in enumerate(self.episodes):
            candidates[i, 0, list(ep.candidates)] = True
        self._candidates = candidates.to(self.device)
        self._target_rows = [  # each object that is a target: the sub-scenes where it is
            (k, self._target_column[:, 0] == k)
            for k in sorted({max(ep.target, 0) for ep in self.episodes})
        ]
        self._half_flat = self._box_half.flatten(1)
        self._z0 = torch.zeros((self.num_envs, len(self.objects)), device=self.device)
        self._stages = StageTracker(self.task.stages.names, self.num_envs, self.device)
        fingers = [link for pair in self.agent.finger_pairs for link, _ in pair]
        self._reader = SceneReader(self.objects, self.agent.tcp_links, fingers)

    def _perturbed_values(self, axis: str) -> list[dict | None]:
        """Each sub-scene's drawn values of a perturbation axis (None where not perturbed)."""
        return [ep.perturbation.get(axis) for ep in self.episodes]

    def _load_lighting(self, options: dict) -> None:
        if not light(self.scene, self._perturbed_values("lighting"), self.enable_shadow):
            super()._load_lighting(options)

    def _setup_sensors(self, options: dict) -> None:
        super()._setup_sensors(options)
        move_cameras(self._sensors, self._perturbed_values("camera"))

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
        self._stages.reset(env_idx)
        self._now = None

    # Scoring --------------------------------------------------------------------------
    def _after_control_step(self) -> None:
        self._now = None  # the scene moved: the next reader measures it again

    def _measured(self) -> Measured:
        """This step's measurements, read once (``evaluate`` reads them; the reward and
        the observation that follow it in a step share them)."""
        if self._now is None:
            self._now = self._reader.measure()
        return self._now

    def _of_target(self, values: torch.Tensor) -> torch.Tensor:
        """Each sub-scene's entry of ``values`` (N, K, ...) for its target object."""
        return select(values, self._target_column)

    def _grasp(self, now: Measured, k: int) -> torch.Tensor:
        """(N,) whether the robot grasps object ``k``, checked once per step."""
        if k not in now.grasped:
            now.grasped[k] = self.agent.grasping(self.objects[k], now.contacts)
        return now.grasped[k]

    def _grasped(self, now: Measured, mask: torch.Tensor) -> torch.Tensor:
        """(N, K) grasp flags, checked only for objects where ``mask`` has any row set."""
        grasped = torch.zeros_like(mask)
        if not bool(mask.any()):
            return grasped
        for k in torch.nonzero(mask.any(dim=0)).flatten().tolist():
            grasped[:, k] = self._grasp(now, k)
        return grasped

    def _target_grasped(self, now: Measured) -> torch.Tensor:
        """(N,) whether each sub-scene's target is grasped."""
        flags = [self._grasp(now, k) & rows for k, rows in self._target_rows]
        return flags[0] if len(flags) == 1 else torch.stack(flags).any(dim=0)

    def _watched(self, raised: torch.Tensor) -> torch.Tensor:
        """(N, K) objects whose grasp is checked this step: the raised ones."""
        return raised

    def _goal_conditions(self, now: Measured, grasped: torch.Tensor) -> list[torch.Tensor]:
        """(N,) conditions of the family's stages after reach and lift (none here), from
        this step's measurements and the objects' grasp flags (N, K)."""
        return []

    def _goal_reward(
        self,
        reward: torch.Tensor,
        info: dict,
        now: Measured,
        grasped: torch.Tensor,
        lifted: torch.Tensor,
    ) -> torch.Tensor:
        """``reward`` plus the family's terms for its goal after the lift (none here);
        ``grasped`` and ``lifted`` are the target's grasp flag and lift fraction."""
        return reward

    def evaluate(self) -> dict:
        th, schema = self.task.thresholds, self.task.stages
        self._now = now = self._reader.measure()  # the step's one read
        pos = now.pos
        dist = box_distance(now.tcp[..., :3], pos, now.quat, self._box_center, self._box_half).amin(
            dim=1
        )
        rise = pos[..., 2] - self._z0
        raised = rise > th.lift
        grasped = self._grasped(now, self._watched(raised))
        within, lifted = dist < th.reach, raised & grasped
        # reach and lift of the target, then the family's goal stages: (N, stages)
        events = torch.stack((within, lifted), dim=1)
        conditions = events.gather(2, self._target_pair).squeeze(2) & self._has_target
        goal = self._goal_conditions(now, grasped)
        if goal:
            conditions = torch.cat((conditions, torch.stack(goal, dim=1)), dim=1)
        stages = self._stages
        stages.update(dist, events & self._candidates, rise, conditions)
        f, names, first = stages.flags, schema.names, stages.first
        success = names.index(schema.success)
        seen = first >= 0
        info = {
            "reach": f[:, 0],
            "lift": f[:, 1],
            "reached_object": first[:, 0],
            "lifted_object": first[:, 1],
            "any_reach": seen[:, 0],
            "any_lift": seen[:, 1],
            "target_distance": self._of_target(dist).masked_fill(self._no_target, torch.inf),
        }
        info.update({name: f[:, i] for i, name in enumerate(names) if name not in info})
        info.update(
            success=f[:, success],
            # the success stage's own condition at this step, not latched: success at the end
            success_now=conditions[:, success],
            stage_score=schema.score(f),
        )
        return info

    def _get_obs_extra(self, info: dict) -> dict:
        now = self._measured()
        obs = dict(tcp_pose=now.tcp.flatten(1))
        if "state" in self.obs_mode:
            obs["obj_pose"] = now.objects.flatten(1)
            obs["obj_half_size"] = self._half_flat
        return obs

    # Rewards --------------------------------------------------------------------------
    def compute_dense_reward(self, obs: Any, action: torch.Tensor, info: dict) -> torch.Tensor:
        """Staged: approach the target (1), grasp it (1), raise it (2), then the family's
        goal terms (``_goal_reward``). Success gives the maximum; episodes without a target
        get 0."""
        now = self._measured()
        rise = self._of_target(now.pos[..., 2] - self._z0)
        grasped = self._target_grasped(now)
        reward = 1.0 - torch.tanh(10.0 * info["target_distance"])  # 0 at an infinite distance
        lifted = (rise / self.task.thresholds.lift).clamp(0, 1)
        reward = reward + grasped.float() * (1.0 + 2.0 * lifted)
        reward = self._goal_reward(reward, info, now, grasped, lifted)
        reward = reward.masked_fill(self._no_target, 0.0)
        return reward.masked_fill(info["success"], self._max_reward)

    @property
    def _max_reward(self) -> float:
        return self.PICK_REWARD + self.goal_reward

    def compute_normalized_dense_reward(self, obs: Any, action: torch.Tensor, info: dict):
        return self.compute_dense_reward(obs, action, info) / self._max_reward
