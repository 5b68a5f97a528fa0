"""``lerobot-eval`` on the stored held-out episodes: a gymnasium env and LeRobot's env config.

``StoredEpisodesEnv`` is one env over ``stored.StoredEpisodes`` (numpy in and out), as LeRobot's
envs are: observations ``pixels`` (camera -> (H, W, 3) uint8, the LeRobot export's cameras)
and ``agent_pos`` (float32, the robot's joint-space policy interface, the export's
``observation.state``); actions that interface (``pd_joint_pos``: the Franka's 7 joint
positions in rad and its gripper value, the PiperX's 12 joints and 2 grippers). Its
``task_description`` and ``task`` are the episode's instruction, ``_max_episode_steps`` the
horizon, ``render()`` the cameras side by side. An episode ends ``terminated`` at its first
success (``stop_on_success``; else it plays the whole horizon, as ``instructmove eval``) and
``truncated`` at the horizon. ``info["is_success"]`` is success so far, ``info["instructmove"]``
the episode's score so far (``StoredEpisodes.result()``, the row ``instructmove eval`` writes)
and ``info["episode_index"]`` the stored episode; the reward is the stage score's increase,
so an episode's summed reward is its stage score S. ``results=PATH`` appends each finished
episode's row (with its stored index, steps and instruction) to a JSON-lines file.

Which episodes: each reset that starts an episode plays the schedule's next stored episode,
``episode_index``, ``episode_index + stride``, ...; a reset with the first seed the env saw
starts it over (LeRobot seeds each evaluation from ``--seed`` up, so lerobot-train's periodic
evaluations replay the same episodes); past the set's end it wraps round, with a warning.
The stored episode fixes the scene and its seed: a reset's seed picks nothing else.

``InstructMoveEnv`` (defined where lerobot imports; importing this module never needs it) is
LeRobot's ``EnvConfig`` for it, registered as ``--env.type=instructmove``; the distribution in
``integrations/lerobot_env_instructmove`` loads it (lerobot 0.4.4:
``--env.discover_packages_path=lerobot_env_instructmove``; lerobot >= 0.6 imports installed
``lerobot_env_*`` distributions itself). ``--eval.n_episodes=N`` with ``--env.episode_index=K``
evaluates stored episodes K .. K + N - 1, lerobot's episode n being stored episode K + n. Its
``features_map`` names the features as the LeRobot export does (``observation.images.<camera>``,
``observation.state``, ``action``, cameras at ``width`` x ``height``, 224 x 224 by default), so
a policy trained on the export runs without a rename map.

Under lerobot the env holds a finished episode (``hold_after_end``): gymnasium's vector
autoreset (a ``reset()`` with no arguments right after the end) keeps the last observation and
further steps repeat the last transition with reward 0, as lerobot 0.6's
``FreezeAfterEpisodeEnd`` does, so the rollout's own reset starts the next episode and none
is skipped. lerobot 0.4.4 builds every env of a vector env from the same keyword arguments:
one schedule shared by them hands out the episodes in reset order, which needs them in one
process (its default ``SyncVectorEnv``); lerobot >= 0.6 builds them through the config's
``create_envs``, which gives env i of n the episodes ``episode_index + i``, ``+ n``, ...
"""

from __future__ import annotations

import importlib
import importlib.util
import json
import os
import warnings
from collections import OrderedDict
from dataclasses import dataclass, field
from functools import cache, partial
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..obs_formats import SIZE
from ..tasks import TASKS
from .stored import CONTROL_MODE, EpisodeSet, Observation, StoredEpisodes

#: gymnasium ids are ``gym_instructmove/<env id>`` (LeRobot's ``gym_<type>/<task>``).
NAMESPACE = "gym_instructmove"
FPS = 30  # the tasks' control frequency, the LeRobot export's fps
_UNSET: Any = object()  # a reset argument not given (gymnasium's autoreset gives none)


