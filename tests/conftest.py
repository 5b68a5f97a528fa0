"""Shared fixtures: envs are expensive to build, so modules share them."""

from __future__ import annotations

import gymnasium as gym
import pytest

import instructmove_ms  # noqa: F401  (registers envs and robots)

ENV_ID = "PickCategory-InstructMove"


def pytest_report_header(config) -> str:
    from instructmove_ms.floats import describe

    return describe()


def make_env(env_id: str = ENV_ID, **kwargs):
    """A state env for the scripted tests. Their seeds were picked for their scenes (a cup on
    its saucer, a target on the right) as InstructMove 1.0's sampler draws them."""
    kwargs.setdefault("robot_uids", "franka")  # the scripted tests drive a Franka
    kwargs.setdefault("sampler", 1)
    kwargs.setdefault("obs_mode", "state")
    kwargs.setdefault("render_backend", "none")
    return gym.make(env_id, **kwargs)


@pytest.fixture(scope="module")
def oracle_plans():
    """The planner oracle's actions on the harness tests' stored episodes (``oracle_replay``)."""
    from oracle_replay import COUNT, EPISODES, oracle_actions

    return oracle_actions(EPISODES, list(range(COUNT)))


@pytest.fixture(scope="module")
def oracle_reference(tmp_path_factory):
    """``instructmove eval`` of the oracle on the same stored episodes: the rows a harness
    must reproduce."""
    from oracle_replay import COUNT, EPISODES, oracle_rows

    return oracle_rows(EPISODES, COUNT, tmp_path_factory.mktemp("oracle"))


@pytest.fixture(scope="module")
def state_env():
    env = make_env()
    yield env
    env.close()


def hand_spec(placed, robot: str, robot_qpos, target: int = 0):
    """A hand-made PickCategory episode: ``placed`` lists (category, pose) with the pose as
    (x, y) or a full (x, y, z, qw, qx, qy, qz); the first instance of each category is used."""
    from instructmove_ms.assets import load_snapshot
    from instructmove_ms.episode import EpisodeSpec, ObjectSpec

    catalog = load_snapshot()
    objects = tuple(
        ObjectSpec(
            catalog.of_category(cat)[0].uuid,
            cat,
            "target" if k == target else "distractor",
            tuple(pose) if len(pose) == 7 else (*pose, 0.002, 1.0, 0.0, 0.0, 0.0),
        )
        for k, (cat, pose) in enumerate(placed)
    )
    return EpisodeSpec(
        family="pick_category",
        robot=robot,
        snapshot=catalog.name,
        split="train",
        seed=0,
        instruction=f"pick up the {objects[target].category.replace('_', ' ')}",
        objects=objects,
        target=target,
        candidates=tuple(range(len(objects))),
        robot_qpos=tuple(float(q) for q in robot_qpos),
    )


def verify_spec(spec, catalog) -> list[str]:
    """The verifier's problems with ``spec``, for its family and its robot's gripper."""
    from mani_skill.agents.registration import REGISTERED_AGENTS

    from instructmove_ms.tasks import FAMILIES
    from instructmove_ms.verify import verify

    opening = REGISTERED_AGENTS[spec.robot].agent_cls.gripper.max_width
    return verify(spec, catalog, FAMILIES[spec.family], opening)


@pytest.fixture
def user_snapshot(monkeypatch, tmp_path):
    """Writes a snapshot of its own into a temporary user folder: ``make(name, categories,
    per_category, frozen)`` returns its name; every one is gone after the test."""
    from instructmove_ms.assets import snapshot as snap

    monkeypatch.setattr(snap, "user_snapshot_dir", lambda: tmp_path / "snapshots")

    def make(name: str, categories: list[str], per_category: int, frozen) -> str:
        entries = snap.build_entries(sorted(set(categories)), per_category, frozen)
        snap.write_snapshot(tmp_path / "snapshots" / f"{name}.json", name, entries, frozen)
        return name

    yield make
    snap.load_snapshot.cache_clear()


@pytest.fixture
def own_registry(monkeypatch):
    """A copy of the asset generators' registry to register into; the real one is left
    untouched."""
    from instructmove_ms.assets.generators import GENERATORS, REVISIONS, registry

    monkeypatch.setattr(registry, "REVISIONS", {c: dict(b) for c, b in REVISIONS.items()})
    monkeypatch.setattr(registry, "GENERATORS", dict(GENERATORS))
    return registry


def with_a_tag(before):
    """A rebuild of ``before``: the same object with a tag on it (a part it lacked)."""

    def build(d):
        traits = before(d)
        d.box("tag", (0.004, 0.004, 0.001), (0.0, 0.0, 0.001), "paper", "red", visual_only=True)
        return traits

    return build


@pytest.fixture
def revision_4(own_registry, monkeypatch, tmp_path):
    """A library revision 4 that rebuilds the mouse (its build came in revision 2), and a
    user snapshot folder of its own."""
    from instructmove_ms.assets import snapshot as snap
    from instructmove_ms.assets.generators import registry, revised

    monkeypatch.setattr(registry, "LIBRARY", 4)
    revised("mouse", 4)(with_a_tag(registry.GENERATORS["mouse"].build))
    monkeypatch.setattr(snap, "user_snapshot_dir", lambda: tmp_path)
    snap.load_snapshot.cache_clear()
    yield registry
    snap.load_snapshot.cache_clear()
