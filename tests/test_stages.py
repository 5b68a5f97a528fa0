"""Stage helpers: rotations, distances to rotated boxes, first-event latching and the
latched stage flags."""

from __future__ import annotations

import itertools
import math

import torch
from mani_skill.utils.geometry.rotation_conversions import quaternion_apply, quaternion_invert

from instructmove_ms.tasks.stages import (
    StageTracker,
    box_distance,
    first_index,
    latch_first,
    rotate,
    select,
)


def test_rotate_matches_maniskill_quaternions():
    gen = torch.Generator().manual_seed(0)
    quat = torch.nn.functional.normalize(torch.randn(5, 6, 4, generator=gen), dim=-1)
    v = torch.randn(5, 6, 3, generator=gen)
    torch.testing.assert_close(rotate(quat, v), quaternion_apply(quat, v))
    torch.testing.assert_close(
        rotate(quat, v, inverse=True), quaternion_apply(quaternion_invert(quat), v)
    )
    torch.testing.assert_close(rotate(quat, rotate(quat, v), inverse=True), v)


def test_select_takes_each_rows_entry():
    values = torch.arange(2 * 3 * 4, dtype=torch.float32).view(2, 3, 4)
    column = torch.tensor([[2], [0]])
    assert select(values, column).tolist() == [values[0, 2].tolist(), values[1, 0].tolist()]
    assert select(values[..., 0], column).tolist() == [8.0, 12.0]


def test_box_distance_handles_rotation_and_several_points():
    yaw = math.pi / 2  # the box's long x side now runs along world y
    quat = torch.tensor([[[math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)]]])
    pos = torch.tensor([[[1.0, 0.0, 0.0]]])
    center = torch.zeros(1, 1, 3)
    half = torch.tensor([[[0.2, 0.05, 0.05]]])
    points = torch.tensor([[[1.0, 0.15, 0.0], [1.0, 0.3, 0.0], [1.2, 0.0, 0.0]]])
    d = box_distance(points, pos, quat, center, half)
    assert d.shape == (1, 3, 1)
    torch.testing.assert_close(d[0, :, 0], torch.tensor([0.0, 0.1, 0.15]))


def test_first_index_and_latch():
    mask = torch.tensor([[False, True, True], [False, False, False]])
    score = torch.tensor([[0.0, 0.3, 0.1], [0.0, 0.0, 0.0]])
    first = first_index(mask, score)
    assert first.tolist() == [2, -1]
    assert latch_first(torch.tensor([0, -1]), first).tolist() == [0, -1]


def test_first_index_along_the_last_axis_of_stacked_events():
    mask = torch.tensor([[[True, True, False], [False, False, False]]])
    score = torch.tensor([[[0.3, 0.1, 0.0], [0.0, 0.0, 0.0]]])
    assert first_index(mask, score).tolist() == [[1, -1]]


def test_stage_flags_latch_in_order():
    """Every prefix-closed state and every condition pattern of four stages: a stage is
    set when it was, or when its condition holds and the stage before it is set now."""
    for old in itertools.product([False, True], repeat=4):
        if any(old[i] and not old[i - 1] for i in range(1, 4)):
            continue  # a set stage has the ones before it set
        for holds in itertools.product([False, True], repeat=4):
            expected, before = [], True
            for was, now in zip(old, holds, strict=True):
                before = was or (now and before)
                expected.append(before)
            tracker = StageTracker(("a", "b", "c", "d"), 1, "cpu")
            tracker.flags = torch.tensor([old])
            none = torch.zeros(1, 2, 3, dtype=torch.bool)
            tracker.update(torch.zeros(1, 3), none, torch.zeros(1, 3), torch.tensor([holds]))
            assert tracker.flags[0].tolist() == expected, (old, holds)
