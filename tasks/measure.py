"""What one step of the scene shows, read once: the objects' and TCPs' poses, the objects'
velocities when asked, and the step's contacts for grasp checks.

On the CPU backend a read walks the SAPIEN entities once and makes one tensor, instead of a
ManiSkill ``Pose`` per body; on the GPU backend it takes ManiSkill's batched reads of the
physics buffers.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import sapien
import torch

from instructmove_ms.agents.contacts import ContactForces


class SceneReader:
    """Reads the raw poses (position, wxyz quaternion) of a fixed list of ManiSkill
    ``objects`` (actors) and ``tcps`` (links), each merged over the sub-scenes, in one
    pass; the objects' linear velocities; and the contacts of the ``fingers`` (links)."""

    def __init__(self, objects: Sequence, tcps: Sequence, fingers: Sequence) -> None:
        self.objects, self.tcps, self.fingers = list(objects), list(tcps), list(fingers)
        self.scene = self.objects[0].scene
        # per body, per sub-scene: the SAPIEN entity (a link's is its component's entity)
        self._entities = [
            [o if isinstance(o, sapien.Entity) else o.entity for o in body._objs]
            for body in (*self.objects, *self.tcps)
        ]

    def _poses(self) -> torch.Tensor:
        """(N, objects + tcps, 7) raw poses."""
        if self.scene.gpu_sim_enabled:
            bodies = (*self.objects, *self.tcps)
            return torch.stack([body.pose.raw_pose for body in bodies], dim=1)
        parts = []
        for i in range(len(self._entities[0])):  # sub-scene by sub-scene, body by body
            for entities in self._entities:
                pose = entities[i].pose
                parts += (pose.p, pose.q)
        flat = np.concatenate(parts).astype(np.float32, copy=False)
        return torch.from_numpy(flat.reshape(len(self._entities[0]), len(self._entities), 7))

    def measure(self) -> Measured:
        """This step's poses and contacts."""
        poses = self._poses()
        k = len(self.objects)
        return Measured(poses[:, :k], poses[:, k:], ContactForces(self.scene, self.fingers), self)

    def velocities(self) -> torch.Tensor:
        """(N, objects, 3) linear velocities."""
        if self.scene.gpu_sim_enabled:
            return torch.stack([body.linear_velocity for body in self.objects], dim=1)
        rows = [[b.linear_velocity for b in body._bodies] for body in self.objects]
        return torch.from_numpy(np.asarray(rows, dtype=np.float32).transpose(1, 0, 2))


@dataclass
class Measured:
    """One step's measurements, shared by ``evaluate``, the reward and the observation:
    raw poses of the ``objects`` (N, K, 7) and of each arm's ``tcp`` (N, arms, 7), the
    step's ``contacts``, and what is read only when asked: velocities and grasp flags (by
    object index)."""

    objects: torch.Tensor
    tcp: torch.Tensor
    contacts: ContactForces
    reader: SceneReader
    grasped: dict[int, torch.Tensor] = field(default_factory=dict)
    _velocity: torch.Tensor | None = None

    @property
    def pos(self) -> torch.Tensor:
        return self.objects[..., :3]

    @property
    def quat(self) -> torch.Tensor:
        return self.objects[..., 3:]

    @property
    def velocity(self) -> torch.Tensor:
        """(N, K, 3) the objects' linear velocities."""
        if self._velocity is None:
            self._velocity = self.reader.velocities()
        return self._velocity
