"""Pin the light Franka's pictures of tests/test_franka_visuals.py (tests/data/franka_light/),
after its meshes or the scene changed:

    python tests/tools/record_franka_views.py
"""

import sys
from pathlib import Path

import imageio.v2 as imageio
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from test_franka_visuals import PINNED, POSES, pinned_path, views  # noqa: E402

from instructmove_ms.agents.franka import FrankaInstructMove  # noqa: E402

PINNED.mkdir(parents=True, exist_ok=True)
with pytest.MonkeyPatch.context() as monkeypatch:
    shots = views(FrankaInstructMove.urdf_path, monkeypatch)
for step, shot in zip(POSES, shots, strict=True):
    for camera, (rgb, _) in shot.items():
        imageio.imwrite(pinned_path(step, camera), rgb)
        print(pinned_path(step, camera))
