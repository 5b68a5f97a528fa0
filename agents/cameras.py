"""Camera rigs described by published intrinsics, at a configurable resolution."""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Default resolution of robot cameras: small enough for CPU rendering, 16:9 like the
#: real sensors. Override with ``gym.make(..., sensor_configs=dict(width=W, height=H))``
#: (up to 1280x720); the field of view stays the published one.
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
