"""What the robot's scene cameras see of each candidate, receptacle and reference object.

Measured from segmentation renders of the agent's ``scene_cameras`` (static or exterior,
not the wrist cameras) at the env's resolution, after the reset: an object's visible
pixels, and their fraction of its own area (the pixels it covers when every other object
and the robot are hidden). An object counts as visible when one scene camera shows at
least ``MIN_PIXELS`` of it and at least ``MIN_FRACTION`` of its own area. Held-out sets and
demos keep only episodes whose watched objects (``watched``) are all visible.
"""

from __future__ import annotations

from collections.abc import Iterable

import sapien
import torch

#: Smallest visible part of a candidate in one scene camera: pixels at the default
#: resolution (160 x 90), and the fraction of the object's own area.
MIN_PIXELS = 10
MIN_FRACTION = 0.3


def _render_bodies(entities: Iterable) -> list:
    bodies = (e.find_component_by_type(sapien.render.RenderBodyComponent) for e in entities)
    return [b for b in bodies if b is not None]


def _segmentations(env) -> dict[str, torch.Tensor]:
    """(H, W) per-scene ids of sub-scene 0 seen by each scene camera, as the scene is now."""
    env.scene.update_render(update_sensors=True, update_human_render_cameras=False)
    out = {}
    for uid in env.agent.scene_cameras:
        camera = env._sensors[uid]
        camera.capture()
        obs = camera.get_obs(rgb=False, depth=False, position=False, segmentation=True)
        out[uid] = obs["segmentation"][0, ..., 0]
    return out


def watched(spec) -> list[int]:
    """The objects that must be visible: the candidates, the receptacles and the
    reference object a relation names."""
    reference = spec.cue.get("reference")
    return sorted(
        {*spec.candidates, *spec.destinations, *([] if reference is None else [reference])}
    )


def measure(env) -> dict:
    """Visibility of sub-scene 0's candidates and receptacles, per scene camera:
    ``{"cameras", "min_pixels", "min_fraction", "objects": [{"index", "pixels",
    "fraction"}]}`` with one figure per camera; ``hidden_objects`` says which fail."""
    env = env.unwrapped
    spec = env.episodes[0]
    ids = {k: int(env.objects[k].per_scene_id[0]) for k in range(len(env.objects))}
    together = _segmentations(env)
    robot = [part.entity for link in env.agent.robot.links for part in link._objs]
    rows = []
    for k in watched(spec):
        others = [e for j, obj in enumerate(env.objects) if j != k for e in obj._objs]
        hidden = [(b, b.visibility) for b in _render_bodies(others + robot)]
        for body, _ in hidden:
            body.visibility = 0.0
        try:
            alone = _segmentations(env)
        finally:
            for body, value in hidden:
                body.visibility = value
        pixels = [int((together[c] == ids[k]).sum()) for c in together]
        own = [int((alone[c] == ids[k]).sum()) for c in together]
        rows.append(
            {
                "index": k,
                "pixels": pixels,
                "fraction": [
                    round(p / o, 3) if o else 0.0 for p, o in zip(pixels, own, strict=True)
                ],
            }
        )
    return {
        "cameras": list(together),
        "min_pixels": MIN_PIXELS,
        "min_fraction": MIN_FRACTION,
        "objects": rows,
    }


def hidden_objects(figures: dict) -> list[int]:
    """The watched objects that no scene camera shows well enough (empty: all visible)."""
    return [
        row["index"]
        for row in figures["objects"]
        if not any(
            p >= MIN_PIXELS and f >= MIN_FRACTION
            for p, f in zip(row["pixels"], row["fraction"], strict=True)
        )
    ]
