"""The ``instructmove`` command line."""

from __future__ import annotations

import json

import pytest

from instructmove_ms.cli import main


def test_episode_prints_the_seeds_spec(capsys):
    assert main(["episode", "--seed", "5", "--no-render"]) == 0
    spec = json.loads(capsys.readouterr().out)
    assert spec["seed"] == 5 and spec["family"] == "pick_category"
    assert spec["objects"][spec["target"]]["role"] == "target"


def test_envs_and_assets_list_what_is_registered(capsys):
    assert main(["envs"]) == 0
    assert "PickCategory-InstructMove" in capsys.readouterr().out
    assert main(["assets", "list", "--category", "mug", "--format", "jsonl"]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert len(rows) == 10 and {r["category"] for r in rows} == {"mug"}
    assert all(r["is_container"] for r in rows)
    required = {
        "uuid",
        "domain",
        "super_category",
        "category",
        "colors",
        "shape",
        "material",
        "height",
        "is_graspable",
        "is_container",
        "split",
        "grasps",
        "expressions",
    }
    assert required <= set(rows[0])
    assert all(r["grasps"] and len(r["expressions"]["seen"]) >= 5 for r in rows)


def test_bad_split_is_a_clear_error(capsys):
    assert main(["episode", "--split", "nope", "--no-render"]) == 2
    err = capsys.readouterr().err
    assert "'nope'" in err and "'unseen_instance'" in err


def test_eval_writes_reports_and_rejects_unknown_policies(tmp_path, capsys):
    out = tmp_path / "eval"
    args = [
        "eval",
        "--task",
        "PickCategory-InstructMove",
        "--robot",
        "franka",
        "--policy",
        "random",
        "--episodes",
        "1",
        "--out",
        str(out),
    ]
    assert main(args) == 0
    assert "| pick_category | franka | seen | normal | 1 |" in capsys.readouterr().out
    assert json.loads((out / "summary.json").read_text())["episodes"] == 1
    assert main([*args[:5], "--policy", "nonsense", "--out", str(out)]) == 2
    assert "'nonsense'" in capsys.readouterr().err


def test_assets_rehash_names_an_unknown_snapshot(capsys):
    assert main(["assets", "rehash", "nosuch"]) == 2
    err = capsys.readouterr().err
    assert "unknown snapshot 'nosuch'" in err and "'recognisable'" in err


@pytest.mark.parametrize("size", ["128", "128x", "0x96", "axb"])
def test_a_bad_image_size_is_a_clear_error(size, capsys):
    argv = ["eval", "--task", "PickCategory-InstructMove", "--policy", "ws://127.0.0.1:9"]
    with pytest.raises(SystemExit) as exit_:
        main([*argv, "--out", "x", "--image-size", size])
    assert exit_.value.code == 2
    assert f"image size must be WxH, e.g. 128x96, got {size!r}" in capsys.readouterr().err


def test_export_lerobot_names_the_formats_it_writes(capsys):
    argv = ["export", "lerobot", "--traj", "t.h5", "--out", "x", "--repo-id", "me/x"]
    with pytest.raises(SystemExit):
        main([*argv, "--format", "v2.0"])
    err = capsys.readouterr().err
    assert "'v2.0'" in err and "'v3.0'" in err and "'v2.1'" in err


def test_assets_build_never_changes_the_released_snapshot(capsys):
    """The shipped snapshot is InstructMove 1.0's: a build that would write other instances
    into it is refused, naming what would change, and the file stays as it was."""
    from instructmove_ms.assets import snapshot as snap

    path = snap.snapshot_path(snap.DEFAULT_SNAPSHOT)
    before = path.read_bytes()
    assert main(["assets", "build", "--per-category", "1"]) == 2
    err = capsys.readouterr().err
    assert "'recognisable' ships with a released benchmark" in err
    assert "114 instances, not 1140" in err and "--name NEW" in err
    assert path.read_bytes() == before
