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
import importlib
import logging
from pathlib import Path
from types import ModuleType

import numpy as np

#: What the server imports, found at start (importing this module needs none of them).
MODULES = {
    "torch": "torch",
    "functional": "torch.nn.functional",
    "policies": "lerobot.configs.policies",
    "factory": "lerobot.policies.factory",
    "utils": "lerobot.policies.utils",
    "server": "openpi_server.websocket_policy_server",
}


def _modules() -> dict[str, ModuleType]:
    try:
        return {name: importlib.import_module(path) for name, path in MODULES.items()}
    except ImportError as exc:
        raise SystemExit(
            f"serving a LeRobot checkpoint needs lerobot >= 0.4 and openpi's server ({exc}); "
            "run it with the Python of an environment that has them (scripts/lerobot_env.sh "
            "builds one)"
        ) from None


class CheckpointPolicy:
    """A LeRobot policy checkpoint answering openpi requests with action chunks (openpi's
    server calls ``infer``)."""

    def __init__(self, checkpoint: Path, device: str = "cpu") -> None:
        if not (checkpoint / "config.json").is_file():
            raise SystemExit(f"{checkpoint}: not a LeRobot checkpoint (config.json missing)")
        m = self.m = _modules()
        self.config = m["policies"].PreTrainedConfig.from_pretrained(checkpoint)
        self.config.device = device
        self.policy = m["factory"].get_policy_class(self.config.type).from_pretrained(checkpoint)
        self.policy.to(device).eval()
        self.device = m["torch"].device(device)
        self.pre, self.post = m["factory"].make_pre_post_processors(
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
        torch, resize = self.m["torch"], self.m["functional"].interpolate
        prepare = self.m["utils"].prepare_observation_for_inference
        with torch.inference_mode():
            batch = prepare(raw, self.device, str(obs.get("prompt", "")))
            for key, feature in self.features.items():
                shape = tuple(feature.shape)  # (C, H, W) for an image
                if len(shape) == 3 and tuple(batch[key].shape[1:]) != shape:
                    batch[key] = resize(batch[key], size=shape[1:], mode="bilinear", antialias=True)
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
    server = policy.m["server"].WebsocketPolicyServer(policy, args.host, args.port, metadata)
    server.serve_forever()


if __name__ == "__main__":
    main()
