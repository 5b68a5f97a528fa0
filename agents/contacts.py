"""Pairwise contact forces of one physics step, read once however many pairs are asked for.

ManiSkill's ``scene.get_pairwise_contact_forces(a, b)`` reads every contact of the CPU scene
for each pair it is asked about; a grasp check asks about two fingers per arm per object.
``ContactForces`` reads the contact list once and keeps each pair's contacts, then sums a
pair's impulses as ManiSkill does (same contacts, same order, same arithmetic: the same
forces). On the GPU it defers to ManiSkill's queries, which are batched already.
"""

from __future__ import annotations

import numpy as np
import torch
from mani_skill.utils import common


class ContactForces:
    """``forces(a, b)``: the (N, 3) contact force on ``a`` from ``b`` (Newtons) at the
    scene's last physics step. Make a new one after the scene steps."""

    def __init__(self, scene) -> None:
        self.scene = scene
        self._pairs: dict[frozenset, list] | None = None

    def _read(self) -> dict[frozenset, list]:
        """The step's contacts by the pair of entities they join, in PhysX's order."""
        pairs: dict[frozenset, list] = {}
        for contact in self.scene.px.get_contacts():
            first, second = (body.entity for body in contact.bodies)
            pairs.setdefault(frozenset((first, second)), []).append(contact)
        return pairs

    def __call__(self, a, b) -> torch.Tensor:
        if self.scene.gpu_sim_enabled:
            return self.scene.get_pairwise_contact_forces(a, b)
        if self._pairs is None:
            self._pairs = self._read()
        mine, theirs = a._bodies[0].entity, b._bodies[0].entity
        total = np.zeros(3)
        for contact in self._pairs.get(frozenset((mine, theirs)), ()):
            impulse = np.sum([point.impulse for point in contact.points], axis=0)
            total += impulse * (1 if contact.bodies[0].entity == mine else -1)  # on the first
        return common.to_tensor(total)[None, :] / self.scene.px.timestep
