"""Snapshots: immutable lists of assets (uuid + content hash) that experiments freeze.

A snapshot file names every instance by (category, index) with its uuid and the hash of its
generated content (``identity.content_hash``: numbers counted in quanta far above
floating-point noise, so every machine computes the same hash). Loading regenerates each
instance and refuses a snapshot whose content no longer matches, so an experiment can never
silently run on changed assets. Growing the library (new categories, more instances) writes
a new snapshot; old ones keep their meaning.

A snapshot also records how its instances are built (``Frozen``): whether they wear their
textures (printed labels, dials, grain: ``textures``; one written without rebuilds its
instances plain), and the library revision it was frozen at (``library``; absent means 1):
each category is rebuilt by its newest generator at or before that revision
(``generators.registry``), so a revised generator never changes an older snapshot. One
ships with the package: ``recognisable`` (revision 3), on which InstructMove 1.0 plays.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cache
from importlib import resources
from pathlib import Path

from ..files import write_json, write_text
from ..worker_log import mark
from .catalog import DEFAULT_SNAPSHOT, Catalog, Instance, generate_instance, plain
from .generators import GENERATORS, LIBRARY
from .identity import IDENTITY_SCHEME, content_hash, hash_for
from .importer import data_home

SNAPSHOT_DIR = "snapshots"


@dataclass(frozen=True)
class Frozen:
    """How a snapshot builds its instances: with their textures or plain, and at which
    library revision (see ``generators.registry``)."""

    textures: bool = True
    library: int = LIBRARY


#: The snapshots that ship with the package, and how each builds its instances.
SHIPPED = {"recognisable": Frozen(textures=True, library=3)}


def build_entries(
    categories: list[str], per_category: int, frozen: Frozen = Frozen()
) -> list[dict]:
    """The entries of instances ``0 .. per_category - 1`` of each of ``categories``, built
    as ``frozen`` says."""
    return [
        entry_of(_built(cat, index, frozen)) for cat in categories for index in range(per_category)
    ]


def _built(category: str, index: int, frozen: Frozen) -> Instance:
    inst = generate_instance(category, index, frozen.library)
    return inst if frozen.textures else plain(inst)


def write_snapshot(path: Path, name: str, entries: list[dict], frozen: Frozen = Frozen()) -> Path:
    """Write atomically (temporary file in the same folder, then rename), under the
    current identity scheme. The library revision is written only past 1, so files from
    before revisions keep their bytes."""
    data = {
        "identity": IDENTITY_SCHEME,
        "name": name,
        "instances": entries,
        "textures": frozen.textures,
    }
    if frozen.library > 1:
        data["library"] = frozen.library
    return write_text(path, json.dumps(data, indent=1, sort_keys=True) + "\n")


def package_snapshot_dir() -> Path:
    return Path(str(resources.files("instructmove_ms.assets").joinpath(SNAPSHOT_DIR)))


def user_snapshot_dir() -> Path:
    return data_home() / SNAPSHOT_DIR


def imported_record_path(uuid: str) -> Path:
    return data_home() / "imported" / f"{uuid}.json"


def snapshot_path(name: str) -> Path | None:
    """The file of snapshot ``name``: shipped with the package, else in the user folder."""
    for folder in (package_snapshot_dir(), user_snapshot_dir()):
        path = folder / f"{name}.json"
        if path.is_file():
            return path
    return None


def available_snapshots() -> list[str]:
    names = {
        p.stem for d in (package_snapshot_dir(), user_snapshot_dir()) for p in d.glob("*.json")
    }
    return sorted(names)


def _load_entry(name: str, entry: dict, frozen: Frozen) -> Instance:
    if entry.get("source") == "import":
        path = imported_record_path(entry["uuid"])
        if not path.is_file():
            raise ValueError(
                f"snapshot {name!r} needs imported asset {entry['uuid']}, "
                f"whose record {path} is missing"
            )
        return Instance.from_record(json.loads(path.read_text()))
    if entry["category"] not in GENERATORS:
        raise ValueError(
            f"snapshot {name!r} needs category {entry['category']!r}, "
            "which has no generator in this version"
        )
    return _built(entry["category"], entry["index"], frozen)


@cache
def load_snapshot(name: str = DEFAULT_SNAPSHOT) -> Catalog:
    """The catalog of snapshot ``name``; every instance rebuilt and hash-checked."""
    catalog = Catalog(name, _checked(name, json.loads(_existing(name).read_text())))
    mark("library")
    return catalog


def frozen_as(name: str) -> Frozen:
    """How snapshot ``name`` builds its instances."""
    return _frozen(json.loads(_existing(name).read_text()))


def _frozen(data: dict) -> Frozen:
    """How snapshot file ``data`` builds its instances (files from before textures are
    plain; files from before revisions are at library revision 1)."""
    return Frozen(data.get("textures", False), data.get("library", 1))


def _existing(name: str) -> Path:
    """The file of snapshot ``name``; a ``ValueError`` names the snapshots there are."""
    path = snapshot_path(name)
    if path is None:
        raise ValueError(f"unknown snapshot {name!r}; allowed: {available_snapshots()}")
    return path


def _checked(name: str, data: dict) -> list[Instance]:
    """The instances of snapshot file ``data``, each regenerated and hash-checked under
    the file's identity scheme."""
    scheme = data.get("identity", 1)
    instances = []
    for entry in data["instances"]:
        inst = _load_entry(name, entry, _frozen(data))
        if inst.uuid != entry["uuid"] or hash_for(inst, scheme) != entry["content_hash"]:
            hint = (
                " (it was frozen with exact floats, identity scheme 1, which another "
                "machine's math kernels can break: `instructmove assets rehash "
                f"{name}` re-hashes it where it still loads)"
                if scheme == 1
                else ""
            )
            raise ValueError(
                f"snapshot {name!r} is stale: {entry['category']} #{entry['index']} "
                f"({entry['uuid']}) changed since it was frozen; a changed generator is a "
                "new library revision, frozen as a new snapshot (`instructmove assets build "
                f"--name NEW`){hint}"
            )
        instances.append(inst)
    return instances


