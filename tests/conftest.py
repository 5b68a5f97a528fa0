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
    kwargs.setdefault("robot_uids", "franka")  # the scripted tests drive a Franka
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
