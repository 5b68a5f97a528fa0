"""The README's main command end to end, scaled down: demos, MCAP, evaluation, report."""

from __future__ import annotations

import json

import pytest

from instructmove_ms.export import read_episode
from instructmove_ms.quickstart import POLICIES, QuickstartSettings, run
from instructmove_ms.tasks import TASKS


def test_quickstart_writes_every_output_and_resumes(tmp_path):
    settings = QuickstartSettings(
        demos=1, episodes=1, videos=1, workers=1, export_size=32, lerobot_size=32
    )
    report = run(tmp_path, settings)
    text = report.read_text()
    for task, spec in TASKS.items():
        assert (tmp_path / "demos" / f"{task}_{spec.default_robot}.h5").is_file()
        assert len(list((tmp_path / "eval" / task / "oracle" / "videos").glob("*.mp4"))) == 1
    (mcap,) = sorted((tmp_path / "mcap").glob("*.mcap"))
    episode = read_episode(mcap)
    assert episode.instruction and f"`mcap/{mcap.name}`" in text
    for robot in {spec.default_robot for spec in TASKS.values()}:
        info = json.loads((tmp_path / "lerobot" / robot / "meta" / "info.json").read_text())
        assert info["robot_type"] == robot and info["codebase_version"] == "v3.0"
        assert f"`lerobot/{robot}`" in text
    header = next(line for line in text.splitlines() if line.startswith("| family"))
    assert all(f" {p} " in header for p in POLICIES)
    runs = json.loads((tmp_path / "summary.json").read_text())
    assert sorted(runs) == sorted(POLICIES) and all(len(runs[p]) == len(TASKS) for p in POLICIES)
    before = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*.h5")}
    run(tmp_path, settings)  # everything done: nothing is redone
    assert {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*.h5")} == before


def test_quickstart_rejects_bad_settings():
    with pytest.raises(ValueError, match="quickstart demos must be at least 1, got 0"):
        QuickstartSettings(demos=0)
