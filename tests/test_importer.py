"""Importing external meshes: decomposition, checks, records and a usable snapshot."""

from __future__ import annotations

import json

import numpy as np
import pytest
import trimesh

from instructmove_ms.assets import snapshot as snap
from instructmove_ms.assets.importer import AssetImportError, read_metadata
from instructmove_ms.assets.sim import TIMESTEP, spawn, table_scene


def _cup_mesh() -> trimesh.Trimesh:
    """A hollow cup: an open cylinder wall with a floor (a concave shape)."""
    wall = trimesh.creation.annulus(r_min=0.03, r_max=0.035, height=0.09)
    wall.apply_translation([0, 0, 0.045])
    floor = trimesh.creation.cylinder(radius=0.035, height=0.006)
    floor.apply_translation([0, 0, 0.003])
    return trimesh.util.concatenate([wall, floor])


@pytest.fixture()
def source(tmp_path, monkeypatch):
    monkeypatch.setenv("INSTRUCTMOVE_HOME", str(tmp_path / "home"))
    folder = tmp_path / "scans"
    folder.mkdir()
    _cup_mesh().export(folder / "cup.obj")
    (folder / "metadata.json").write_text(
        json.dumps(
            {
                "assets": [
                    {
                        "id": "scan_cup_01",
                        "mesh": "cup.obj",
                        "category": "mouthwash_cup",
                        "colors": ["blue"],
                        "material": "plastic",
                        "shape": "cylinder",
                        "graspable": True,
                        "container": True,
                        "scale": 1.0,
                        "interior": {"center": [0, 0, 0.006], "half": [0.02, 0.02], "height": 0.08},
                    }
                ]
            }
        )
    )
    return folder


def test_import_makes_a_snapshot_with_a_hollow_physical_cup(source, tmp_path):
    report = snap.import_folder(source, "my_scans", extend=None, threshold=0.08)
    path, rejected = report.path, report.rejected
    assert not rejected
    assert path.parent == tmp_path / "home" / "snapshots"
    catalog = snap.load_snapshot("my_scans")
    (cup,) = catalog.instances
    assert cup.category == "mouthwash_cup" and cup.is_container
    pieces = [p for p in cup.parts if not p.visual_only]
    assert len(pieces) >= 3, "CoACD split the concave cup into several convex pieces"
    assert all((tmp_path / "home") in __import__("pathlib").Path(p.mesh).parents for p in pieces)
    np.testing.assert_allclose(cup.dims, (0.07, 0.07, 0.09), atol=0.003)
    # an egg dropped into the cup stays inside it: the collision follows the concave shape
    scene = table_scene()
    cup_entity = spawn(scene, cup)
    egg = spawn(scene, snap.generate_instance("egg", 0), z=0.12)
    for _ in range(int(1.5 / TIMESTEP)):
        scene.step()
    rel = np.asarray(egg.pose.p) - np.asarray(cup_entity.pose.p)
    assert np.linalg.norm(rel[:2]) < 0.03 and 0.0 < rel[2] < 0.09


def test_reimport_uses_the_cache_and_keeps_the_uuid(source):
    snap.import_folder(source, "a", extend=None, threshold=0.08)
    first = snap.load_snapshot("a").instances[0]
    snap.import_folder(source, "b", extend=None, threshold=0.08)
    assert snap.load_snapshot("b").instances[0] == first


def test_bad_metadata_names_the_problem(source):
    meta = json.loads((source / "metadata.json").read_text())
    meta["assets"][0]["material"] = "unobtainium"
    (source / "metadata.json").write_text(json.dumps(meta))
    with pytest.raises(AssetImportError, match="'unobtainium'.*allowed"):
        read_metadata(source)


def _write_source(folder, meshes: dict) -> None:
    """An import folder with one plastic box per (id, mesh)."""
    folder.mkdir(parents=True, exist_ok=True)
    assets = []
    for asset_id, mesh in meshes.items():
        mesh.export(folder / f"{asset_id}.obj")
        assets.append(
            {
                "id": asset_id,
                "mesh": f"{asset_id}.obj",
                "category": "cardboard_box",
                "colors": ["red"],
                "material": "plastic",
                "shape": "cuboid",
                "graspable": False,
            }
        )
    (folder / "metadata.json").write_text(json.dumps({"assets": assets}))


def _box_without(faces) -> trimesh.Trimesh:
    box = trimesh.creation.box([0.24, 0.16, 0.12])
    keep = np.ones(len(box.faces), dtype=bool)
    keep[list(faces)] = False
    box.update_faces(keep)
    return box


def test_broken_meshes_are_refused_by_asset_and_file_and_nothing_is_written(tmp_path, monkeypatch):
    home = tmp_path / "home"
    monkeypatch.setenv("INSTRUCTMOVE_HOME", str(home))
    source = tmp_path / "broken"
    _write_source(
        source,
        {
            "two_open_walls": _box_without([0, 1, 4, 5]),  # holes in two walls
            "flat_card": trimesh.creation.box([0.24, 0.16, 0.0]),
        },
    )
    with pytest.raises(ValueError) as caught:
        snap.import_folder(source, "broken", extend=None)
    message = str(caught.value)
    assert "nothing written" in message
    assert f"'two_open_walls': {source / 'two_open_walls.obj'} is not watertight" in message
    assert f"'flat_card': {source / 'flat_card.obj'} is flat" in message
    assert not (home / "snapshots").exists(), "no snapshot"
    assert not (home / "coacd").exists(), "no decomposition cached"


def test_a_small_hole_is_filled_and_reported(tmp_path, monkeypatch):
    monkeypatch.setenv("INSTRUCTMOVE_HOME", str(tmp_path / "home"))
    source = tmp_path / "holed"
    _write_source(source, {"one_missing_triangle": _box_without([3])})
    report = snap.import_folder(source, "holed", extend=None, threshold=0.08)
    assert not report.rejected
    ((asset_id, repairs),) = report.repaired
    assert asset_id == "one_missing_triangle" and repairs == [
        "filled holes bounded by 3 open edges"
    ]
    (box,) = snap.load_snapshot("holed").instances
    np.testing.assert_allclose(box.dims, (0.24, 0.16, 0.12), atol=0.002)
