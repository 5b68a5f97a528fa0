"""The procedural object library: generators, catalog, snapshots and splits."""

from .catalog import Catalog, Instance, generate_instance, load_snapshot, taxonomy

__all__ = ["Catalog", "Instance", "generate_instance", "load_snapshot", "taxonomy"]
