"""Run inside a LeRobot environment (scripts/lerobot_env.sh: lerobot 0.4.4 for v3.0;
scripts/lerobot_v21_env.sh: lerobot 0.3.3 for v2.1): load a dataset with the real
``lerobot.datasets.lerobot_dataset.LeRobotDataset`` and save what it reads of some frames.

    python lerobot_read.py ROOT REPO_ID OUT.npz [--action-chunk N] INDEX [INDEX ...]

With ``--action-chunk N`` the dataset is opened as openpi's data loader opens it: by
``repo_id`` alone under ``$HF_LEROBOT_HOME`` (ROOT is ignored), its metadata first, and
``delta_timestamps`` asking for ``N`` actions from each frame at the dataset's fps.

OUT.npz holds, per index, the frame's state, action (a chunk with ``action_is_pad`` under
``--action-chunk``), episode and frame index, its task and every camera's image (H, W, 3,
uint8 from lerobot's float CHW in [0, 1]); plus the dataset's length, episode count and tasks.
"""

import argparse
import json

import numpy as np
from lerobot.datasets.lerobot_dataset import (
    CODEBASE_VERSION,
    LeRobotDataset,
    LeRobotDatasetMetadata,
)

parser = argparse.ArgumentParser()
parser.add_argument("root")
parser.add_argument("repo_id")
parser.add_argument("out")
parser.add_argument("indices", nargs="+", type=int)
parser.add_argument("--action-chunk", type=int, default=0)
args = parser.parse_args()
if args.action_chunk:
    meta = LeRobotDatasetMetadata(args.repo_id)
    steps = [t / meta.fps for t in range(args.action_chunk)]
    dataset = LeRobotDataset(args.repo_id, delta_timestamps={"action": steps})
else:
    dataset = LeRobotDataset(args.repo_id, root=args.root)
arrays = {}
tasks = []
KEYS = ("observation.state", "action", "action_is_pad", "episode_index", "frame_index", "index")
for i in args.indices:
    item = dataset[i]
    for key, value in item.items():
        if key.startswith("observation.images."):
            image = (value.numpy().transpose(1, 2, 0) * 255.0).round().astype(np.uint8)
            arrays[f"{i}/{key}"] = image
        elif key in KEYS:
            arrays[f"{i}/{key}"] = value.numpy()
    tasks.append(item["task"])
table = dataset.meta.tasks
if isinstance(table, dict):  # v2.1: {task_index: task}
    task_list = [table[k] for k in sorted(table)]
    episode_columns = sorted({k for e in dataset.meta.episodes.values() for k in e})
else:  # v3.0: a frame indexed by task
    task_list = list(table.index)
    episode_columns = list(dataset.meta.episodes.column_names)
meta = {
    "lerobot_format": CODEBASE_VERSION,
    "length": len(dataset),
    "episodes": dataset.num_episodes,
    "tasks": task_list,
    "frame_tasks": tasks,
    "fps": dataset.fps,
    "cameras": list(dataset.meta.video_keys),
    "robot_type": dataset.meta.robot_type,
    "episode_columns": episode_columns,
}
np.savez(args.out, meta=json.dumps(meta), **arrays)
