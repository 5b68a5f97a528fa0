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


class StageTracker:
    """Latched stage flags of N sub-scenes, named by a family's ``StageSchema``: each stage
    counts once its condition holds after the one before it has. Also latches the first
    object the robot reached and lifted (the target or a distractor: grounding errors)."""

    def __init__(self, names: tuple[str, ...], num_envs: int, device) -> None:
        self.flags = {s: torch.zeros(num_envs, dtype=torch.bool, device=device) for s in names}
        self.reached_object = torch.full((num_envs,), -1, dtype=torch.long, device=device)
        self.lifted_object = torch.full_like(self.reached_object, -1)

    def reset(self, env_idx: torch.Tensor) -> None:
        for flag in self.flags.values():
            flag[env_idx] = False
        self.reached_object[env_idx] = -1
        self.lifted_object[env_idx] = -1

    def update(
        self,
        dist: torch.Tensor,
        within: torch.Tensor,
        lifted: torch.Tensor,
        rise: torch.Tensor,
        conditions: list[torch.Tensor],
    ) -> None:
        """``dist``, ``within``, ``lifted``, ``rise`` (N, K) per object; ``conditions`` (N,)
        per stage, in the schema's order."""
        self.reached_object = latch_first(self.reached_object, first_index(within, dist))
        self.lifted_object = latch_first(self.lifted_object, first_index(lifted, -rise))
        previous = None
        for flag, condition in zip(self.flags.values(), conditions, strict=True):
            flag |= condition if previous is None else condition & previous
            previous = flag
