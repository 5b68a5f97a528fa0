"""The language-blind audit: it finds InstructMove 1.0's shortcuts, never sees the answer,
and stays quiet where the answer carries no signal."""

from __future__ import annotations

import dataclasses
import json
import random

import pytest

from instructmove_ms import audit
from instructmove_ms.assets import load_snapshot
from instructmove_ms.audit import learned
from instructmove_ms.audit.choices import by_decision, choices_of
from instructmove_ms.audit.noise import yardstick
from instructmove_ms.audit.scenes import choices, stored_specs
from instructmove_ms.cli import main
from instructmove_ms.heldout import load_set


@pytest.fixture(scope="module")
def v7():
    return choices(stored_specs(7))


def _failed(cells) -> set[tuple[str, str, str]]:
    return {(c.family, c.split, c.adversary) for c in cells if c.failed}


def _answered(choices, answer):
    """``choices`` with the answer each gets from ``answer(choice)``."""
    return [dataclasses.replace(c, answer=answer(c)) for c in choices]


def test_rules_find_the_shortcuts_of_sets_v7(v7):
    failed = _failed(audit.judge(v7, trees=False)[0])
    # the unseen splits' target is the only unfamiliar candidate
    assert ("pick_category", "unseen_category", "novelty") in failed
    assert ("place_a2b", "unseen_instance", "novelty") in failed
    assert ("pick_spatial", "unseen_instance", "novelty") in failed
    # PickAttribute's target is the odd material out; PlaceA2B's object the lightest
    assert ("pick_attribute", "seen", "odd material") in failed
    assert ("place_a2b", "unseen_category", "smallest mass") in failed
    # what held: PickSpatial seen, where the relation alone tells target from distractor
    assert not any(f[:2] == ("pick_spatial", "seen") for f in failed)


def test_no_rule_finds_the_target_of_sets_v8():
    """InstructMove 2.0's stored sets (the symmetric sampler) fail no gated cell of the rules,
    and novelty sits exactly at chance in every split."""
    cells = audit.judge(choices(stored_specs(8)), trees=False)[0]
    assert not _failed(cells)
    novelty = [c for c in cells if c.adversary == "novelty" and c.robot == "pooled"]
    assert novelty and all(c.accuracy == pytest.approx(c.chance) for c in novelty)


def test_no_rule_fails_where_the_answer_is_drawn_blind(v7):
    draw = random.Random(7)
    blind = _answered(v7, lambda c: draw.randrange(len(c.options)))
    cells = audit.judge(blind, trees=False)[0]
    assert not _failed(cells)
    worst = max(c.z for c in cells if c.gated)
    assert worst < 3.0


def test_the_noise_yardstick_tells_v7s_shortcuts_from_v8s_noise(v7):
    """Answers redrawn by a fair die: v7's largest pooled rule excess lies past every draw
    where a shortcut was found (not the receptacle, which held); v8's lies among the draws,
    as does a set whose answers were themselves drawn blind."""
    for (_, kind), group in by_decision(v7).items():
        found = yardstick(group, draws=200)
        assert found.scenes > 300 and found.median > 0.0
        if kind == "object":
            assert found.share == 0.0 and found.observed > found.p95, found
    for group in by_decision(choices(stored_specs(8))).values():
        assert yardstick(group, draws=200).share > 0.05
    draw = random.Random(11)
    spatial = [c for c in v7 if c.family == "pick_spatial"]
    blind = yardstick(_answered(spatial, lambda c: draw.randrange(len(c.options))), draws=200)
    assert blind.share > 0.05 and blind.observed < blind.p95 + 0.02


def test_an_adversary_sees_neither_roles_nor_instruction():
    catalog = load_snapshot()
    spec = load_set("PlaceA2B-InstructMove", "franka", "seen")[0]
    other = next(k for k in spec.candidates if k != spec.target)
    roles = {spec.target: "distractor", other: "target"}
    swapped = dataclasses.replace(
        spec,
        objects=tuple(
            dataclasses.replace(o, role=roles.get(k, o.role)) for k, o in enumerate(spec.objects)
        ),
        target=other,
        instruction="put the thing somewhere",
        cue={},
        certificate={"visibility": spec.certificate["visibility"]},
    )
    before, after = choices_of(spec, catalog), choices_of(swapped, catalog)
    assert [c.options for c in before] == [c.options for c in after]
    assert before[0].answer != after[0].answer


def test_trees_learn_a_planted_signal_and_nothing_else(v7):
    spatial = [c for c in v7 if c.family == "pick_spatial" and c.split == "seen"]

    def heaviest(c):
        masses = [o.numbers["mass"] for o in c.options]
        return masses.index(max(masses))

    planted = learned.cross_validated(_answered(spatial, heaviest))
    assert sum(planted) / len(planted) > 0.9
    draw = random.Random(3)
    blind = learned.cross_validated(_answered(spatial, lambda c: draw.randrange(2)))
    assert abs(sum(blind) / len(blind) - 0.5) < 0.1


def test_cli_audit_writes_the_report_and_fails_sets_v7(tmp_path):
    from instructmove_ms.heldout import set_path, write_set
    from instructmove_ms.splits import EVAL_SPLITS
    from instructmove_ms.tasks import TASKS

    sets = tmp_path / "sets"  # the first 20 episodes of every v7 set, as episodes write lays them
    for env_id, task in TASKS.items():
        for robot in task.supported_robots:
            for split in EVAL_SPLITS:
                specs = load_set(env_id, robot, split, version=7)[:20]
                write_set(set_path(env_id, robot, split, sets), specs)
    out = tmp_path / "audit"
    args = ["--sets", str(sets), "--training-scenes", "6", "--fresh-scenes", "2"]
    assert main(["audit", *args, "--out", str(out)]) == 1
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sets"] == str(sets)
    assert summary["episodes"] == 20 * 24
    fresh = [c for c in summary["cells"] if c["source"] == "fresh"]
    assert {c["split"] for c in fresh} == {"seen", "unseen_instance", "unseen_category", "pooled"}
    assert {c["scenes"] for c in fresh if c["split"] == "seen"} == {2}
    failed = {(c["family"], c["split"], c["adversary"]) for c in summary["failed"]}
    assert ("pick_category", "unseen_instance", "novelty") in failed
    assert any(c["adversary"] == "trees, trained" for c in summary["cells"])
    assert "**failed**" in (out / "report.md").read_text()
    assert [(n["family"], n["kind"]) for n in summary["noise"]][-2:] == [
        ("place_a2b", "object"),
        ("place_a2b", "receptacle"),
    ]
    assert "## Noise at this size" in (out / "report.md").read_text()
    plots = sorted(p.name for p in out.glob("*.png"))
    assert plots == [
        "pick_attribute.png",
        "pick_category.png",
        "pick_spatial.png",
        "place_a2b.png",
        "place_a2b_receptacle.png",
    ]
    assert all((out / p).read_bytes()[:4] == b"\x89PNG" for p in plots)


def test_cli_audit_refuses_a_negative_scene_count(tmp_path, capsys):
    assert main(["audit", "--training-scenes", "-1", "--out", str(tmp_path)]) == 2
    assert "training scenes must be 0 or more, got -1" in capsys.readouterr().err
    assert main(["audit", "--fresh-scenes", "-2", "--out", str(tmp_path)]) == 2
    assert "fresh scenes must be 0 or more, got -2" in capsys.readouterr().err