class EpisodeSchedule:
    """The stored episodes an env plays: ``first``, ``first + stride``, ... One schedule
    shared by the envs of a vector env hands the episodes out in the order they reset, in
    the process that made it (a copy in another process would hand out the same ones)."""

    def __init__(self, first: int = 0, stride: int = 1, shared: bool = False) -> None:
        if first < 0 or stride < 1:
            raise ValueError(f"episode_index must be >= 0 and stride >= 1, got {first}, {stride}")
        self.first, self.stride, self.shared = first, stride, shared
        self.next, self.first_seed, self.pid = first, None, os.getpid()

    def claim(self, seed: int | None = None) -> int:
        """The next episode's index (unbounded); the first seed seen again starts over."""
        if self.shared and os.getpid() != self.pid:
            raise RuntimeError(
                "the instructmove envs of a vector env share one episode schedule, which "
                "another process got a copy of (lerobot-eval 0.4.4 with "
                "--eval.use_async_envs=true): every worker would play the same episodes. "
                "Leave use_async_envs off (0.4.4's default) or use lerobot >= 0.6"
            )
        if seed is not None:
            if self.first_seed is None:
                self.first_seed = seed
            elif seed == self.first_seed:
                self.next = self.first
        index, self.next = self.next, self.next + self.stride
        return index


