"""Run inside the LeRobot environment (scripts/lerobot_env.sh): load a dataset with the real
``lerobot.datasets.lerobot_dataset.LeRobotDataset`` and save what it reads of some frames.

    python lerobot_read.py ROOT REPO_ID OUT.npz INDEX [INDEX ...]

OUT.npz holds, per index, the frame's state, action, episode and frame index, its task and
every camera's image (H, W, 3, uint8 from lerobot's float CHW in [0, 1]); plus the dataset's
length, episode count and tasks.
"""

import json
import sys

import numpy as np
from lerobot.datasets.lerobot_dataset import LeRobotDataset

root, repo_id, out, *indices = sys.argv[1:]
dataset = LeRobotDataset(repo_id, root=root)
arrays = {}
tasks = []
for i in map(int, indices):
    item = dataset[i]
    for key, value in item.items():
        if key.startswith("observation.images."):
            image = (value.numpy().transpose(1, 2, 0) * 255.0).round().astype(np.uint8)
            arrays[f"{i}/{key}"] = image
        elif key in ("observation.state", "action", "episode_index", "frame_index", "index"):
            arrays[f"{i}/{key}"] = value.numpy()
    tasks.append(item["task"])
meta = {
    "length": len(dataset),
    "episodes": dataset.num_episodes,
    "tasks": list(dataset.meta.tasks.index),
    "frame_tasks": tasks,
    "fps": dataset.fps,
    "cameras": list(dataset.meta.video_keys),
    "robot_type": dataset.meta.robot_type,
    "episode_columns": list(dataset.meta.episodes.column_names),
}
np.savez(out, meta=json.dumps(meta), **arrays)
