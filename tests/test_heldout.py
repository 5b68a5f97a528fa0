"""Stored held-out evaluation sets: complete, valid, reproducible, disjoint from training."""

from __future__ import annotations

import dataclasses
import json

import gymnasium as gym
import pytest

import instructmove_ms  # noqa: F401
from conftest import verify_spec
from instructmove_ms import heldout
from instructmove_ms.assets import load_snapshot
from instructmove_ms.cli import main
from instructmove_ms.episode import SPEC_VERSION
from instructmove_ms.splits import EVAL_SEED_BASE, EVAL_SPLITS, eval_seed
from instructmove_ms.tasks import FAMILIES, TASKS, visibility
from instructmove_ms.tasks.visibility import hidden_objects
from instructmove_ms.verify import certificate

SETS = [
    (env_id, robot) for env_id, spec in sorted(TASKS.items()) for robot in spec.supported_robots
]


@pytest.mark.parametrize(("env_id", "robot"), SETS)
def test_every_set_is_complete_valid_and_regenerates(env_id, robot):
    catalog = load_snapshot()
    for split in EVAL_SPLITS:
        specs = heldout.load_set(env_id, robot, split)
        assert len(specs) == heldout.EPISODES_PER_SET
        assert len({s.seed for s in specs}) == len(specs)
        for spec in specs:
            assert spec.seed >= EVAL_SEED_BASE, "never a training seed"
            assert (spec.family, spec.robot, spec.split) == (TASKS[env_id].family, robot, split)
            assert verify_spec(spec, catalog) == []
            assert spec.version == SPEC_VERSION
            assert spec.certificate == certificate(spec, catalog, FAMILIES[spec.family])
            assert hidden_objects(spec.certificate["visibility"]) == []
            watched = [row["index"] for row in spec.certificate["visibility"]["objects"]]
            assert watched == visibility.watched(spec)
            assert set(spec.candidates) | set(spec.destinations) <= set(watched)
        env = gym.make(
            env_id, robot_uids=robot, split=split, obs_mode="state", render_backend="none"
        )
        for spec in specs[:3]:  # the stored specs are what the code samples for their seeds
            sampled = env.unwrapped.sample_episode(spec.seed)
            assert sampled == dataclasses.replace(spec, certificate=sampled.certificate)
            assert {**sampled.certificate, "visibility": spec.certificate["visibility"]} == (
                spec.certificate
            )
            stored = env.unwrapped.under_condition(spec, "alternative_target")
            seeded = env.unwrapped.sample_episode(spec.seed, "alternative_target")
            assert stored == dataclasses.replace(seeded, certificate=stored.certificate)
        env.close()


def test_show_prints_a_stored_spec(capsys):
    assert (
        main(
            [
                "episodes",
                "show",
                "--task",
                "PickSpatial-InstructMove",
                "--split",
                "unseen_instance",
                "--index",
                "7",
            ]
        )
        == 0
    )
    spec = json.loads(capsys.readouterr().out)
    assert spec["split"] == "unseen_instance" and spec["robot"] == "franka"
    stored = heldout.load_set("PickSpatial-InstructMove", "franka", "unseen_instance")[7]
    assert spec["seed"] == stored.seed >= eval_seed("unseen_instance", 7)
    assert main(["episodes", "show", "--index", "100"]) == 2
    assert "--index 100" in capsys.readouterr().err


def test_a_contact_sheet_shows_each_episode_from_the_scene_camera(tmp_path):
    import cv2
    import numpy as np

    from instructmove_ms.episode_sheet import TILE_HEIGHT, TILE_WIDTH, episode_sheet

    path = episode_sheet("PickSpatial-InstructMove", "piperx", "seen", tmp_path / "s.png", 3, 2)
    sheet = cv2.imread(str(path))
    band = sheet.shape[0] // 2 - TILE_HEIGHT  # two rows: tile and caption each
    assert sheet.shape == (2 * (TILE_HEIGHT + band), 2 * TILE_WIDTH, 3) and band > 0
    env = gym.make(
        "PickSpatial-InstructMove",
        robot_uids="piperx",
        obs_mode="rgb",
        sensor_configs={"width": TILE_WIDTH, "height": TILE_HEIGHT},
    )
    spec = heldout.load_set("PickSpatial-InstructMove", "piperx", "seen")[1]
    obs, _ = env.reset(options={"episode": spec})
    env.close()
    image = obs["sensor_data"]["static_camera"]["rgb"][0].numpy()[..., ::-1]
    np.testing.assert_array_equal(sheet[:TILE_HEIGHT, TILE_WIDTH:], image)  # episode 1
    assert (sheet[TILE_HEIGHT + band :, TILE_WIDTH:] == 255).all(), "no fourth episode"
    caption = sheet[TILE_HEIGHT : TILE_HEIGHT + band, :TILE_WIDTH]
    assert (caption < 128).any() and (caption == 255).mean() > 0.6, "dark text on white"


