"""Camera rigs described by published intrinsics, at a configurable resolution."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from mani_skill.sensors.camera import CameraConfig

#: Default resolution of robot cameras: small enough for CPU rendering, 16:9 like the
#: real sensors. Override with ``gym.make(..., sensor_configs=dict(width=W, height=H))``
#: (up to 1280x720); both published fields of view stay, whatever the aspect
#: (``PublishedCameraConfig``): a 224 x 224 image shows the whole 16:9 view, squeezed.
DEFAULT_WIDTH, DEFAULT_HEIGHT = 160, 90
REFERENCE_WIDTH, REFERENCE_HEIGHT = 1280, 720


@dataclass(frozen=True)
class Intrinsics:
    """Published focal lengths (pixels) at the reference 1280x720 resolution."""

    fx: float
    fy: float

    @property
    def fov_x(self) -> float:
        return 2.0 * math.atan(REFERENCE_WIDTH / 2.0 / self.fx)

    @property
    def fov_y(self) -> float:
        """Vertical field of view (ManiSkill's ``fov``) in radians."""
        return 2.0 * math.atan(REFERENCE_HEIGHT / 2.0 / self.fy)


@dataclass
class PublishedCameraConfig(CameraConfig):
    """A camera with ``published`` focal lengths (at 1280x720) scaled to whatever ``width`` x
    ``height`` is configured, so both published fields of view hold (ManiSkill's ``fov`` fixes
    only the vertical one). They replace any ``fov`` or ``intrinsic`` given."""

    published: Intrinsics | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.published is not None:
            sx, sy = self.width / REFERENCE_WIDTH, self.height / REFERENCE_HEIGHT
            self.fov = None
            self.intrinsic = np.array(
                [
                    [self.published.fx * sx, 0.0, self.width / 2],
                    [0.0, self.published.fy * sy, self.height / 2],
                    [0.0, 0.0, 1.0],
                ]
            )
