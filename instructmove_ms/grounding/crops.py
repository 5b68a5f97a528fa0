"""Every object of a scene as the policy's cameras show it at the first step.

A scene is reset in an rgb env at the policy's 224 x 224; every object is located in each
camera by segmentation and cut out as a square around it, resized to ``CROP`` x ``CROP``,
with the object's mask as a fourth channel (so a crop that also holds a neighbour says which
object is meant) and where the crop lay (``GEOMETRY``). A decision holds its options' crops
first (the candidates, or the receptacles), then the scene's other objects (a spatial
reference among them). Locating by segmentation is given: what is learned from the crops is
choosing, not detecting. Decisions are stored in shards (``Decisions.save``) that a rerun
reuses while the episodes they were rendered from are unchanged.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Sequence
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np
from PIL import Image

from ..audit.choices import decisions
from ..episode import EpisodeSpec
from ..files import atomic_path

#: Side of an option's crop (pixels).
CROP = 32
#: Cameras per robot whose crops an option holds (the scene cameras first, then the wrist's).
CAMERAS = 3
#: What each camera's crop says of where it lay: shown at all, its middle (x, y) and side as
#: fractions of the image, the square root of the option's pixels over the image side.
GEOMETRY = ("shown", "x", "y", "side", "pixels")
#: Fewer mask pixels than this and a camera does not show the option.
MIN_PIXELS = 4
#: The square around an option reaches this fraction of its larger side past each edge.
MARGIN = 0.15


def crop(rgb: np.ndarray, mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(4 x CROP x CROP uint8: RGB and the mask, the GEOMETRY figures) of the object whose
    ``mask`` (H x W bool) lies in ``rgb`` (H x W x 3 uint8); zeros where it is not shown."""
    h, w = mask.shape
    ys, xs = np.nonzero(mask)
    if len(ys) < MIN_PIXELS:
        return np.zeros((4, CROP, CROP), np.uint8), np.zeros(len(GEOMETRY), np.float32)
    y0, y1, x0, x1 = ys.min(), ys.max() + 1, xs.min(), xs.max() + 1
    side = max(y1 - y0, x1 - x0) * (1 + 2 * MARGIN)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    box = (cx - side / 2, cy - side / 2, cx + side / 2, cy + side / 2)
    layers = [  # apart: Pillow would weigh the colours by the mask as an alpha channel
        Image.fromarray(a).transform(
            (CROP, CROP), Image.Transform.EXTENT, box, Image.Resampling.BILINEAR
        )
        for a in (rgb, mask.astype(np.uint8) * 255)
    ]
    out = np.dstack([np.asarray(layer) for layer in layers]).transpose(2, 0, 1)
    figures = [1.0, cx / w, cy / h, side / w, math.sqrt(len(ys)) / w]
    return np.ascontiguousarray(out), np.array(figures, np.float32)


def digest(specs: Sequence[EpisodeSpec]) -> str:
    """What identifies the episodes a shard was rendered from."""
    return hashlib.sha256("\n".join(s.to_json() for s in specs).encode()).hexdigest()


