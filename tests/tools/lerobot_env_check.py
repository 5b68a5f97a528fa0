"""Run in the LeRobot environment (scripts/lerobot_env.sh) with ``lerobot_bridge`` on its
``PYTHONPATH``: LeRobot's own code on the ``instructmove`` env, for tests/test_lerobot_eval.py.

    python lerobot_env_check.py OUT --actions A.npy --policy-args FLAGS --policy-features F
        [--task T --robot R --split S --width W --height H]

First saves, in ``OUT/policy``, a randomly initialised policy (``FLAGS``: a JSON list of
lerobot's ``--policy.*`` flags) with the features ``F`` (JSON: name -> [type, shape], as a
checkpoint trained on our LeRobot export declares them) and its processors, then writes
``OUT/policy.ready``: a ``lerobot-eval`` of it may start. Then loads the plugin as
``--env.discover_packages_path=lerobot_env_instructmove`` does, parses
``--env.type=instructmove`` as lerobot's configs do and makes the vector env with lerobot's
``make_env``. ``OUT/report.json`` holds the policy features lerobot derives from the config,
the first observation as ``preprocess_observation`` and ``add_envs_task`` hand it to a
policy, the rollout of the actions in ``A.npy`` (stored episode 0) through lerobot's
``rollout`` (steps, successes and rewards counted as ``eval_policy`` counts them) and the
stored episodes each env of the config's ``create_envs`` (lerobot >= 0.6's hook) plays in
three rollouts. The env's own score rows go to ``OUT/rollout.jsonl``.
"""

import argparse
import json
from dataclasses import dataclass
from pathlib import Path

import draccus
import numpy as np
import torch
from lerobot.configs.parser import load_plugin
from lerobot.configs.policies import PreTrainedConfig
from lerobot.configs.types import FeatureType, PolicyFeature
from lerobot.envs.configs import EnvConfig
from lerobot.envs.factory import make_env, make_env_pre_post_processors
from lerobot.envs.utils import add_envs_task, env_to_policy_features, preprocess_observation
from lerobot.policies.factory import get_policy_class, make_pre_post_processors
from lerobot.processor import PolicyProcessorPipeline
from lerobot.processor.converters import policy_action_to_transition, transition_to_policy_action
from lerobot.scripts.lerobot_eval import rollout
from torch import nn

parser = argparse.ArgumentParser()
parser.add_argument("out", type=Path)
parser.add_argument("--actions", type=Path, required=True)
parser.add_argument("--policy-args", required=True)
parser.add_argument("--policy-features", required=True)
parser.add_argument("--task", default="PickCategory-InstructMove")
parser.add_argument("--robot", default="franka")
parser.add_argument("--split", default="unseen_category")
parser.add_argument("--width", type=int, default=128)
parser.add_argument("--height", type=int, default=96)
args = parser.parse_args()
SEED = 1000  # lerobot-eval's default --seed: episode n is seeded SEED + n


@dataclass
class Flags:
    """``--env.*`` and ``--policy.*`` as lerobot's pipeline configs parse them."""

    env: EnvConfig | None = None
    policy: PreTrainedConfig | None = None


class Replay(nn.Module):
    """Plays recorded actions, one per ``select_action`` (what lerobot asks a policy)."""

    def __init__(self, actions: np.ndarray) -> None:
        super().__init__()
        self.actions, self.t = torch.from_numpy(actions), 0

    def reset(self) -> None:
        self.t = 0

    def select_action(self, batch: dict) -> torch.Tensor:
        action = self.actions[min(self.t, len(self.actions) - 1)][None]
        self.t += 1
        return action


def env_config(*extra: str) -> EnvConfig:
    argv = ["--type=instructmove", f"--task={args.task}", f"--robot={args.robot}"]
    argv += [f"--split={args.split}", f"--width={args.width}", f"--height={args.height}"]
    return draccus.parse(Flags, args=[f"--env.{a[2:]}" for a in (*argv, *extra)]).env


# The checkpoint: a random policy with the features of one trained on our export.
args.out.mkdir(parents=True, exist_ok=True)
policy_cfg = draccus.parse(Flags, args=json.loads(args.policy_args)).policy
features = {
    name: PolicyFeature(type=FeatureType[kind], shape=tuple(shape))
    for name, (kind, shape) in json.loads(args.policy_features).items()
}
policy_cfg.output_features = {k: v for k, v in features.items() if v.type is FeatureType.ACTION}
policy_cfg.input_features = {k: v for k, v in features.items() if v.type is not FeatureType.ACTION}
torch.manual_seed(0)
get_policy_class(policy_cfg.type)(policy_cfg).save_pretrained(args.out / "policy")
for pipeline in make_pre_post_processors(policy_cfg):
    pipeline.save_pretrained(args.out / "policy")
(args.out / "policy.ready").touch()

load_plugin("lerobot_env_instructmove")
from instructmove_ms.integrations.lerobot_env import InstructMoveEnv  # noqa: E402

report: dict = {"registered": EnvConfig.get_choice_class("instructmove") is InstructMoveEnv}
cfg = env_config(f"--results={args.out / 'rollout.jsonl'}")
report["features"] = {
    k: [v.type.name, list(v.shape)] for k, v in env_to_policy_features(cfg).items()
}
vec = make_env(cfg, n_envs=1)[cfg.type][0]
report["env"] = {"class": type(vec.envs[0]).__name__, "max_steps": vec.call("_max_episode_steps")}
obs, _ = vec.reset(seed=[SEED])
batch = add_envs_task(vec, preprocess_observation(obs))
report["observation"] = {
    k: [str(v.dtype).removeprefix("torch."), list(v.shape)] if hasattr(v, "shape") else v
    for k, v in batch.items()
}

# The recorded actions through lerobot's rollout, counted as eval_policy counts an episode.
env_pre, env_post = make_env_pre_post_processors(cfg, policy_cfg)
pre = PolicyProcessorPipeline(steps=[])
post = PolicyProcessorPipeline(
    steps=[], to_transition=policy_action_to_transition, to_output=transition_to_policy_action
)
data = rollout(vec, Replay(np.load(args.actions)), env_pre, env_post, pre, post, seeds=[SEED])
done_index = int(torch.argmax(data["done"][0].to(int)))
mask = torch.arange(data["done"].shape[1]) <= done_index + 1
successes = data["success"][0].tolist()
report["rollout"] = {
    "steps": data["done"].shape[1],
    "done_index": done_index,
    "success": bool((data["success"][0] * mask).any()),
    "first_success": successes.index(True) + 1 if True in successes else None,
    "sum_reward": float((data["reward"][0] * mask).sum()),
    "played": vec.envs[0].index,
}
vec.close()

# lerobot >= 0.6 makes the envs through the config's create_envs: env i of 2 plays
# episode_index + i, + 2, ...; the first seeds again start over.
short = env_config("--episode_length=1", "--episode_index=5")
vec = short.create_envs(n_envs=2)[short.type][0]
played = []
for seeds in ([SEED, SEED + 1], [SEED + 2, SEED + 3], [SEED, SEED + 1]):
    obs, _ = vec.reset(seed=seeds)
    played.append([env.index for env in vec.envs])
    for _ in range(2):  # the second steps the held episodes
        obs, *_ = vec.step(obs["agent_pos"])
    assert [env.index for env in vec.envs] == played[-1], "an autoreset started an episode"
vec.close()
report["create_envs"] = played
(args.out / "report.json").write_text(json.dumps(report, indent=1))
