"""Run inside the LeRobot environment (scripts/lerobot_env.sh): whether a checkpoint learned.
The policy's own training loss on a fixed batch of a dataset (every ``--every``-th frame, in
eval mode, no gradients), for the checkpoint and for the same policy freshly initialised:

    python lerobot_fixed_batch_loss.py CHECKPOINT ROOT REPO_ID [--every N]

prints ``{"initial": L0, "trained": L1, "frames": N}`` as JSON. The logged loss of a batch of 8
is noise around its mean; this one is the same batch before and after, so its ratio measures
what was learned, on any CPU's kernels.
"""

import argparse
import json

import torch
from lerobot.configs.policies import PreTrainedConfig
from lerobot.datasets.factory import resolve_delta_timestamps
from lerobot.datasets.lerobot_dataset import LeRobotDataset, LeRobotDatasetMetadata
from lerobot.policies.factory import get_policy_class, make_pre_post_processors

parser = argparse.ArgumentParser()
parser.add_argument("checkpoint")
parser.add_argument("root")
parser.add_argument("repo_id")
parser.add_argument("--every", type=int, default=4)
args = parser.parse_args()

config = PreTrainedConfig.from_pretrained(args.checkpoint)
config.device = "cpu"
meta = LeRobotDatasetMetadata(args.repo_id, root=args.root)
dataset = LeRobotDataset(
    args.repo_id, root=args.root, delta_timestamps=resolve_delta_timestamps(config, meta)
)
frames = [dataset[i] for i in range(0, len(dataset), args.every)]
batch = torch.utils.data.default_collate(
    [{k: v for k, v in frame.items() if isinstance(v, torch.Tensor)} for frame in frames]
)
pre, _ = make_pre_post_processors(config, pretrained_path=args.checkpoint)
batch = pre(batch)
policy_class = get_policy_class(config.type)
torch.manual_seed(0)
losses = {}
for name, policy in (
    ("initial", policy_class(config)),
    ("trained", policy_class.from_pretrained(args.checkpoint)),
):
    policy.eval()
    with torch.no_grad():
        losses[name] = float(policy.forward(batch)[0])
print(json.dumps({**losses, "frames": len(frames)}))
