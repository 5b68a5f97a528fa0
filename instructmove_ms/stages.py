"""Batched stage metrics: distances to object geometry and latched stage flags."""

from __future__ import annotations

import torch
from mani_skill.utils.geometry.rotation_conversions import quaternion_apply, quaternion_invert


def box_distance(
    points: torch.Tensor,
    pos: torch.Tensor,
    quat: torch.Tensor,
    center: torch.Tensor,
    half: torch.Tensor,
) -> torch.Tensor:
    """Distance from each of ``points`` (N, P, 3) to each object's box: (N, P, K), 0 inside.

    Objects have world poses ``pos`` (N, K, 3), ``quat`` (N, K, 4, wxyz); each box has its
    ``center`` and ``half`` extents (N, K, 3) in the object's frame.
    """
    rel = points[:, :, None, :] - pos[:, None]
    inv = quaternion_invert(quat)[:, None].expand(*rel.shape[:-1], 4)
    local = quaternion_apply(inv, rel) - center[:, None]
    outside = (local.abs() - half[:, None]).clamp(min=0.0)
    return torch.linalg.norm(outside, dim=-1)


def first_index(mask: torch.Tensor, score: torch.Tensor) -> torch.Tensor:
    """Per row, the index of the lowest ``score`` among ``mask``-ed entries, -1 if none."""
    masked = torch.where(mask, score, torch.full_like(score, torch.inf))
    idx = masked.argmin(dim=1)
    return torch.where(mask.any(dim=1), idx, torch.full_like(idx, -1))


def latch_first(current: torch.Tensor, candidate: torch.Tensor) -> torch.Tensor:
    """Keep ``current`` where set (>= 0), else take ``candidate``."""
    return torch.where(current >= 0, current, candidate)
