"""InstructMove as a vla-eval benchmark: ``benchmark: "instructmove_ms.integrations.vla_eval:
InstructMoveBenchmark"`` in a vla-eval config (examples: ``integrations/vla_eval/*.yaml``).

Each vla-eval task is one stored held-out set (task, robot, split, condition, perturbation;
see ``stored``) and ``episode_idx`` picks the stored episode, so every lab runs the same
scenes: ``episodes_per_task: N`` runs the set's first N. The model server gets
``images`` (camera -> H x W x 3 uint8, the LeRobot export's cameras; ``send_wrist_image:
false`` keeps only the scene cameras), ``state`` (float32, the robot's joint-space policy
interface; left out with ``send_state: false``) and ``task_description`` (the instruction),
and answers ``actions`` in that interface (``pd_joint_pos``: the Franka's 7 joints and
gripper, the PiperX's 12 joints and 2 grippers). An episode runs its whole horizon
(ManiSkill's convention, as ``instructmove eval``; ``stop_on_success: true`` ends it at the
first success) and is scored as ``instructmove eval`` scores it: the metrics hold
``success`` (once), ``success_at_end``, ``stage_score`` (S) and each stage's flag, and
vla-eval's summary averages them.

``render: cpu`` renders with SAPIEN's CPU Vulkan device (Mesa's lavapipe), chosen per env,
so it needs no environment set before SAPIEN is imported.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from . import require

_base = require("vla_eval.benchmarks.base", "vla-eval", "the vla-eval benchmark")
_specs = require("vla_eval.specs", "vla-eval", "the vla-eval benchmark")

from .. import heldout  # noqa: E402
from ..episode import CONDITIONS  # noqa: E402  (after the optional import's check)
from ..obs_formats import SIZE  # noqa: E402
from ..splits import EVAL_SPLITS  # noqa: E402
from ..tasks import TASKS  # noqa: E402
from ..validation import check_choice  # noqa: E402
from .stored import EpisodeSet, StoredEpisodes  # noqa: E402

#: vla-eval's ``render`` modes -> ManiSkill's render backend (None: its default device)
RENDER_BACKENDS = {"gpu": None, "cpu": "cpu"}
#: The metrics vla-eval averages, beyond the stage flags of the tasks' families.
SCORES = ("success", "success_at_end", "stage_score")


class InstructMoveBenchmark(_base.StepBenchmark):
    """The held-out sets of ``tasks`` (env ids; default every family) for ``robot``
    (default each task's own) on ``split``, under each of ``conditions`` (default
    ``normal``; ``["all"]`` for the five), perturbed at ``perturb`` (e.g. ``lighting:2``),
    from the stored sets of ``set_version`` (default the current; an earlier released one
    reproduces results on it)."""

    render_backends: ClassVar[frozenset[str]] = frozenset(RENDER_BACKENDS)
    render_backend: ClassVar[str | None] = None

    @classmethod
    def configure_render(cls, mode: str) -> dict[str, str]:
        check_choice("render mode", mode, RENDER_BACKENDS)
        cls.render_backend = RENDER_BACKENDS[mode]
        return {}

    def __init__(
        self,
        tasks: list[str] | None = None,
        robot: str | None = None,
        split: str = "unseen_category",
        conditions: list[str] | None = None,
        perturb: str | None = None,
        image_size: list[int] | tuple[int, int] = (SIZE, SIZE),
        send_state: bool = True,
        send_wrist_image: bool = True,
        stop_on_success: bool = False,
        set_version: int | None = None,
    ) -> None:
        super().__init__()
        conditions = list(CONDITIONS) if conditions in (["all"], "all") else conditions
        check_choice("split", split, EVAL_SPLITS)
        for env_id in tasks or ():
            check_choice("task", env_id, TASKS)
        for condition in conditions or ():
            check_choice("condition", condition, CONDITIONS)
        if set_version is not None:
            check_choice("set version", set_version, heldout.SET_VERSIONS)
        self.sets = [
            EpisodeSet(
                env_id,
                robot or TASKS[env_id].default_robot,
                split,
                condition,
                perturb,
                set_version,
            )
            for env_id in tasks or list(TASKS)
            for condition in conditions or ["normal"]
        ]
        self.image_size = (int(image_size[0]), int(image_size[1]))
        self.send_state, self.send_wrist_image = send_state, send_wrist_image
        self.stop_on_success = stop_on_success
        self.envs: dict[str, StoredEpisodes] = {}
        self.current: StoredEpisodes | None = None

    def get_tasks(self) -> list[dict]:
        return [
            {
                "name": s.name,
                "env_id": s.env_id,
                "robot": s.robot,
                "split": s.split,
                "condition": s.condition,
                **({"perturb": s.perturb} if s.perturb else {}),
                **({"set_version": s.version} if s.version is not None else {}),
            }
            for s in self.sets
        ]

    def _episodes(self, name: str) -> StoredEpisodes:
        """The env of task ``name`` (one open at a time: a robot's scene is large)."""
        if name not in self.envs:
            for other in self.envs.values():
                other.close()
            s = next(s for s in self.sets if s.name == name)
            self.envs = {name: StoredEpisodes(s, self.image_size, self.render_backend)}
        return self.envs[name]

    def reset(self, task: dict) -> Any:
        self.current = self._episodes(task["name"])
        return self.current.reset(int(task.get("episode_idx", 0)))

    def step(self, action: dict) -> Any:
        actions = np.asarray(action.get("actions", action.get("action")), dtype=np.float32)
        if actions.ndim > 1 and actions.shape[0] != 1:
            raise ValueError(
                f"got a chunk of {actions.shape[0]} actions; one action per step is played "
                "(give the model server a chunk_size so that it sends them one at a time)"
            )
        obs, _ = self.current.step(actions.reshape(-1))
        success = self.current.success
        done = self.current.done or (self.stop_on_success and success)
        return _base.StepResult(obs=obs, reward=float(success), done=done, info={})

    def make_obs(self, raw_obs: Any, task: dict) -> dict:
        images = raw_obs.images
        if not self.send_wrist_image:
            images = {c: images[c] for c in self.current.scene_cameras}
        obs: dict[str, Any] = {"images": images, "task_description": raw_obs.instruction}
        if self.send_state:
            obs["state"] = raw_obs.state
        return obs

    def get_step_result(self, step_result: Any) -> dict:
        result = self.current.result()
        return {**{k: result[k] for k in SCORES}, **result["stages"], "choice": result["choice"]}

    def get_metric_keys(self) -> dict[str, str]:
        stages = {name for s in self.sets for name in TASKS[s.env_id].stages.names}
        return dict.fromkeys([*SCORES, *sorted(stages)], "mean")

    def get_metadata(self) -> dict[str, Any]:
        horizon = max(TASKS[s.env_id].max_episode_steps for s in self.sets)
        return {"max_steps": horizon, "max_episodes_per_task": self._stored_count()}

    def _stored_count(self) -> int:
        from ..heldout import load_set

        return min(len(load_set(s.env_id, s.robot, s.split, version=s.version)) for s in self.sets)

    def get_action_spec(self) -> dict:
        return {"joints": _specs.DimSpec("joints", 0, "joint_pos_absolute")}

    def get_observation_spec(self) -> dict:
        spec = {"images": _specs.IMAGE_RGB, "language": _specs.LANGUAGE}
        if self.send_state:
            spec["state"] = _specs.STATE_JOINT
        return spec

    def get_hold_action(self, last_action: dict | None) -> dict:
        """Live mode: hold the last joint targets, or before any the joints where they are
        (the state is in the actions' units)."""
        return last_action or {"actions": self._last_result.obs.state}

    def cleanup(self) -> None:
        for env in self.envs.values():
            env.close()
        self.envs, self.current = {}, None
