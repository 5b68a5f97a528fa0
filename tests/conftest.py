"""Shared fixtures: envs are expensive to build, so modules share them."""

from __future__ import annotations

import gymnasium as gym
import pytest

import instructmove_ms  # noqa: F401  (registers envs and robots)

ENV_ID = "PickCategory-InstructMove"


def blas_kernel() -> str:
    """The kernel numpy's OpenBLAS runs on this machine (``OPENBLAS_CORETYPE`` forces one)."""
    import ctypes
    import glob
    import os

    import numpy as np

    libs = os.path.join(os.path.dirname(np.__file__), os.pardir, "numpy.libs", "libopenblas*")
    for path in glob.glob(libs):
        lib = ctypes.CDLL(path)
        for name in ("openblas_get_corename64_", "openblas_get_corename"):
            if hasattr(lib, name):
                getter = getattr(lib, name)
                getter.restype = ctypes.c_char_p
                return getter().decode()
    return "unknown"


def pytest_report_header(config) -> str:
    import os

    import numpy as np

    disabled = os.environ.get("NPY_DISABLE_CPU_FEATURES", "") or "none"
    return f"numpy {np.__version__}, BLAS kernel {blas_kernel()}, CPU features off: {disabled}"


def make_env(env_id: str = ENV_ID, **kwargs):
    kwargs.setdefault("robot_uids", "franka")  # the scripted tests drive a Franka
    kwargs.setdefault("obs_mode", "state")
    kwargs.setdefault("render_backend", "none")
    return gym.make(env_id, **kwargs)


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
        snapshot="default",
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
