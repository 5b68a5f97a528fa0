"""Generated objects behave physically: containers hold things, objects rest where put."""

from __future__ import annotations

import math

import numpy as np
import pytest

from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets.sim import TIMESTEP, spawn, table_scene


def _simulate(scene, seconds: float) -> None:
    for _ in range(int(seconds / TIMESTEP)):
        scene.step()


def _tilt(entity) -> float:
    w, x, y, _ = entity.pose.q
    return math.degrees(math.acos(float(np.clip(1 - 2 * (x * x + y * y), -1, 1))))


@pytest.mark.parametrize("index", [0, 5])
def test_bowl_holds_a_small_object_dropped_into_it(index):
    catalog = load_snapshot()
    bowl = catalog.of_category("bowl")[index]
    small = catalog.of_category("garlic")[0]  # a small round object (the egg stands in a cup)
    scene = table_scene()
    bowl_entity = spawn(scene, bowl)
    _simulate(scene, 0.3)
    drop_z = bowl.height + 0.03
    egg = spawn(scene, small, xy=(0.01, -0.005), z=drop_z)
    _simulate(scene, 2.0)
    inside = np.asarray(egg.pose.p) - np.asarray(bowl_entity.pose.p)
    region = bowl.interior
    assert np.all(np.abs(inside[:2] - region.center[:2]) <= np.asarray(region.half) + 0.02)
    assert region.center[2] < inside[2] < drop_z - 0.01, "it rests inside, above the floor"
    assert _tilt(bowl_entity) < 3.0


def test_mug_stands_upright():
    scene = table_scene()
    for k, mug in enumerate(load_snapshot().of_category("mug")):
        entity = spawn(scene, mug, xy=(0.5 * k, 0.0))
        _simulate(scene, 1.5)
        assert _tilt(entity) < 2.0, mug.uuid
        assert np.linalg.norm(np.asarray(entity.pose.p[:2]) - (0.5 * k, 0.0)) < 0.005


def test_banana_stays_on_the_table():
    scene = table_scene()
    bananas = load_snapshot().of_category("banana")
    entities = [spawn(scene, b, xy=(0.5 * k, 0.0), yaw=0.3 * k) for k, b in enumerate(bananas)]
    _simulate(scene, 3.0)
    for k, entity in enumerate(entities):
        assert np.linalg.norm(np.asarray(entity.pose.p[:2]) - (0.5 * k, 0.0)) < 0.01
        assert entity.pose.p[2] < 0.01, "lying on the table"


def test_franka_gripper_picks_up_one_instance_of_every_super_category():
    from instructmove_ms.assets.grasp_trial import grasp_trial

    catalog = load_snapshot()
    sample = {}
    for inst in catalog.instances:
        if inst.is_graspable:
            sample.setdefault(inst.super_category, inst)
    results = grasp_trial(list(sample.values()))
    assert len(results) >= 15
    passed = [r for r in results if r.passed]
    assert len(passed) >= 0.9 * len(results), [r.category for r in results if not r.passed]
    assert all(r.rise >= 0.08 for r in passed), "a passed trial lifted the object"
