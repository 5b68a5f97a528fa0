"""The Franka's light visual meshes (agents/descriptions/franka): ManiSkill's description but
for them, and the same picture. Each pose of ``POSES`` (the rest pose, and two joint targets
of the recorded PickCategory demo where both scene cameras see the arm) is rendered at
224 x 224 by every camera with ManiSkill's full meshes and with ours: the images differ by at
most ``MAX_MAD`` levels on average, and the robot's silhouettes overlap by ``MIN_IOU`` at least
wherever it covers ``MIN_PIXELS``. The light pictures are pinned (tests/data/franka_light/,
``tests/tools/record_franka_views.py`` writes them) and held within ``MAX_MAD`` of them."""

from __future__ import annotations

import json
import re
from pathlib import Path

import gymnasium as gym
import imageio.v2 as imageio
import numpy as np
import pytest
import torch
import trimesh
from mani_skill.agents.robots.panda.panda import Panda

from instructmove_ms.agents.franka import FrankaInstructMove

DATA = Path(__file__).parent / "data"
PINNED = DATA / "franka_light"
#: The recorded case's scene is drawn by InstructMove 1.0's sampler.
RECORDED_SAMPLER = 1
CASE = json.loads((DATA / "step_reference.json").read_text())["cases"][
    "PickCategory-InstructMove/franka"
]
#: None: the episode's rest pose; k: the arm at the recorded demo's joint targets of step k.
POSES = (None, 80, 120)
SIZE = 224
#: A person would not tell these apart: mean absolute difference over the image (levels of
#: 255) and intersection over union of the robot's pixels.
MAX_MAD = 2.0
MIN_IOU = 0.98
MIN_PIXELS = 200
MESH = re.compile(r'filename="[^"]*meshes/(visual|collision)/([^"]+)"')


def views(urdf: str, monkeypatch) -> list[dict[str, tuple[np.ndarray, np.ndarray]]]:
    """Per pose of ``POSES``, each camera's (rgb, robot mask) with the robot of ``urdf``."""
    monkeypatch.setattr(FrankaInstructMove, "urdf_path", urdf)
    env = gym.make(
        "PickCategory-InstructMove",
        robot_uids="franka",
        sampler=RECORDED_SAMPLER,
        obs_mode="rgb+segmentation",
        sensor_configs=dict(width=SIZE, height=SIZE),
    )
    env.reset(seed=CASE["seed"])
    robot = env.unwrapped.agent.robot
    ids = [link._objs[0].entity.per_scene_id for link in robot.get_links()]
    shots = []
    for step in POSES:
        qpos = robot.get_qpos().clone()
        if step is not None:
            qpos[0, :7] = torch.tensor(CASE["actions"][step][:7])
            qpos[0, 7:] = 0.04  # fingers open
        robot.set_qpos(qpos)
        sensors = env.unwrapped.get_obs()["sensor_data"]
        shots.append(
            {
                camera: (
                    data["rgb"][0].numpy(),
                    np.isin(data["segmentation"][0, ..., 0].numpy(), ids),
                )
                for camera, data in sensors.items()
            }
        )
    env.close()
    return shots


def pinned_path(step: int | None, camera: str) -> Path:
    return PINNED / f"{'rest' if step is None else f'step{step}'}_{camera}.png"


def mad(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a.astype(int) - b.astype(int)).mean())


def test_the_light_description_is_maniskills_but_for_its_visual_meshes():
    ours = Path(FrankaInstructMove.urdf_path)
    theirs = Path(Panda.urdf_path)
    assert MESH.sub(r"\1/\2", ours.read_text()) == MESH.sub(r"\1/\2", theirs.read_text())
    collision = sorted(
        {name for kind, name in MESH.findall(ours.read_text()) if kind == "collision"}
    )
    for name in collision:
        source = theirs.parent / "franka_description" / "meshes" / "collision" / name
        assert (ours.parent / "meshes" / "collision" / name).read_bytes() == source.read_bytes()
    srdf = ours.with_suffix(".srdf").read_bytes()  # the loader reads it beside the URDF
    assert srdf == theirs.with_suffix(".srdf").read_bytes()


def test_light_visual_meshes_are_one_sided_where_maniskills_are_double_sided():
    """A renderer culls the back faces of the light meshes only (no camera sees them)."""

    def sides(urdf: Path) -> set:
        names = {name for kind, name in MESH.findall(urdf.read_text()) if kind == "visual"}
        folder = next(p for p in urdf.parent.rglob("visual") if (p / min(names)).exists())
        parts = [
            g
            for name in names
            for g in trimesh.load(folder / name, force="scene").geometry.values()
        ]
        return {bool(g.visual.material.doubleSided) for g in parts}

    assert sides(Path(Panda.urdf_path)) == {True}
    assert sides(Path(FrankaInstructMove.urdf_path)) == {False}


def test_the_light_description_moves_as_the_full_one(monkeypatch):
    """The recorded Franka demo's actions replay to the same bits with either description."""
    from test_step_reference import replayed

    case = "PickCategory-InstructMove/franka"
    runs = []
    for urdf in (Panda.urdf_path, FrankaInstructMove.urdf_path):
        monkeypatch.setattr(FrankaInstructMove, "urdf_path", urdf)
        runs.append(replayed(case, CASE["seed"], np.asarray(CASE["actions"]), CASE["steps"]))
    assert runs[0] == runs[1]


@pytest.fixture(scope="module")
def pictures():
    with pytest.MonkeyPatch.context() as monkeypatch:
        full = views(Panda.urdf_path, monkeypatch)
        light = views(FrankaInstructMove.urdf_path, monkeypatch)
    return full, light


def test_light_meshes_show_the_picture_of_the_full_ones(pictures):
    full, light = pictures
    robot_seen = 0
    for step, a, b in zip(POSES, full, light, strict=True):
        for camera, (rgb, mask) in a.items():
            light_rgb, light_mask = b[camera]
            assert mad(rgb, light_rgb) <= MAX_MAD, (step, camera, mad(rgb, light_rgb))
            if max(mask.sum(), light_mask.sum()) >= MIN_PIXELS:
                robot_seen += 1
                iou = (mask & light_mask).sum() / (mask | light_mask).sum()
                assert iou >= MIN_IOU, (step, camera, iou)
    assert robot_seen >= 2 * len(POSES), "the robot is in view of most pictures"


def test_light_pictures_stay_as_pinned(pictures):
    _, light = pictures
    for step, shot in zip(POSES, light, strict=True):
        for camera, (rgb, _) in shot.items():
            pinned = imageio.imread(pinned_path(step, camera))
            assert mad(rgb, pinned) <= MAX_MAD, (step, camera, mad(rgb, pinned))