class StoredEpisodesEnv(gym.Env):
    """One stored held-out set as a gymnasium env (see the module's doc)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": FPS}

    def __init__(
        self,
        task: str = "PickCategory-InstructMove",
        robot: str | None = None,
        split: str = "unseen_category",
        condition: str = "normal",
        perturb: str | None = None,
        episode_index: int = 0,
        stride: int = 1,
        width: int = SIZE,
        height: int = SIZE,
        episode_length: int | None = None,
        stop_on_success: bool = True,
        fps: int = FPS,
        render_mode: str | None = "rgb_array",
        render_backend: str | None = None,
        results: str | None = None,
        hold_after_end: bool = False,
        schedule: EpisodeSchedule | None = None,
        set_version: int | None = None,
    ) -> None:
        self.stored = StoredEpisodes(
            EpisodeSet(task, robot, split, condition, perturb, set_version),
            (width, height),
            render_backend,
        )
        self.schedule = schedule or EpisodeSchedule(episode_index, stride)
        horizon = self.stored.max_steps
        self._max_episode_steps = horizon if episode_length is None else int(episode_length)
        if not 0 < self._max_episode_steps <= horizon:
            raise ValueError(
                f"episode_length {episode_length} outside 1..{horizon}, the stored episodes' "
                "horizon (leave it unset to evaluate as the benchmark does)"
            )
        self.stop_on_success, self.hold_after_end = stop_on_success, hold_after_end
        self.results = Path(results) if results else None
        self.render_mode = render_mode
        self.metadata = {**self.metadata, "render_fps": fps}
        first = self.stored.reset(0)  # builds the simulation: the spaces are its own
        self.observation_space = spaces.Dict(
            {
                "pixels": spaces.Dict(  # ordered as ManiSkill orders the cameras
                    OrderedDict(
                        (camera, spaces.Box(0, 255, image.shape, np.uint8))
                        for camera, image in first.images.items()
                    )
                ),
                "agent_pos": spaces.Box(-np.inf, np.inf, first.state.shape, np.float32),
            }
        )
        bounds = self.stored.env.unwrapped.single_action_space
        self.action_space = spaces.Box(bounds.low, bounds.high, bounds.shape, np.float32)
        self.task_description = self.task = ""  # the instruction, once an episode starts
        self.index = -1  # the stored episode playing
        self._obs, self._score, self._end = self._observation(first), 0.0, None

    def reset(self, *, seed: int | None = _UNSET, options: dict | None = _UNSET):
        autoreset = seed is _UNSET and options is _UNSET
        if self.hold_after_end and self._end is not None and autoreset:
            obs, _, _, _, info = self._end  # a vector env's autoreset: hold the episode
            return obs, info
        seed = None if seed is _UNSET else seed
        super().reset(seed=seed)
        claimed = self.schedule.claim(seed)
        self.index = claimed % self.stored.count
        if claimed >= self.stored.count:
            warnings.warn(
                f"episode {claimed} of a schedule from {self.schedule.first} is past the "
                f"{self.stored.count} stored episodes of {self.stored.set.name}: playing "
                f"stored episode {self.index} again",
                stacklevel=2,
            )
        first = self.stored.reset(self.index)
        self.task_description = self.task = first.instruction
        self._obs, self._score, self._end = self._observation(first), 0.0, None
        return self._obs, {"is_success": False, "episode_index": self.index}

    def step(self, action):
        if self._end is not None:
            obs, _, terminated, truncated, info = self._end
            return obs, 0.0, terminated, truncated, info
        if self.index < 0:
            raise RuntimeError("step before reset")
        observation, _ = self.stored.step(np.asarray(action))
        result = self.stored.result()
        reward, self._score = result["stage_score"] - self._score, result["stage_score"]
        success = self.stored.success
        terminated = self.stop_on_success and success
        truncated = not terminated and self.stored.steps >= self._max_episode_steps
        info = {"is_success": success, "episode_index": self.index, "instructmove": result}
        self._obs = self._observation(observation)
        if terminated or truncated:
            self._end = (self._obs, 0.0, terminated, truncated, info)
            self._record(result)
        return self._obs, float(reward), terminated, truncated, info

    def render(self) -> np.ndarray:
        """The cameras of the last observation side by side, (H, W x cameras, 3) uint8."""
        return np.concatenate(list(self._obs["pixels"].values()), axis=1)

    def close(self) -> None:
        self.stored.close()

    @staticmethod
    def _observation(obs: Observation) -> dict:
        return {"pixels": dict(obs.images), "agent_pos": obs.state}

    def _record(self, result: dict) -> None:
        if self.results is None:
            return
        row = {"episode_index": self.index, "steps": self.stored.steps}
        row.update(instruction=self.task_description, **result)
        self.results.parent.mkdir(parents=True, exist_ok=True)
        with self.results.open("a") as f:  # one line per write: envs may share the file
            f.write(json.dumps(row) + "\n")


for _env_id in TASKS:
    if f"{NAMESPACE}/{_env_id}" not in gym.registry:
        gym.register(
            f"{NAMESPACE}/{_env_id}",
            entry_point=f"{__name__}:StoredEpisodesEnv",
            kwargs={"task": _env_id},
            order_enforce=False,  # lerobot reads task_description off the env: no wrapper
            disable_env_checker=True,
        )


@cache
def describe(
    task: str,
    robot: str | None,
    split: str,
    condition: str,
    perturb: str | None,
    set_version: int | None = None,
) -> tuple[str, tuple[str, ...], int]:
    """(robot, cameras, interface dimension) of a stored set, from its env without rendering
    (LeRobot's config declares the features before it makes the env)."""
    from mani_skill.sensors.camera import parse_camera_configs

    from .. import heldout

    config = heldout.evaluator_config(
        task, robot, split, condition, perturbation=perturb, version=set_version
    )
    kwargs = {"obs_mode": "state", "control_mode": CONTROL_MODE, "render_backend": "none"}
    env = gym.make(config.env_id, **config.env_kwargs, **kwargs)
    try:
        u = env.unwrapped
        cameras = [*parse_camera_configs(u._default_sensor_configs)]  # as ManiSkill orders them
        cameras += [c for c in parse_camera_configs(u.agent._sensor_configs) if c not in cameras]
        dim = int(u.single_action_space.shape[0])
        return config.env_kwargs["robot_uids"], tuple(cameras), dim
    finally:
        env.close()


def _lerobot_configs() -> tuple[Any, str | None]:
    """LeRobot's env config module, or None and why not."""
    if importlib.util.find_spec("lerobot") is None:
        return None, (
            "lerobot is not installed: pip install 'lerobot>=0.4.4' "
            "./integrations/lerobot_env_instructmove"
        )
    try:
        return importlib.import_module("lerobot.envs.configs"), None
    except Exception as exc:  # a broken lerobot must not break the gymnasium env
        return None, f"lerobot does not import: {type(exc).__name__}: {exc}"


_configs, WHY_NO_CONFIG = _lerobot_configs()

if _configs is not None:
    from lerobot.configs.types import FeatureType, PolicyFeature
    from lerobot.utils.constants import ACTION, OBS_IMAGES, OBS_STATE

    @_configs.EnvConfig.register_subclass("instructmove")
    @dataclass
    class InstructMoveEnv(_configs.EnvConfig):
        """``--env.type=instructmove``: the stored held-out episodes of ``task`` (an env id)
        for ``robot`` (None: the task's own) on ``split`` under ``condition`` and the
        perturbation levels ``perturb`` (e.g. ``lighting:2,camera:1``), of set version
        ``set_version`` (None: the current; an earlier released one reproduces results on
        it), from ``episode_index`` on, cameras at ``width`` x ``height``. ``episode_length``
        cuts the horizon (None: the stored one, as the benchmark scores); ``results`` is a
        JSON-lines file each finished episode's InstructMove score row is appended to."""

        task: str | None = "PickCategory-InstructMove"
        robot: str | None = None
        split: str = "unseen_category"
        condition: str = "normal"
        perturb: str | None = None
        set_version: int | None = None
        episode_index: int = 0
        width: int = SIZE
        height: int = SIZE
        fps: int = FPS
        episode_length: int | None = None
        stop_on_success: bool = True
        render_mode: str = "rgb_array"
        render_backend: str | None = None
        results: str | None = None
        features: dict[str, PolicyFeature] = field(default_factory=dict)
        features_map: dict[str, str] = field(default_factory=dict)

        def __post_init__(self) -> None:
            if not self.disable_env_checker:
                raise ValueError(
                    "disable_env_checker must stay true: gymnasium's checker wraps the env, "
                    "and lerobot reads the instruction (task_description) off the bare env"
                )
            if self.width < 1 or self.height < 1:
                raise ValueError(f"width and height must be positive: {self.width}x{self.height}")
            robot, cameras, dim = describe(
                self.task, self.robot, self.split, self.condition, self.perturb, self.set_version
            )
            self.robot = robot
            image = (self.height, self.width, 3)
            self.features = {
                ACTION: PolicyFeature(type=FeatureType.ACTION, shape=(dim,)),
                "agent_pos": PolicyFeature(type=FeatureType.STATE, shape=(dim,)),
            }
            self.features_map = {ACTION: ACTION, "agent_pos": OBS_STATE}
            for camera in cameras:
                self.features[f"pixels/{camera}"] = PolicyFeature(
                    type=FeatureType.VISUAL, shape=image
                )
                self.features_map[f"pixels/{camera}"] = f"{OBS_IMAGES}.{camera}"
            self._schedule = EpisodeSchedule(self.episode_index, shared=True)

        @property
        def package_name(self) -> str:
            return __name__  # imported by lerobot when the gym id is not registered

        @property
        def gym_id(self) -> str:
            return f"{NAMESPACE}/{self.task}"

        @property
        def gym_kwargs(self) -> dict:
            """What lerobot 0.4.4 makes each env with (all envs share the schedule)."""
            return {
                "task": self.task,
                "robot": self.robot,
                "split": self.split,
                "condition": self.condition,
                "perturb": self.perturb,
                "set_version": self.set_version,
                "width": self.width,
                "height": self.height,
                "episode_length": self.episode_length,
                "stop_on_success": self.stop_on_success,
                "fps": self.fps,
                "render_mode": self.render_mode,
                "render_backend": self.render_backend,
                "results": self.results,
                "hold_after_end": True,
                "schedule": self._schedule,
            }

        def create_envs(self, n_envs: int, use_async_envs: bool = False) -> dict:
            """lerobot >= 0.6's hook: env i of ``n_envs`` plays ``episode_index + i``, then
            every ``n_envs``-th episode on (in any process)."""
            kwargs = {k: v for k, v in self.gym_kwargs.items() if k != "schedule"}
            makers = [
                partial(StoredEpisodesEnv, **kwargs, episode_index=k, stride=n_envs)
                for k in range(self.episode_index, self.episode_index + n_envs)
            ]
            same_step = gym.vector.AutoresetMode.SAME_STEP
            if use_async_envs and n_envs > 1:  # workers import this module: no fork
                vector = gym.vector.AsyncVectorEnv(
                    makers, autoreset_mode=same_step, context="forkserver"
                )
            else:
                vector = gym.vector.SyncVectorEnv(makers, autoreset_mode=same_step)
            return {self.type: {0: vector}}

else:

    def __getattr__(name: str) -> Any:
        why = f" (LeRobot's env config: {WHY_NO_CONFIG})" if name == "InstructMoveEnv" else ""
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}{why}")
