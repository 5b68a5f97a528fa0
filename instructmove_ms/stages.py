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
    """Latched stage flags of N sub-scenes; each stage counts only after the previous one.

    Pick families: reach -> lift. PlaceA2B adds reach_place -> place after lift. Without a
    target (generic, empty, absent_object conditions) only any-object stages move.
    """

    STAGES = ("reach", "lift", "reach_place", "place")

    def __init__(self, num_envs: int, device) -> None:
        self.flags = {
            s: torch.zeros(num_envs, dtype=torch.bool, device=device) for s in self.STAGES
        }
        self.reached_object = torch.full((num_envs,), -1, dtype=torch.long, device=device)
        self.lifted_object = torch.full_like(self.reached_object, -1)

    def reset(self, env_idx: torch.Tensor) -> None:
        for flag in self.flags.values():
            flag[env_idx] = False
        self.reached_object[env_idx] = -1
        self.lifted_object[env_idx] = -1

    def update(
        self,
        target: torch.Tensor,
        dist: torch.Tensor,
        within: torch.Tensor,
        lifted: torch.Tensor,
        rise: torch.Tensor,
        over_goal: torch.Tensor,
        placed: torch.Tensor,
    ) -> None:
        """``target`` (N,) index or -1; ``dist``, ``within``, ``lifted``, ``rise`` (N, K) per
        object; ``over_goal``, ``placed`` (N,) for the target object."""
        rows = torch.arange(target.shape[0], device=target.device)
        has = target >= 0
        t = target.clamp(min=0)
        f = self.flags
        self.reached_object = latch_first(self.reached_object, first_index(within, dist))
        self.lifted_object = latch_first(self.lifted_object, first_index(lifted, -rise))
        f["reach"] |= has & within[rows, t]
        f["lift"] |= has & lifted[rows, t] & f["reach"]
        f["reach_place"] |= over_goal & f["lift"]
        f["place"] |= placed & f["reach_place"]
