"""Export of recorded episodes as MCAP files with Foxglove schemas (see docs/mcap.md)."""

from .mcap import ExportReport, ExportSettings, episode_path, export_trajectory
from .reader import McapEpisode, read_episode, read_messages, score_inputs
from .source import TrajectoryError, load_trajectory

__all__ = [
    "ExportReport",
    "ExportSettings",
    "McapEpisode",
    "TrajectoryError",
    "episode_path",
    "export_trajectory",
    "load_trajectory",
    "read_episode",
    "read_messages",
    "score_inputs",
]