def rehash(name: str) -> tuple[int, int]:
    """Rewrite snapshot ``name`` under the current identity scheme, after checking every
    instance under the scheme it was written with (neither the instances nor their uuids
    change), and move its rendered-colour table along. Returns how many instances it holds
    and how many stored colours were kept."""
    from .appearance import rehash_table, table_path

    path = _existing(name)
    data = json.loads(path.read_text())
    instances = _checked(name, data)
    old = {e["uuid"]: e["content_hash"] for e in data["instances"]}
    entries = [
        {**e, "content_hash": content_hash(i)}
        for e, i in zip(data["instances"], instances, strict=True)
    ]
    write_snapshot(path, name, entries, _frozen(data))
    load_snapshot.cache_clear()
    table = table_path(name)
    kept = rehash_table(table, old, instances) if table.is_file() else 0
    return len(entries), kept


def entry_of(inst: Instance) -> dict:
    entry = {
        "uuid": inst.uuid,
        "category": inst.category,
        "index": inst.index,
        "content_hash": content_hash(inst),
    }
    if inst.index < 0:  # imported assets have no generator index
        entry["source"] = "import"
    return entry


@dataclass(frozen=True)
class ImportReport:
    """An import's snapshot, the (asset id, reasons) of the assets left out and the
    (asset id, repairs) of those whose meshes were repaired."""

    path: Path
    rejected: list[tuple[str, list[str]]]
    repaired: list[tuple[str, list[str]]]


def import_folder(
    source: Path, name: str, extend: str | None = DEFAULT_SNAPSHOT, threshold: float = 0.05
) -> ImportReport:
    """Import ``source`` (see ``importer``), check every asset, and write snapshot ``name``
    (the assets of ``extend`` plus the imported ones that pass). Where no asset passes,
    nothing is written and a ``ValueError`` gives every asset's reasons."""
    from tqdm import tqdm

    from .importer import AssetImportError, import_asset, read_metadata
    from .quality import check_instances

    if snapshot_path(name) is not None and name in {
        p.stem for p in package_snapshot_dir().glob("*.json")
    }:
        raise ValueError(f"snapshot {name!r} ships with the package; choose another name")
    entries = read_metadata(source)
    base = list(load_snapshot(extend).instances) if extend else []
    rejected, repaired, imported = [], [], []
    for entry in tqdm(entries, desc="decomposing", unit="asset"):
        try:
            inst, repairs = import_asset(entry, source, threshold)
        except AssetImportError as exc:
            rejected.append((entry["id"], [str(exc)]))
            continue
        imported.append((entry["id"], inst))
        if repairs:
            repaired.append((entry["id"], repairs))
    kept = []
    results = check_instances([inst for _, inst in imported])
    for (asset_id, inst), result in zip(imported, results, strict=True):
        if result.ok:
            kept.append(inst)
        else:
            rejected.append((asset_id, result.failures))
    if not kept:
        reasons = "; ".join(f"{a}: {', '.join(r)}" for a, r in rejected)
        raise ValueError(f"no asset of {source} passed the checks, nothing written ({reasons})")
    for inst in kept:
        write_json(imported_record_path(inst.uuid), inst.to_record(), indent=None)
    snapshot = [entry_of(i) for i in base + kept]
    frozen = frozen_as(extend) if extend else Frozen()
    path = write_snapshot(user_snapshot_dir() / f"{name}.json", name, snapshot, frozen)
    load_snapshot.cache_clear()
    return ImportReport(path, rejected, repaired)
