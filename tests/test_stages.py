"""Stage helpers: distances to rotated boxes and first-event latching."""

from __future__ import annotations

import math

import torch

from instructmove_ms.tasks.stages import box_distance, first_index, latch_first


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
