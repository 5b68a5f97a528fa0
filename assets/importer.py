"""Import external assets (scanned or generated meshes) into a snapshot of their own.

A source folder holds mesh files and ``metadata.json``::

    {"assets": [{"id": "blue_mug_01", "mesh": "blue_mug_01.obj", "category": "mug",
                 "colors": ["blue"], "material": "ceramic", "shape": "cylinder",
                 "graspable": true, "container": true, "scale": 1.0,
                 "interior": {"center": [0, 0, 0.01], "half": [0.03, 0.03], "height": 0.08},
                 "synonyms": ["mug"], "domain": "...", "super_category": "..."}]}

Meshes are in metres after ``scale``, z up, in their resting pose. Each mesh is checked
(``clean_mesh``: degenerate and duplicate faces are dropped, small holes filled and both
reported; a mesh that stays open, or is flat, is refused naming the asset and its file),
decomposed into convex pieces with CoACD (cached by content in the user data folder, never
inside the installed package; an entry appears complete or not at all), recentred to rest on
z = 0, checked like generated assets, and stored as an instance record. The new snapshot
lists the extended snapshot's assets plus the imported ones, so envs take it with
``snapshot=NAME``.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import uuid as uuidlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from ..files import atomic_path, staging, write_json
from .catalog import Instance, taxonomy
from .generators import GENERATORS
from .parts import Part, Region
from .vocab import COLORS, MATERIAL_WORD, MATERIALS, SHAPES

IMPORT_NAMESPACE = uuidlib.UUID("0b7e8a52-92d1-4d37-9a57-4c0c3a4f8e11")
REQUIRED = ("id", "mesh", "category", "colors", "material", "shape")


def data_home() -> Path:
    """User data folder for imported assets, caches and user snapshots."""
    return Path(os.environ.get("INSTRUCTMOVE_HOME", Path.home() / ".instructmove"))


class AssetImportError(ValueError):
    """Bad metadata or mesh in an import folder."""


@dataclass(frozen=True)
class Piece:
    path: Path  # OBJ centred on the piece's bounding box
    center: tuple[float, float, float]  # where that centre sits in the object frame


def _check_entry(entry: dict, index: int) -> None:
    missing = [k for k in REQUIRED if k not in entry]
    if missing:
        raise AssetImportError(
            f"asset #{index}: missing fields {missing}; required: {list(REQUIRED)}"
        )
    for color in entry["colors"]:
        if color not in COLORS:
            raise AssetImportError(
                f"asset {entry['id']!r}: unknown colour {color!r}; allowed: {sorted(COLORS)}"
            )
    if not 1 <= len(entry["colors"]) <= 2:
        raise AssetImportError(f"asset {entry['id']!r}: give 1 or 2 colours")
    if entry["material"] not in MATERIALS:
        raise AssetImportError(
            f"asset {entry['id']!r}: unknown material {entry['material']!r}; "
            f"allowed: {sorted(MATERIALS)}"
        )
    if entry["shape"] not in SHAPES:
        raise AssetImportError(
            f"asset {entry['id']!r}: unknown shape {entry['shape']!r}; allowed: {list(SHAPES)}"
        )
    if entry["category"] not in taxonomy() and not {"domain", "super_category"} <= set(entry):
        raise AssetImportError(
            f"asset {entry['id']!r}: category {entry['category']!r} is not in "
            "the taxonomy; give its domain and super_category"
        )


def _write_obj(path: Path, mesh: trimesh.Trimesh) -> None:
    with atomic_path(path) as tmp:
        mesh.export(tmp, file_type="obj")


#: Metres: a mesh thinner than this in any direction is flat (no volume to grasp or hold).
MIN_EXTENT = 1e-3


def clean_mesh(mesh: trimesh.Trimesh, where: str) -> list[str]:
    """Repair ``mesh`` in place where that is safe and say what was done; raise an
    ``AssetImportError`` starting with ``where`` (the asset and its file) for a mesh that is
    flat or stays open (edges of one face only) after its holes were filled. Closed parts
    that touch (edges of more than two faces) are fine: each becomes convex pieces."""
    notes = []
    faces = len(mesh.faces)
    mesh.update_faces(mesh.nondegenerate_faces())
    mesh.update_faces(mesh.unique_faces())
    mesh.remove_unreferenced_vertices()
    if len(mesh.faces) < faces:
        notes.append(f"removed {faces - len(mesh.faces)} degenerate or duplicate faces")
    if len(mesh.faces) == 0 or float(mesh.extents.min()) < MIN_EXTENT:
        raise AssetImportError(f"{where} is flat: extents {np.round(mesh.extents, 4).tolist()} m")
    open_edges = _open_edges(mesh)
    if open_edges:
        trimesh.repair.fill_holes(mesh)
        if _open_edges(mesh):
            raise AssetImportError(
                f"{where} is not watertight: {_open_edges(mesh)} edges bound one face only "
                "(holes too large to fill)"
            )
        notes.append(f"filled holes bounded by {open_edges} open edges")
    if mesh.volume <= 0:
        trimesh.repair.fix_normals(mesh)
        notes.append("turned its faces outward")
    return notes


def _open_edges(mesh: trimesh.Trimesh) -> int:
    """Edges that belong to one face only."""
    return int(
        (np.bincount(mesh.edges_unique_inverse, minlength=len(mesh.edges_unique)) == 1).sum()
    )


def decompose(mesh: trimesh.Trimesh, digest: str, threshold: float) -> tuple[list[Piece], Path]:
    """CoACD convex pieces and the visual mesh, centred, cached by content (built in a
    staging folder and moved into place whole)."""
    folder = data_home() / "coacd" / f"{digest}-{threshold}"
    index = folder / "pieces.json"
    if not index.is_file():
        with staging(folder.parent) as tmp:
            _decompose(mesh, threshold, tmp)
            shutil.rmtree(folder, ignore_errors=True)  # a partial entry of an older release
            os.replace(tmp, folder)
    centres = json.loads(index.read_text())
    pieces = [Piece(folder / f"piece_{k:03d}.obj", tuple(c)) for k, c in enumerate(centres)]
    return pieces, folder / "visual.obj"


def _decompose(mesh: trimesh.Trimesh, threshold: float, folder: Path) -> None:
    """Write the CoACD pieces (centred), the visual mesh and the pieces' centres into
    ``folder``."""
    import coacd

    coacd.set_log_level("error")
    hulls = coacd.run_coacd(
        coacd.Mesh(mesh.vertices, mesh.faces),
        threshold=threshold,
        max_convex_hull=32,
        preprocess_resolution=30,
        resolution=1000,
        mcts_iterations=60,
        mcts_nodes=12,
    )
    centres = []
    for k, (verts, faces) in enumerate(hulls):
        piece = trimesh.Trimesh(verts, faces).convex_hull
        centre = piece.bounds.mean(axis=0)
        piece.apply_translation(-centre)
        _write_obj(folder / f"piece_{k:03d}.obj", piece)
        centres.append([float(v) for v in centre])
    visual = mesh.copy()
    visual.apply_translation(-visual.bounds.mean(axis=0))
    _write_obj(folder / "visual.obj", visual)
    write_json(folder / "pieces.json", centres, indent=None)


def import_asset(entry: dict, source: Path, threshold: float = 0.05) -> tuple[Instance, list[str]]:
    """One metadata entry of ``source`` as an instance (mesh checked, decomposed,
    recentred) and what was repaired in its mesh."""
    mesh_path = source / entry["mesh"]
    if not mesh_path.is_file():
        raise AssetImportError(f"asset {entry['id']!r}: mesh file {mesh_path} not found")
    try:
        mesh = trimesh.load(mesh_path, force="mesh")
    except Exception as exc:
        raise AssetImportError(f"asset {entry['id']!r}: cannot read {mesh_path}: {exc}") from exc
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise AssetImportError(f"asset {entry['id']!r}: {mesh_path} holds no triangle mesh")
    scale = float(entry.get("scale", 1.0))
    mesh.apply_scale(scale)
    repaired = clean_mesh(mesh, f"asset {entry['id']!r}: {mesh_path}")
    lo, hi = mesh.bounds
    offset = np.array([-(lo[0] + hi[0]) / 2, -(lo[1] + hi[1]) / 2, -lo[2]])
    mesh.apply_translation(offset)
    digest = hashlib.sha256(mesh_path.read_bytes() + repr(scale).encode()).hexdigest()[:24]
    pieces, visual = decompose(mesh, digest, threshold)
    color, material = entry["colors"][0], entry["material"]
    identity = (1.0, 0.0, 0.0, 0.0)
    parts = []
    for k, piece in enumerate(pieces):
        hull = trimesh.load(piece.path, force="mesh")
        parts.append(
            Part(
                f"piece_{k}",
                "mesh",
                tuple(float(v) for v in hull.extents / 2),
                piece.center,
                identity,
                material,
                color,
                COLORS[color],
                mesh=str(piece.path),
                mesh_volume=float(hull.volume),
            )
        )
    parts.append(
        Part(
            "visual",
            "mesh",
            tuple(float(v) for v in mesh.extents / 2),
            tuple(float(v) for v in mesh.bounds.mean(axis=0)),
            identity,
            material,
            color,
            COLORS[color],
            visual_only=True,
            mesh=str(visual),
        )
    )
    category = entry["category"]
    known = taxonomy().get(category)
    gen = GENERATORS.get(category)
    nouns = entry.get("synonyms") or (gen.synonyms if gen else (category.replace("_", " "),))
    interior = entry.get("interior")
    instance = Instance(
        uuid=str(uuidlib.uuid5(IMPORT_NAMESPACE, f"{entry['id']}/{digest}")),
        category=category,
        index=-1,
        domain=entry.get("domain", known.domain if known else ""),
        super_category=entry.get("super_category", known.super_category if known else ""),
        parts=tuple(parts),
        colors=tuple(entry["colors"]),
        material=MATERIAL_WORD.get(material, material),
        shape=entry["shape"],
        nouns=tuple(nouns),
        is_graspable=bool(entry.get("graspable", True)),
        is_container=bool(entry.get("container", False)),
        interior=None
        if interior is None
        else Region(
            tuple(float(v) for v in np.asarray(interior["center"], dtype=float) + offset),
            tuple(float(v) for v in interior["half"]),
            float(interior["height"]),
        ),
    )
    return instance, repaired


def read_metadata(source: Path) -> list[dict]:
    path = source / "metadata.json"
    if not path.is_file():
        raise AssetImportError(f"{path} not found: an import folder needs a metadata.json")
    try:
        entries = json.loads(path.read_text())["assets"]
    except (json.JSONDecodeError, KeyError, TypeError) as exc:
        raise AssetImportError(f'{path}: expected {{"assets": [...]}}: {exc}') from exc
    for k, entry in enumerate(entries):
        _check_entry(entry, k)
    return entries
