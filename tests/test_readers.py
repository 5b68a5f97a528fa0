"""The reader protocol: material drawn from a seed (the same seed, the same material; the
key kept apart from what the reader sees) and the scorer's written rules."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets.catalog import Catalog
from instructmove_ms.heldout import SET_VERSION
from instructmove_ms.readers import material
from instructmove_ms.readers.briefs import BRIEFS, brief
from instructmove_ms.readers.names import accepted_names, first_guess, names_category, normalise
from instructmove_ms.readers.pictures import GRID, cell_key
from instructmove_ms.readers.score import found, judgement, score


def _key(tmp_path, kind, items, name="key.json"):
    path = tmp_path / name
    path.write_text(json.dumps({"kind": kind, "seed": 1, "items": items}))
    return path


def _answers(tmp_path, name, lines):
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize(
    ("answer", "category", "named"),
    [
        ("mug", "mug", True),
        ("A red coffee mug", "mug", True),  # modifiers before an accepted name
        ("Mugs", "mug", True),  # plural
        ("pair of scissors; shears", "scissors", True),
        ("Post-it notes", "sticky_notes", True),
        ("cup", "pen_holder", False),  # the miss readers made
        ("wooden bowl; soap dish", "soap_dish", False),  # only the first guess counts
        ("soap dish (wooden)", "soap_dish", True),
        ("remote control", "ac_remote", False),  # fits any remote
        ("remote control", "tv_remote", True),
        ("", "mug", False),
        ("egg in an egg cup", "egg", True),  # a prepositional phrase after the noun
        ("phone on a stand", "phone_stand", False),  # names the phone
        ("glass of juice", "spice_jar", False),
    ],
)
def test_a_first_guess_names_a_category_by_the_written_rules(answer, category, named):
    assert names_category(answer, category) is named


def test_every_category_has_its_own_names():
    names = accepted_names()
    assert set(names) == set(load_snapshot().categories)
    catalog = load_snapshot()
    for category, accepted in names.items():
        nouns = {normalise(n) for i in catalog.of_category(category) for n in i.nouns}
        assert nouns & set(accepted), f"{category}: none of its own nouns is accepted"
    owners: dict[str, list[str]] = {}
    for category, accepted in names.items():
        for name in accepted:
            owners.setdefault(name, []).append(category)
    assert {n: c for n, c in owners.items() if len(c) > 1} == {}, "a name tells one category"
    with pytest.raises(ValueError, match="unknown category 'teapot'"):
        names_category("teapot", "teapot")
    assert first_guess("a vase or a cup") == "a vase"


def test_names_need_two_of_three_readers(tmp_path):
    key = _key(tmp_path, "close_ups", [{"n": 1, "category": "mug"}, {"n": 2, "category": "vase"}])
    readers = [
        _answers(tmp_path, "a.txt", ["1: mug", "2: vase"]),
        _answers(tmp_path, "b.txt", ["1: coffee mug", "2: wastebasket"]),
        _answers(tmp_path, "c.txt", ["1. cup of tea", "2) bin"]),
    ]
    result = score(key, readers)
    assert (result["agreement"], result["passed"], result["per_reader"]) == (2, 1, [2, 1, 0])
    assert score(key, readers, agreement=1)["passed"] == 2
    with pytest.raises(ValueError, match="agreement 4 outside 1..3"):
        score(key, readers, agreement=4)
    bad = _answers(tmp_path, "bad.txt", ["3: mug"])
    with pytest.raises(ValueError, match="answer number 3 outside 1..2"):
        score(key, [bad])


def test_instruction_judgements(tmp_path):
    items = [{"n": n, "instruction": f"pick up the mug {n}"} for n in (1, 2, 3)]
    key = _key(tmp_path, "instructions", items)
    answers = _answers(tmp_path, "a.txt", ["1: natural", "2: Odd - robotic", "3: ambiguous"])
    result = score(key, [answers])
    assert result["passed"] == 1
    assert result["judgements"] == [{"natural": 1, "odd": 1, "unnatural": 0, "ambiguous": 1}]
    assert judgement("unnatural: garbled") == "unnatural" and judgement("fine") is None


def test_an_episode_answer_names_the_cell_its_object_holds():
    seg = np.zeros((64, 64), np.int16)
    seg[0:8, 8:16] = 7  # object 0 fills cell B1
    seg[56:64, 0:6] = 9  # object 1 holds most of cell A8 ...
    seg[56:64, 6:8] = 7  # ... where object 0 has less
    owners, _ = cell_key(seg, {7: 0, 9: 1})
    assert len(owners) == GRID and owners[0][1] == 0 and owners[7][0] == 1 and owners[3][3] == -1
    pick = {"target": 0, "destination": -1, "owners": [owners]}
    assert found("1 B1", pick) and found("1 b1", pick)
    assert not found("1 A8", pick) and not found("2 B1", pick) and not found("B1", pick)
    place = {"target": 0, "destination": 1, "owners": [owners, owners]}
    assert found("1 B1 / 2 A8", place) and not found("1 B1", place)
    # a small object that holds the most pixels of no cell still owns the cell holding most
    # of it (what the reader is asked to name)
    seg[24:32, 24:32] = 7  # object 0 fills cell D4 ...
    seg[24:26, 24:28] = 5  # ... where object 2, small, lies
    owners, _ = cell_key(seg, {7: 0, 9: 1, 5: 2})
    assert owners[3][3] == 2 and sum(row.count(2) for row in owners) == 1
    assert owners[0][1] == 0 and owners[7][0] == 1  # the others keep theirs
    # the cell holding most of an object counts where another object holds more of it
    seg[:] = 0
    seg[8:16, 22:24] = 7  # object 0: 16 pixels in cell C2 (alone) ...
    seg[8:11, 24:32] = 7  # ... and 24 in cell D2,
    seg[11:16, 24:32] = 9  # where object 1 has 40
    owners, most = cell_key(seg, {7: 0, 9: 1})
    assert most == {"0": [1, 3], "1": [1, 3]}
    assert owners[1][2] == 0 and owners[1][3] == 1
    item = {"target": 0, "destination": -1, "owners": [owners], "most": [most]}
    assert found("1 D2", item) and found("1 C2", item) and not found("1 E2", item)
    assert not found("1 D2", {**item, "most": [{}]}), "an older key: owners alone"
    item = {"target": 1, "destination": -1, "owners": [owners], "most": [most]}
    assert found("1 D2", item) and not found("1 C2", item)


def _small_catalog(categories):
    catalog = load_snapshot()
    return Catalog("test", [i for c in categories for i in catalog.of_category(c)])


def test_close_ups_are_drawn_from_the_seed(tmp_path):
    catalog = _small_catalog(["mug", "apple", "stapler"])
    keys = [
        json.loads(material.close_ups(catalog, seed, tmp_path / str(k)).read_text())
        for k, seed in enumerate((5, 5, 6))
    ]
    assert keys[0] == keys[1] and keys[0]["items"] != keys[2]["items"]
    assert sorted(i["category"] for i in keys[0]["items"]) == ["apple", "mug", "stapler"]
    reader = sorted(p.name for p in (tmp_path / "0" / "reader").iterdir())
    assert reader == ["BRIEF.txt", "close_ups_1.png"]  # the key lies outside
    assert (tmp_path / "0" / "reader" / "BRIEF.txt").read_text() == BRIEFS["close_ups"]
    with pytest.raises(ValueError, match="unknown category 'teapot'"):
        material.close_ups(catalog, 5, tmp_path / "x", only=["teapot"])
    every = json.loads(
        material.close_ups(catalog, 5, tmp_path / "all", ["mug"], every_instance=True).read_text()
    )
    assert sorted(i["uuid"] for i in every["items"]) == sorted(
        i.uuid for i in catalog.of_category("mug")
    )


def test_in_scene_boxes_each_category_in_a_stored_episode(tmp_path):
    import cv2

    from instructmove_ms.heldout import load_set

    key = json.loads(
        material.in_scene(load_snapshot(), 3, tmp_path, only=["mug", "apple"]).read_text()
    )
    assert [i["n"] for i in key["items"]] == [1, 2] and key["absent"] == []
    for item in key["items"]:
        _, env_id, robot, rest = item["source"].split("/")
        split, index = rest.split("#")
        spec = load_set(env_id, robot, split)[int(index)]
        assert item["uuid"] in {o.uuid for o in spec.objects}
    page = cv2.imread(str(tmp_path / "reader" / "in_scene_1.png"))[..., ::-1]
    magenta = (page[..., 0] == 255) & (page[..., 1] == 0) & (page[..., 2] == 255)
    assert magenta[:, :224].sum() > 20 and magenta[:, 224:448].sum() > 20  # one box per tile
    assert "224 x 224 pixels" in (tmp_path / "reader" / "BRIEF.txt").read_text()


def test_in_scene_can_show_the_same_views_at_a_larger_resolution(tmp_path):
    import cv2

    small, large = (
        json.loads(
            material.in_scene(
                load_snapshot(), 3, tmp_path / str(side), only=["mug"], side=side
            ).read_text()
        )
        for side in (224, 448)
    )
    assert small["side"] == 224 and large["side"] == 448
    assert [i["source"] for i in small["items"]] == [i["source"] for i in large["items"]]
    pages = [cv2.imread(str(tmp_path / str(s) / "reader" / "in_scene_1.png")) for s in (224, 448)]
    boxes = [int(((p[..., 1] == 0) & (p[..., 0] == 255) & (p[..., 2] == 255)).sum()) for p in pages]
    assert boxes[1] > 1.5 * boxes[0], "the same object, boxed, at twice the side"
    assert (tmp_path / "448" / "reader" / "BRIEF.txt").read_text() == brief("in_scene", 448)
    assert "448 x 448 pixels" in brief("in_scene", 448)
    with pytest.raises(ValueError, match="resolution 4000 is not between 64 and 720"):
        material.in_scene(load_snapshot(), 3, tmp_path / "x", only=["mug"], side=4000)


def test_instructions_and_episodes_are_drawn_from_the_seed(tmp_path):
    first = json.loads(material.instructions(8, tmp_path / "a", count=4).read_text())
    again = json.loads(material.instructions(8, tmp_path / "b", count=4).read_text())
    assert first == again
    sources = [i["source"].split("/")[0] for i in first["items"]]
    stored = f"v{SET_VERSION}"
    assert sorted(sources) == ["train", "train", stored, stored]
    listed = (tmp_path / "a" / "reader" / "instructions.txt").read_text().splitlines()
    assert listed == [f"{i['n']}: {i['instruction']}" for i in first["items"]]

    key = json.loads(material.episodes(9, tmp_path / "e", count=2).read_text())
    for item in key["items"]:
        cells = [
            (cam, r, c)
            for cam, owners in enumerate(item["owners"])
            for r in range(GRID)
            for c in range(GRID)
            if owners[r][c] == item["target"]
        ]
        assert cells, "the target holds a cell in some camera"
        for cam, owners in enumerate(item["owners"]):  # the cell holding most of each object
            for k, (r, c) in item["most"][cam].items():
                assert any(int(k) in row for row in owners) and 0 <= r < GRID and 0 <= c < GRID
    assert (tmp_path / "e" / "reader" / "episode_2.png").is_file()


def test_the_cli_prints_briefs_and_scores(tmp_path):
    key = _key(tmp_path, "close_ups", [{"n": 1, "category": "mug"}])
    answers = _answers(tmp_path, "a.txt", ["1: teacup"])
    run = [sys.executable, "-m", "instructmove_ms.cli", "readers"]
    out = subprocess.run([*run, "score", str(key), str(answers)], capture_output=True, text=True)
    assert out.returncode == 0 and "0 of 1" in out.stdout and "missed 1: mug: teacup" in out.stdout
    brief = subprocess.run([*run, "brief", "instructions"], capture_output=True, text=True)
    assert brief.stdout == BRIEFS["instructions"]
    bad = subprocess.run(
        [*run, "close-ups", "--out", str(tmp_path)], capture_output=True, text=True
    )
    assert bad.returncode == 2 and "--seed" in bad.stderr


def test_close_ups_can_show_another_library_revision(revision_4):
    """``--library N`` shows the snapshot's instances as a revision in the making builds
    them (here a revision 4 of the mouse), before it is frozen; a revision older than a
    category's build is refused by name."""
    from instructmove_ms.assets.catalog import instance_uuid

    mice = _small_catalog(["mouse"])
    fourth = material.at_revision(mice, 4)
    assert fourth.name == "test@r4" and len(fourth) == len(mice)
    assert {i.uuid for i in fourth.instances} == {
        instance_uuid("mouse", i.index, 4) for i in mice.instances
    }
    assert all(any(p.name == "tag" for p in i.parts) for i in fourth.instances)
    assert {i.uuid for i in mice.instances} == {
        instance_uuid("mouse", i.index, 2) for i in mice.instances
    }
    with pytest.raises(ValueError, match="mouse has no build at library revision 1"):
        material.at_revision(mice, 1)


def test_in_scene_shows_an_object_in_the_camera_that_shows_most_of_it():
    from types import SimpleNamespace

    pixels = {"ext": 30, "side": 50, "wrist": 400}
    views = SimpleNamespace(
        cameras=list(pixels),
        scene=2,  # the first two are scene cameras
        mask=lambda camera, k: np.arange(1000) < pixels[camera] * (k + 1),
    )
    assert material.best_camera(views, 0) == "side"
    assert material.best_camera(views, 0, "every") == "wrist"
    pixels |= {"ext": 0, "side": 0}
    assert material.best_camera(views, 0) == "wrist"  # no scene camera shows it
    with pytest.raises(ValueError, match="'wrists' is not one of"):
        material.best_camera(views, 0, "wrists")
