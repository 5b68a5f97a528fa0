"""Batched stage metrics: rotations, distances to object geometry and latched stage flags.

Every function here is a handful of batched tensor operations, the same on the CPU and the
GPU backend, whatever the number of sub-scenes and objects: a step's scoring runs them once.
"""

from __future__ import annotations

import torch


def rotate(quat: torch.Tensor, v: torch.Tensor, inverse: bool = False) -> torch.Tensor:
    """``v`` (..., 3) turned by the unit quaternions ``quat`` (..., 4, wxyz; broadcast
    against ``v``), or by their inverse: v + 2 w c + 2 u x c with c = u x v (the conjugate
    negates u)."""
    w, u = quat[..., :1], quat[..., 1:]
    if inverse:
        c = torch.linalg.cross(v, u)
        return torch.addcmul(v, w, c, value=2.0).sub_(torch.linalg.cross(u, c), alpha=2.0)
    c = torch.linalg.cross(u, v)
    return torch.addcmul(v, w, c, value=2.0).add_(torch.linalg.cross(u, c), alpha=2.0)


def select(values: torch.Tensor, column: torch.Tensor) -> torch.Tensor:
    """Each row's entry of ``values`` (N, K, ...) at the index in ``column`` (N, 1)."""
    trailing = values.shape[2:]
    if trailing:
        column = column.view(-1, 1, *(1 for _ in trailing)).expand(-1, 1, *trailing)
    return values.gather(1, column).squeeze(1)


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
    local = rotate(quat[:, None], rel, inverse=True).sub_(center[:, None])
    return local.abs_().sub_(half[:, None]).clamp_(min=0.0).norm(dim=-1)


def first_index(mask: torch.Tensor, score: torch.Tensor) -> torch.Tensor:
    """Along the last axis, the index of the lowest ``score`` among ``mask``-ed entries, -1
    if none."""
    lowest, idx = torch.where(mask, score, torch.inf).min(dim=-1)
    return idx.masked_fill_(lowest == torch.inf, -1)


def latch_first(current: torch.Tensor, candidate: torch.Tensor) -> torch.Tensor:
    """Keep ``current`` where set (>= 0), else take ``candidate``."""
    return torch.where(current >= 0, current, candidate)


class StageTracker:
    """Latched stage flags of N sub-scenes, named by a family's ``StageSchema``: each stage
    counts once its condition holds after the one before it has. Also latches the first
    object the robot reached and lifted (the target or a distractor: grounding errors).

    Each update makes new tensors (it never writes into the old ones), so what a step
    reported stays as it was after later steps and resets."""

    def __init__(self, names: tuple[str, ...], num_envs: int, device) -> None:
        #: (N, stages) latched flags, in the schema's order
        self.flags = torch.zeros((num_envs, len(names)), dtype=torch.bool, device=device)
        #: (N, 2) the first object reached and the first lifted, -1 before there is one
        self.first = torch.full((num_envs, 2), -1, dtype=torch.long, device=device)

    def reset(self, env_idx: torch.Tensor) -> None:
        self.flags = self.flags.index_fill(0, env_idx, False)
        self.first = self.first.index_fill(0, env_idx, -1)

    def update(
        self,
        dist: torch.Tensor,
        events: torch.Tensor,
        rise: torch.Tensor,
        conditions: torch.Tensor,
    ) -> None:
        """``dist`` and ``rise`` (N, K) per object; ``events`` (N, 2, K) whether each
        object is within reach and whether it is lifted; ``conditions`` (N, stages) per
        stage, in the schema's order. The first object reached is the nearest within reach,
        the first lifted the highest of those lifted.

        A stage is set when it was, or when its condition holds and the stage before it is
        set after this update. Since a set stage has every stage before it set, that is
        the running AND over the stages of (was set or holds now)."""
        self.first = latch_first(self.first, first_index(events, torch.stack((dist, -rise), 1)))
        self.flags = (self.flags | conditions).cummin(dim=1).values
