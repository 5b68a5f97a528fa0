"""The procedural object library: generators, catalog, snapshots and splits."""

from .catalog import Catalog, Instance, generate_instance, taxonomy
from .snapshot import DEFAULT_SNAPSHOT, load_snapshot

__all__ = [
    "DEFAULT_SNAPSHOT",
    "Catalog",
    "Instance",
    "generate_instance",
    "load_snapshot",
    "taxonomy",
]
