"""The per-episode metadata record of an episode MCAP (the ``/episode`` message's JSON)."""

from __future__ import annotations

from importlib import metadata as importlib_metadata

from .replay import RobotParts
from .source import EpisodeSource, Trajectory

FORMAT = "instructmove-episode-mcap/1"
PACKAGES = (
    "instructmove-ms",
    "mani-skill",
    "sapien",
    "mcap",
    "mcap-protobuf-support",
    "foxglove-schemas-protobuf",
)


def software_versions() -> dict[str, str | None]:
    """Installed versions of the packages that produced the file (None if not installed)."""
    versions: dict[str, str | None] = {}
    for name in PACKAGES:
        try:
            versions[name] = importlib_metadata.version(name)
        except importlib_metadata.PackageNotFoundError:
            versions[name] = None
    return versions


def episode_metadata(traj: Trajectory, ep: EpisodeSource, rig: RobotParts, info: dict) -> dict:
    """Everything about the episode that is not a time series: spec, instruction, objects,
    outcome (recorded success and per-step stage flags, the replayed last step's info and its
    stage score), the robot's parts and the software versions."""
    spec = ep.spec
    return {
        "format": FORMAT,
        "source": traj.path.name,
        "env_id": traj.env_id,
        "env_kwargs": traj.env_kwargs,
        "control_mode": traj.control_mode,
        "control_freq": rig.control_freq,
        "episode_id": ep.episode_id,
        "seed": ep.seed,
        "reset_kwargs": ep.reset_kwargs,
        "instruction": spec["instruction"],
        "spec": spec,
        "objects": [
            {"index": k, "uuid": o["uuid"], "category": o["category"], "role": o["role"]}
            for k, o in enumerate(spec["objects"])
        ],
        "success": ep.success,
        "stages": ep.stages,
        "info": info,
        "score": float(info.get("stage_score", 0.0)),
        "arms": {arm: [rig.joint_names[i] for i in index] for arm, index in rig.arms.items()},
        "links": list(rig.link_names),
        "cameras": list(rig.cameras),
        "action_names": list(rig.action_names),
        "versions": software_versions(),
    }