def test_the_former_set_version_stays_loadable(tmp_path, capsys):
    """Version 2, kept for results published on it, loads through the API and the CLI and
    still passes the verifier; it holds the former wording of the same seeds."""
    env_id, robot = "PlaceA2B-InstructMove", "franka"
    old = heldout.load_set(env_id, robot, "seen", version=2)
    catalog = load_snapshot(old[0].snapshot)  # the plain snapshot it was published on
    new = heldout.load_set(env_id, robot, "seen")
    assert len(old) == len(new) == heldout.EPISODES_PER_SET
    assert sum(o.instruction != n.instruction for o, n in zip(old, new, strict=True)) > 50
    assert all(verify_spec(spec, catalog) == [] for spec in old[:10])
    config = heldout.evaluator_config(env_id, robot, "seen", episodes=3, version=2)
    assert [e.spec for e in config.episodes] == old[:3]
    path = tmp_path / "v2.json"
    args = ["eval", "--task", env_id, "--robot", robot, "--episodes", "2", "--set-version", "2"]
    assert main([*args, "--write-config", str(path)]) == 0
    assert "2 episodes ->" in capsys.readouterr().out
    written = heldout.EvaluatorConfig.load(path)
    assert [e.spec.instruction for e in written.episodes] == [s.instruction for s in old[:2]]
    show = ["episodes", "show", "--task", env_id, "--robot", robot, "--index", "4"]
    assert main([*show, "--set-version", "2"]) == 0
    assert json.loads(capsys.readouterr().out)["instruction"] == old[4].instruction
    with pytest.raises(SystemExit) as exc:
        main([*show, "--set-version", "9"])
    assert exc.value.code == 2 and "invalid choice: 9" in capsys.readouterr().err


def _textures_built(env) -> int:
    """How many render shapes of the scene's objects carry a texture."""
    from sapien.render import RenderBodyComponent

    return sum(
        shape.material.base_color_texture is not None
        for actor in env.unwrapped.objects
        for entity in actor._objs
        for shape in entity.find_component_by_type(RenderBodyComponent).render_shapes
    )


def test_version_3_plays_on_the_plain_snapshot_it_was_published_on():
    """Version 4 holds version 3's scenes on the printed snapshot (four scenes moved: a
    print changed what the camera shows of an object); a version-3 episode names the
    plain snapshot, and an env made on the printed one builds it plain."""
    printed = load_snapshot("printed")
    env_id, robot = "PickCategory-InstructMove", "franka"
    old, new = (heldout.load_set(env_id, robot, "seen", version=v) for v in (3, 4))
    assert {s.snapshot for s in old} == {"default"} and {s.snapshot for s in new} == {"printed"}
    assert [heldout.scene_key(s) for s in old] == [heldout.scene_key(s) for s in new]
    k = next(  # an episode with a printed object
        k
        for k, s in enumerate(new)
        if any(p.texture for o in s.objects for p in printed[o.uuid].parts)
    )
    env = gym.make(env_id, robot_uids=robot, obs_mode="state")
    try:
        for spec, wanted in ((new[k], True), (old[k], False)):
            env.reset(options={"episode": spec.to_dict()})
            assert env.unwrapped.catalog_of(spec).name == spec.snapshot
            assert (_textures_built(env) > 0) == wanted
    finally:
        env.close()


#: (older version, newer version, their snapshots, the library revision between them, the
#: least share of the newer version's scenes the older one holds).
REVISED_SETS = [(4, 5, "printed", "detailed", 2, 0.5), (6, 7, "detailed", "recognisable", 3, 0.0)]


@pytest.mark.parametrize(
    ("old_v", "new_v", "old_snap", "new_snap", "revision", "share"), REVISED_SETS
)
def test_a_set_on_a_revised_library_plays_its_assets_and_the_older_keeps_its_own(
    old_v, new_v, old_snap, new_snap, revision, share
):
    """Version 5 is version 4 on the ``detailed`` snapshot (library revision 2), version 7
    version 6 on ``recognisable`` (revision 3): none of the newer scenes holds a build the
    revision replaced, the revised assets are there; an older episode still builds its own
    assets."""
    from instructmove_ms.assets.generators import REVISIONS

    revised = {c for c, builds in REVISIONS.items() if revision in builds}
    older, newer = load_snapshot(old_snap), load_snapshot(new_snap)
    env_id, robot = "PickCategory-InstructMove", "franka"
    old, new = (heldout.load_set(env_id, robot, "seen", version=v) for v in (old_v, new_v))
    assert {s.snapshot for s in old} == {old_snap} and {s.snapshot for s in new} == {new_snap}
    shared = {heldout.scene_key(s) for s in old} & {heldout.scene_key(s) for s in new}
    assert len(shared) >= share * len(new)
    assert all(o.uuid in newer for s in new for o in s.objects)
    news = [o.uuid for s in new for o in s.objects if newer[o.uuid].category in revised]
    assert news and not any(u in older for u in news)
    spec = next(s for s in old if any(older[o.uuid].category in revised for o in s.objects))
    env = gym.make(env_id, robot_uids=robot, obs_mode="state")
    try:
        env.reset(options={"episode": spec.to_dict()})
        assert env.unwrapped.catalog_of(spec).name == old_snap
        built = {o.uuid for o in env.unwrapped.episode.objects}
        assert built == {o.uuid for o in spec.objects} and not built & set(news)
        assert any(older[u].category in revised for u in built)
    finally:
        env.close()


def test_an_older_episode_with_a_replaced_asset_is_played_and_scored(tmp_path):
    """The planner oracle picks up a version-4 object whose category revision 2 rebuilt, in
    an env made on the newest snapshot: planning and scoring read the episode's own
    snapshot (they once read the env's, where that uuid does not exist)."""
    from instructmove_ms.assets.generators import REVISIONS
    from instructmove_ms.evaluation import evaluate_config
    from instructmove_ms.policies import REFERENCE_POLICIES

    revised = {c for c, builds in REVISIONS.items() if 2 in builds}  # what revision 2 rebuilt
    printed = load_snapshot("printed")
    env_id, robot = "PickCategory-InstructMove", "franka"
    spec = next(
        s
        for s in heldout.load_set(env_id, robot, "seen", version=4)
        if printed[s.target_object.uuid].category in revised
    )
    config = heldout.config_of(env_id, robot, "seen", "normal", [spec])
    evaluate_config(REFERENCE_POLICIES["oracle"](), config, tmp_path)
    (row,) = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    assert row["success"] and row["stage_score"] == 1.0, row
