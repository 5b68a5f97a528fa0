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
from instructmove_ms.sampler import SAMPLER
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
            env_id,
            robot_uids=robot,
            split=split,
            sampler=specs[0].sampler,
            obs_mode="state",
            render_backend="none",
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


def test_the_package_holds_benchmarks_1_0_and_2_0():
    """InstructMove 1.0 is set version 7 (sampler 1), 2.0 set version 8 (the symmetric
    sampler) and the default; no other stored set ships."""
    stored = sorted(p.name for p in heldout.default_folder().parent.iterdir() if p.is_dir())
    assert stored == ["v7", "v8"] and heldout.SET_VERSIONS == (7, 8) == (7, heldout.SET_VERSION)
    assert heldout.benchmark_name(7) == "InstructMove 1.0 (held-out sets v7)"
    assert heldout.benchmark_name() == "InstructMove 2.0 (held-out sets v8)"


def test_envs_draw_by_default_with_the_sampler_of_the_current_sets():
    """Training scenes hold out what the current sets test: the envs' default sampler is
    the one every stored episode of the current version came from."""
    env_id = "PickCategory-InstructMove"
    specs = heldout.load_set(env_id, TASKS[env_id].default_robot, "unseen_instance")
    assert {s.sampler for s in specs} == {SAMPLER}
    env = gym.make(env_id, obs_mode="state", render_backend="none")
    assert env.unwrapped.sampler == SAMPLER
    env.close()


def test_a_released_version_stays_loadable_beside_a_newer_one(tmp_path, capsys):
    """Beside InstructMove 2.0 (sets v8, the default), 1.0's sets still load by
    ``--set-version 7``, through the API and the CLI."""
    env_id, robot = "PlaceA2B-InstructMove", "franka"
    released = heldout.load_set(env_id, robot, "seen", version=7)
    newer = heldout.load_set(env_id, robot, "seen")
    assert newer == heldout.load_set(env_id, robot, "seen", version=8)
    assert newer != released and {s.sampler for s in newer} == {2}
    assert heldout.benchmark_name(7) == "InstructMove 1.0 (held-out sets v7)"
    assert heldout.benchmark_name() == "InstructMove 2.0 (held-out sets v8)"
    config = heldout.evaluator_config(env_id, robot, "seen", episodes=3, version=7)
    assert [e.spec for e in config.episodes] == released[:3]
    path = tmp_path / "v7.json"
    args = ["eval", "--task", env_id, "--robot", robot, "--episodes", "2", "--set-version", "7"]
    assert main([*args, "--write-config", str(path)]) == 0
    assert "2 episodes ->" in capsys.readouterr().out
    written = heldout.EvaluatorConfig.load(path)
    assert [e.spec for e in written.episodes] == released[:2]
    show = ["episodes", "show", "--task", env_id, "--robot", robot, "--index", "4"]
    assert main([*show, "--set-version", "7"]) == 0
    assert json.loads(capsys.readouterr().out)["instruction"] == released[4].instruction
    assert main(show) == 0
    assert json.loads(capsys.readouterr().out)["instruction"] == newer[4].instruction
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


def test_an_episode_plays_on_the_snapshot_it_names(user_snapshot):
    """An episode that names another snapshot (here a plain copy of the library, as a
    later benchmark version's sets may name one) is built from that snapshot in any env:
    plain where it names the plain one, printed where it names ``recognisable``."""
    from instructmove_ms.assets.snapshot import Frozen

    catalog = load_snapshot()
    env_id, robot = "PickCategory-InstructMove", "franka"
    spec = next(  # an episode with a printed object
        s
        for s in heldout.load_set(env_id, robot, "seen")
        if any(p.texture for o in s.objects for p in catalog[o.uuid].parts)
    )
    plain = user_snapshot("plain_copy", [o.category for o in spec.objects], 10, Frozen(False))
    env = gym.make(env_id, robot_uids=robot, obs_mode="state")
    try:
        for played, printed in ((spec, True), (dataclasses.replace(spec, snapshot=plain), False)):
            env.reset(options={"episode": played.to_dict()})
            assert env.unwrapped.catalog_of(played).name == played.snapshot
            assert {o.uuid for o in env.unwrapped.episode.objects} == {o.uuid for o in spec.objects}
            assert (_textures_built(env) > 0) == printed
    finally:
        env.close()


def test_an_episode_on_another_snapshot_is_played_and_scored(user_snapshot, tmp_path):
    """The planner oracle picks up a target that only the episode's own snapshot holds (an
    instance past the shipped ones), in an env made on ``recognisable``: planning and
    scoring read the episode's snapshot (they once read the env's, where that uuid does
    not exist)."""
    from instructmove_ms.assets.snapshot import Frozen
    from instructmove_ms.evaluation import evaluate_config
    from instructmove_ms.policies import REFERENCE_POLICIES

    env_id, robot = "PickCategory-InstructMove", "franka"
    stored = heldout.load_set(env_id, robot, "seen")[0]
    shipped = load_snapshot()
    per_category = len(shipped.of_category(stored.target_object.category))
    categories = [o.category for o in stored.objects]
    wider = load_snapshot(user_snapshot("wider", categories, per_category + 1, Frozen()))
    extra = wider.of_category(stored.target_object.category)[per_category]
    assert extra.uuid not in shipped
    objects = list(stored.objects)
    objects[stored.target] = dataclasses.replace(objects[stored.target], uuid=extra.uuid)
    spec = dataclasses.replace(stored, snapshot="wider", objects=tuple(objects), certificate={})
    config = heldout.config_of(env_id, robot, "seen", "normal", [spec])
    evaluate_config(REFERENCE_POLICIES["oracle"](), config, tmp_path)
    (row,) = [json.loads(line) for line in (tmp_path / "episodes.jsonl").read_text().splitlines()]
    assert row["success"] and row["stage_score"] == 1.0, row


def test_writing_sets_never_defaults_to_the_released_ones(capsys):
    """``episodes write`` needs ``--out``: the package's released sets are never written
    over."""
    before = heldout.checksums(heldout.default_folder())
    with pytest.raises(SystemExit) as exc:
        main(["episodes", "write", "--task", "PickCategory-InstructMove", "--n", "1"])
    assert exc.value.code == 2 and "--out" in capsys.readouterr().err
    assert heldout.checksums(heldout.default_folder()) == before