@dataclass(frozen=True)
class Decisions:
    """Rendered decisions, one entry each in the per-decision arrays. Each decision's block
    of ``objects`` crops (and geometry) holds every object of its scene, its ``count``
    options first, and the blocks follow one another in decision order."""

    family: np.ndarray  # str
    kind: np.ndarray  # str: "object" or "receptacle"
    split: np.ndarray  # str
    robot: np.ndarray  # str
    seed: np.ndarray  # int
    answer: np.ndarray  # int: the answer's position among the decision's options
    count: np.ndarray  # int: options
    objects: np.ndarray  # int: objects of the scene (options first)
    instruction: np.ndarray  # str
    crops: np.ndarray  # (options, CAMERAS, 4, CROP, CROP) uint8
    geometry: np.ndarray  # (options, CAMERAS, len(GEOMETRY)) float32

    def __len__(self) -> int:
        return len(self.seed)

    def fingerprint(self) -> str:
        """What identifies these decisions (a model trained on them resumes only on them)."""
        h = hashlib.sha256()
        for name in ("seed", "answer", "count", "objects", "crops", "geometry"):
            h.update(np.ascontiguousarray(getattr(self, name)).tobytes())
        for name in ("family", "kind", "split", "robot", "instruction"):
            h.update("\n".join(map(str, getattr(self, name))).encode())
        return h.hexdigest()

    @property
    def starts(self) -> np.ndarray:
        """Where each decision's block starts in ``crops`` and ``geometry``."""
        return np.concatenate([[0], np.cumsum(self.objects)[:-1]]).astype(int)

    def take(self, rows: Sequence[int] | np.ndarray) -> Decisions:
        """The decisions at ``rows``, in that order."""
        rows = np.asarray(rows, int)
        starts = self.starts
        options = np.concatenate(
            [np.arange(starts[r], starts[r] + self.objects[r]) for r in rows] or [np.zeros(0, int)]
        )
        per = {f.name: getattr(self, f.name)[rows] for f in fields(self) if f.name in _PER}
        return Decisions(**per, crops=self.crops[options], geometry=self.geometry[options])

    def instructed(self, specs: Sequence[EpisodeSpec]) -> Decisions:
        """These decisions with the instructions and answers (-1 where an episode has no
        goal among a decision's options) of ``specs``: the same scenes, in the same order,
        under another condition. The pictures stay, since a condition changes only words."""
        texts, answers = [], []
        for spec in specs:
            for _, options, goal in decisions(spec, goal=False):
                texts.append(spec.instruction)
                answers.append(options.index(goal) if goal in options else -1)
        if len(answers) != len(self):
            raise ValueError(f"{len(answers)} decisions under the condition, {len(self)} rendered")
        return replace(self, instruction=np.array(texts), answer=np.array(answers))

    def save(self, path: Path, source: str) -> Path:
        """Write the decisions and the ``digest`` of their episodes to ``path`` atomically."""
        with atomic_path(path) as tmp:
            arrays = {f.name: getattr(self, f.name) for f in fields(self)}
            np.savez_compressed(tmp, source=np.array(source), **arrays)
        return path

    @staticmethod
    def load(path: Path, source: str | None = None) -> Decisions | None:
        """The decisions stored at ``path``; None where there are none or (given ``source``)
        they were rendered from other episodes."""
        if not Path(path).is_file():
            return None
        with np.load(path) as data:
            if source is not None and str(data["source"]) != source:
                return None
            return Decisions(**{f.name: data[f.name] for f in fields(Decisions)})

    @staticmethod
    def join(parts: Sequence[Decisions]) -> Decisions:
        names = [f.name for f in fields(Decisions)]
        return Decisions(**{n: np.concatenate([getattr(p, n) for p in parts]) for n in names})


#: The per-decision fields of ``Decisions``.
_PER = ("family", "kind", "split", "robot", "seed", "answer", "count", "objects", "instruction")


def of_views(views, spec: EpisodeSpec, goal: bool = True) -> Decisions:
    """Every decision of ``spec`` as ``views`` (a ``readers.material.Views`` of its scene)
    show it; ``goal`` False: of an episode without one too (answers -1)."""
    per: dict[str, list] = {name: [] for name in _PER}
    crops, geometry = [], []
    cameras = views.cameras[:CAMERAS]
    for kind, indices, answer in decisions(spec, goal):
        others = [k for k in range(len(spec.objects)) if k not in indices]
        row = {
            "family": spec.family,
            "kind": kind,
            "split": spec.split,
            "robot": spec.robot,
            "seed": spec.seed,
            "answer": indices.index(answer) if answer in indices else -1,
            "count": len(indices),
            "objects": len(spec.objects),
            "instruction": spec.instruction,
        }
        for name, value in row.items():
            per[name].append(value)
        for k in (*indices, *others):
            cut = [crop(views.rgb[c], views.mask(c, k)) for c in cameras]
            crops.append(np.stack([c for c, _ in cut]))
            geometry.append(np.stack([g for _, g in cut]))
    return Decisions(
        **{name: np.array(values) for name, values in per.items()},
        crops=np.stack(crops),
        geometry=np.stack(geometry),
    )


def rendered(renderer, env_id: str, specs: Sequence[EpisodeSpec]) -> Decisions:
    """Every decision of ``specs`` (normal episodes of ``env_id``) as ``renderer`` (a
    ``readers.material.SceneRenderer``) shows it."""
    if not specs:
        raise ValueError(f"no episodes of {env_id} to render")
    return Decisions.join([of_views(renderer.views(env_id, s), s) for s in specs])
