"""Layouts keep their clearance and stay in the workspace; impossible ones fail clearly."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from instructmove_ms.layout import (
    BACK_SPREAD,
    LayoutError,
    Workspace,
    corners,
    gap,
    sample_layout,
)


def test_layouts_respect_clearance_and_bounds():
    rng = np.random.default_rng(0)
    ws = Workspace()
    for _ in range(30):
        halves = [tuple(rng.uniform(0.01, 0.09, size=2)) for _ in range(6)]
        places = sample_layout(rng, halves, ws, clearance=0.05)
        quads = [corners(h, p) for h, p in zip(halves, places, strict=True)]
        for a, b in itertools.combinations(quads, 2):
            assert gap(a, b) >= 0.05 - 1e-9
        for p in places:
            assert ws.x[0] <= p.x <= ws.x[1] and ws.y[0] <= p.y <= ws.y[1]


def test_gap_measures_distance_between_rectangles():
    from instructmove_ms.layout import Placement

    a = corners((0.05, 0.05), Placement(0.0, 0.0, 0.0))
    b = corners((0.05, 0.05), Placement(0.2, 0.0, 0.0))
    assert gap(a, b) == pytest.approx(0.1)
    c = corners((0.05, 0.05), Placement(0.05, 0.0, 0.3))
    assert gap(a, c) == 0.0


def test_impossible_layout_raises_with_numbers():
    rng = np.random.default_rng(0)
    with pytest.raises(LayoutError, match="could not place 8 objects with 0.05 m"):
        sample_layout(rng, [(0.12, 0.12)] * 8, Workspace(), 0.05, tries_per_object=20, restarts=3)


def test_an_object_with_a_back_turns_it_away_from_the_robot_and_others_turn_freely():
    rng = np.random.default_rng(1)
    ws = Workspace()
    away, free = [], []
    for _ in range(40):
        places = sample_layout(rng, [(0.05, 0.05), (0.03, 0.02)], ws, 0.05, backs=[math.pi, None])
        bin_, other = places
        heading = bin_.yaw + math.pi  # where the back points, in the robot's frame
        off = math.remainder(heading - math.atan2(bin_.y, bin_.x), 2 * math.pi)
        away.append(abs(off))
        free.append(abs(math.remainder(other.yaw - math.atan2(other.y, other.x), 2 * math.pi)))
    assert max(away) <= BACK_SPREAD + 1e-9
    assert max(free) > math.pi / 2, "an object without a back faces any way"
