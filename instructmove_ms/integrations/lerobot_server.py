"""Serve a LeRobot checkpoint with openpi's websocket protocol, for ``instructmove eval
--policy ws://HOST:PORT`` (the ``instructmove`` observation format: our LeRobot export's
keys).

A standalone program: it runs in an environment with lerobot (>= 0.4) and openpi's server,
without InstructMove or a simulator (``scripts/lerobot_env.sh`` builds one)::

    python lerobot_server.py --checkpoint OUT/checkpoints/last/pretrained_model --port 8000

``instructmove serve-lerobot`` starts it under a given interpreter. Each request is turned
into the policy's batch as lerobot's own inference does (images HWC uint8 -> CHW float in
[0, 1], a batch of one, the prompt as ``task``), images resized to the shapes the policy was
trained on, then the checkpoint's own pre-processor (normalisation), the policy's action
chunk (its first ``n_action_steps``) and its post-processor (unnormalisation).
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

try:
    import torch
    import torch.nn.functional as F  # noqa: N812
    from lerobot.configs.policies import PreTrainedConfig
    from lerobot.policies.factory import get_policy_class, make_pre_post_processors
    from lerobot.policies.utils import prepare_observation_for_inference
    from openpi_client import base_policy
    from openpi_server import websocket_policy_server
except ImportError as exc:
    raise SystemExit(
        f"serving a LeRobot checkpoint needs lerobot >= 0.4 and openpi's server ({exc}); run it "
        "with the Python of an environment that has them (scripts/lerobot_env.sh builds one)"
    ) from None

#: Request keys that are not the policy's observation.
CONTROL_KEYS = ("prompt", "timestamp")


class CheckpointPolicy(base_policy.BasePolicy):
    """A LeRobot policy checkpoint answering openpi requests with action chunks."""

    def __init__(self, checkpoint: Path, device: str = "cpu") -> None:
        if not (checkpoint / "config.json").is_file():
            raise SystemExit(f"{checkpoint}: not a LeRobot checkpoint (config.json missing)")
        self.config = PreTrainedConfig.from_pretrained(checkpoint)
        self.config.device = device
        self.policy = get_policy_class(self.config.type).from_pretrained(checkpoint)
        self.policy.to(device).eval()
        self.device = torch.device(device)
        self.pre, self.post = make_pre_post_processors(
            self.config,
            pretrained_path=str(checkpoint),
            preprocessor_overrides={"device_processor": {"device": device}},
        )
        self.features = self.config.input_features
        self.steps = int(getattr(self.config, "n_action_steps", 1))

    def infer(self, obs: dict) -> dict:
        missing = sorted(set(self.features) - set(obs))
        if missing:
            raise ValueError(f"the request lacks {missing}; it has {sorted(obs)}")
        raw = {k: np.array(v) for k, v in obs.items() if k in self.features}  # writable
        with torch.inference_mode():
            batch = prepare_observation_for_inference(raw, self.device, str(obs.get("prompt", "")))
            for key, feature in self.features.items():
                shape = tuple(feature.shape)  # (C, H, W) for an image
                if len(shape) == 3 and tuple(batch[key].shape[1:]) != shape:
                    batch[key] = F.interpolate(
                        batch[key], size=shape[1:], mode="bilinear", antialias=True
                    )
            batch = self.pre(batch)
            chunk = self.policy.predict_action_chunk(batch)[:, : self.steps]
            actions = self.post(chunk)
        return {"actions": actions[0].cpu().numpy().astype(np.float32)}

    def reset(self) -> None:
        self.policy.reset()


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--checkpoint", required=True, type=Path, help="pretrained_model folder")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--device", default="cpu")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO)
    policy = CheckpointPolicy(args.checkpoint, args.device)
    metadata = {"policy": policy.config.type, "checkpoint": str(args.checkpoint)}
    print(f"serving {args.checkpoint} on ws://{args.host}:{args.port}", flush=True)
    server = websocket_policy_server.WebsocketPolicyServer(policy, args.host, args.port, metadata)
    server.serve_forever()


if __name__ == "__main__":
    main()
