"""Pairwise contact forces of one physics step, read once however many pairs are asked for.

ManiSkill's ``scene.get_pairwise_contact_forces(a, b)`` reads every contact of the CPU scene
for each pair it is asked about; a grasp check asks about two fingers per arm per object.
``ContactForces`` reads the contact list once and keeps each pair's contacts (only those of
the ``watched`` bodies, the fingers, when given), then sums a pair's impulses as ManiSkill
does (same contacts, same order, same arithmetic: the same forces). On the GPU it defers to
ManiSkill's queries, which are batched already. ``touching(a, b)`` answers whether a pair
touches at all, so that a grasp check of an untouched finger costs no tensor: from the two
bodies' bounding boxes when they are far apart (the contact list of a scene grows with its
objects: reading it costs about 0.5 us a contact), else from the list.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import torch
from mani_skill.utils import common

#: How much farther apart than their contact offsets two bodies' bounding boxes must be for
#: ``touching`` to answer no without the contact list: more than bodies move in a substep
#: (0.05 m in 1/120 s is 6 m/s), so that no contact of the last substep can join them.
SLACK = 0.05


def _apart(a, b, margin: float) -> bool:
    """Whether the bounding boxes of rigid bodies ``a`` and ``b`` (SAPIEN components) are
    more than ``margin`` apart along some axis."""
    (lo_a, hi_a), (lo_b, hi_b) = (
        a.get_global_aabb_fast().tolist(),
        b.get_global_aabb_fast().tolist(),
    )
    return any(lo > hi + margin for lo, hi in zip(lo_a, hi_b, strict=True)) or any(
        lo > hi + margin for lo, hi in zip(lo_b, hi_a, strict=True)
    )


class ContactForces:
    """``forces(a, b)``: the (N, 3) contact force on ``a`` from ``b`` (Newtons) at the
    scene's last physics step, for ManiSkill actors or links ``a`` and ``b`` (one of them
    ``watched`` when bodies are watched). Make a new one after the scene steps."""

    def __init__(self, scene, watched: Iterable = ()) -> None:
        self.scene = scene
        self._watched = frozenset(body._bodies[0] for body in watched)
        self._pairs: dict[frozenset, list] | None = None
        self._margin = SLACK + 2 * scene.sim_config.scene_config.contact_offset

    def _read(self) -> dict[frozenset, list]:
        """The step's contacts (of the watched bodies) by the pair of rigid bodies they
        join, in PhysX's order."""
        pairs: dict[frozenset, list] = {}
        watched = self._watched
        for contact in self.scene.px.get_contacts():
            first, second = contact.bodies
            if not watched or first in watched or second in watched:
                pairs.setdefault(frozenset((first, second)), []).append(contact)
        return pairs

    def _contacts(self, a, b) -> list:
        mine, theirs = a._bodies[0], b._bodies[0]
        if self._watched and not {mine, theirs} & self._watched:
            raise ValueError(f"neither {a.name!r} nor {b.name!r} is a watched body")
        if self._pairs is None:
            self._pairs = self._read()
        return self._pairs.get(frozenset((mine, theirs)), [])

    def touching(self, a, b) -> bool:
        """Whether ``a`` and ``b`` may touch in some sub-scene: on the CPU, whether PhysX
        lists a contact between them; on the GPU always (its forces are batched)."""
        if self.scene.gpu_sim_enabled:
            return True
        if self._pairs is None and _apart(a._bodies[0], b._bodies[0], self._margin):
            return False
        return bool(self._contacts(a, b))

    def __call__(self, a, b) -> torch.Tensor:
        if self.scene.gpu_sim_enabled:
            return self.scene.get_pairwise_contact_forces(a, b)
        mine = a._bodies[0]
        total = np.zeros(3)
        for contact in self._contacts(a, b):
            impulse = np.sum([point.impulse for point in contact.points], axis=0)
            total += impulse * (1 if contact.bodies[0] is mine else -1)  # on the first
        return common.to_tensor(total)[None, :] / self.scene.px.timestep
