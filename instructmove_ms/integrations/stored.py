"""One stored held-out episode at a time, numpy in and numpy out: what a harness drives.

An evaluation harness (vla-eval, lerobot-eval) owns the loop: it resets an episode, sends
the observation to its model and steps the action back. ``StoredEpisodes`` is that env for
the held-out sets (``heldout``): ``reset(index)`` builds stored episode ``index`` of (task,
robot, split, condition, perturbation), so every lab runs the same scenes; observations are
the ``instructmove`` format's (the LeRobot export's cameras, the robot's joint-space state,
the instruction) and actions the robot's policy interface (``pd_joint_pos``). ``result()``
scores the episode as ``instructmove eval`` does, from the info of the last step taken:
latched stages, success once, success at that step and the stage score S.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..obs_formats import SIZE, ObservationFormat

CONTROL_MODE = "pd_joint_pos"  # the policy interface's actions


@dataclass(frozen=True)
class EpisodeSet:
    """Which stored episodes: a task's held-out set under a condition and perturbation, of
    set version ``version`` (None: the current one)."""

    env_id: str
    robot: str | None = None  # None: the task's default robot
    split: str = "unseen_category"
    condition: str = "normal"
    perturb: str | None = None  # perturbation levels, e.g. "lighting:2,camera:1"
    version: int | None = None

    @property
    def name(self) -> str:
        """A task name for a harness's reports: env, robot, split and condition."""
        parts = [self.env_id.removesuffix("-InstructMove"), self.robot or "default", self.split]
        if self.condition != "normal":
            parts.append(self.condition)
        if self.perturb:
            parts.append(self.perturb.replace(":", "").replace(",", "+"))
        if self.version is not None:
            parts.append(f"v{self.version}")
        return "/".join(parts)


@dataclass(frozen=True)
class Observation:
    """What the policy reads at a step (one env, numpy)."""

    images: dict[str, np.ndarray]  # camera -> (H, W, 3) uint8
    state: np.ndarray  # float32, the robot's joint-space policy interface
    instruction: str


class StoredEpisodes:
    """The env of one ``EpisodeSet``, made on first use (rgb cameras at ``image_size``,
    (width, height)); ``render_backend`` is ManiSkill's (None: its default)."""

    def __init__(
        self,
        episodes: EpisodeSet,
        image_size: tuple[int, int] = (SIZE, SIZE),
        render_backend: str | None = None,
    ) -> None:
        from .. import heldout

        if min(image_size) < 1:
            raise ValueError(f"image size must be positive, got {image_size}")
        self.set = episodes
        self.config = heldout.evaluator_config(
            episodes.env_id,
            episodes.robot,
            episodes.split,
            episodes.condition,
            perturbation=episodes.perturb,
            version=episodes.version,
        )
        self.image_size, self.render_backend = tuple(image_size), render_backend
        self.env: Any = None
        self.index, self.steps, self.info = -1, 0, {}

    @property
    def count(self) -> int:
        """Stored episodes in the set."""
        return len(self.config.episodes)

    @property
    def max_steps(self) -> int:
        """The episode's horizon (ManiSkill's convention: the policy acts for all of it)."""
        return self.config.max_episode_steps

    @property
    def robot(self) -> str:
        return self.config.env_kwargs["robot_uids"]

    def _make(self) -> Any:
        import gymnasium as gym

        width, height = self.image_size
        kwargs = {
            **self.config.env_kwargs,
            "obs_mode": "rgb",
            "control_mode": CONTROL_MODE,
            "sensor_configs": {"width": width, "height": height},
        }
        if self.render_backend:
            kwargs["render_backend"] = self.render_backend
        env = gym.make(self.config.env_id, **kwargs)
        self.interface = env.unwrapped.agent.policy_interface()
        self.scene_cameras = tuple(env.unwrapped.agent.scene_cameras)
        return env

    def reset(self, index: int) -> Observation:
        """Start stored episode ``index`` (0 .. count - 1)."""
        if not 0 <= index < self.count:
            raise ValueError(
                f"episode index {index} outside the stored set {self.set.name} "
                f"(0..{self.count - 1})"
            )
        if self.env is None:
            self.env = self._make()
        episode = self.config.episodes[index]
        obs, _ = self.env.reset(seed=episode.seed, options={"episode": episode.spec.to_dict()})
        self.index, self.steps, self.info = index, 0, {}
        return self._observation(obs)

    @property
    def action_dim(self) -> int:
        return int(self.env.unwrapped.single_action_space.shape[0])

    def step(self, action: np.ndarray) -> tuple[Observation, dict]:
        """Play one action of the policy interface; (observation, the step's info)."""
        if self.index < 0:
            raise RuntimeError("step before reset")
        action = np.asarray(action, dtype=np.float32).reshape(-1)
        if action.shape != (self.action_dim,):
            raise ValueError(
                f"action of shape {action.shape}; the {self.robot} takes ({self.action_dim},) "
                "joint positions (its policy interface)"
            )
        if not np.isfinite(action).all():
            raise ValueError(f"action holds NaN or inf: {action}")
        obs, _, _, _, info = self.env.step(action[None])
        self.steps, self.info = self.steps + 1, info
        return self._observation(obs), info

    @property
    def done(self) -> bool:
        return self.steps >= self.max_steps

    @property
    def success(self) -> bool:
        """Whether the episode has succeeded so far (success once)."""
        return bool(self.info and bool(self.info["success"].reshape(-1)[0]))

    def result(self) -> dict:
        """The episode's score so far, as ``instructmove eval`` writes its rows."""
        from ..metrics import EpisodeResult, score_episode

        u = self.env.unwrapped
        spec = self.config.episodes[self.index].spec
        if not self.info:  # no step taken
            return EpisodeResult.failed(spec, u.task.stages).to_dict()
        return score_episode(spec, self.info, u.task.stages, u.catalog_of(spec)).to_dict()

    def _observation(self, obs: dict) -> Observation:
        return Observation(
            images=ObservationFormat.images(obs),
            state=ObservationFormat.state(obs, self.interface),
            instruction=self.env.unwrapped.get_language_instruction()[0],
        )

    def close(self) -> None:
        if self.env is not None:
            self.env.close()
            self.env = None
