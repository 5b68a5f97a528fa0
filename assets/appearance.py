"""How instances look once rendered: each one's dominant colour, and the colour words and
attribute contrasts the camera can show.

``photometry`` measures them: an instance rendered alone on the table's colour under
ManiSkill's default lights, from four sides 0.45 m away and 45 degrees above, at the
default camera resolution; its pixels (from the segmentation) in CIE Lab, and the most
populated colour (a coarse Lab histogram's fullest bin, averaged) is its rendered colour.
Reference swatches render each vocabulary colour on a sphere of each material the same
way. The measurements of the shipped snapshots are stored beside them
(``snapshots/appearance/<snapshot>.json``, written by ``instructmove assets build``), so
composition reads the same colours on every machine and needs no renderer; other
snapshots' instances are rendered on first use.

``delta_e`` compares two colours (CIE94 with lightness weighted half; about 1 is a just
noticeable difference); ``DISTINCT`` is what the attribute cue needs between two objects it
tells apart by colour, ``MATCH`` how near an instance's rendered colour must be to a stated
colour's swatch for the camera to show that colour (``shown_color``).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from functools import cache
from importlib import resources
from pathlib import Path

import numpy as np

from ..files import write_text
from .catalog import DEFAULT_SNAPSHOT, Instance
from .identity import content_hash
from .vocab import MATERIALS

#: Rendered colours at least this far apart read as different colours (``delta_e``).
DISTINCT = 12.0
#: An instance shows a stated colour when its rendered colour is within this of the
#: colour's swatch.
MATCH = 15.0
#: Roughness difference that reads as another material (ceramic 0.25 vs plastic 0.45 does
#: not; wood 0.75 vs plastic does).
ROUGHNESS_STEP = 0.3
_BIN = 8.0  # Lab histogram bin for the dominant colour


def srgb_to_lab(rgb: np.ndarray) -> np.ndarray:
    """CIE Lab (D65) of sRGB values in [0, 1], shape (..., 3)."""
    rgb = np.asarray(rgb, dtype=float)
    linear = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    m = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    xyz = linear @ m.T / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.stack(
        [116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])],
        axis=-1,
    )


def delta_e(a, b) -> float:
    """CIE94 colour difference of two Lab colours, with lightness weighted half
    (``K_L = 2``: shading moves lightness across an object's faces, not its hue) and the
    two chromas' geometric mean as reference, so that it is symmetric."""
    (l1, a1, b1), (l2, a2, b2) = (np.asarray(v, float) for v in (a, b))
    c1, c2 = np.hypot(a1, b1), np.hypot(a2, b2)
    c, dc = np.sqrt(c1 * c2), c1 - c2
    dh2 = max((a1 - a2) ** 2 + (b1 - b2) ** 2 - dc**2, 0.0)
    return float(
        np.sqrt(((l1 - l2) / 2) ** 2 + (dc / (1 + 0.045 * c)) ** 2 + dh2 / (1 + 0.015 * c) ** 2)
    )


def dominant(lab: np.ndarray) -> np.ndarray:
    """The mean of the fullest coarse Lab bin of ``lab`` pixels (n, 3)."""
    bins = np.floor(lab / _BIN).astype(int)
    keys, inverse, counts = np.unique(bins, axis=0, return_inverse=True, return_counts=True)
    return lab[inverse.ravel() == int(np.argmax(counts))].mean(axis=0)


def table_path(snapshot: str = DEFAULT_SNAPSHOT) -> Path:
    """The file of a snapshot's rendered colours and swatches, beside the snapshot."""
    folder = resources.files("instructmove_ms.assets").joinpath("snapshots", "appearance")
    return Path(str(folder)) / f"{snapshot}.json"


def write_table_file(path: Path, instances: dict, swatches: dict) -> Path:
    """Write a table (atomically), one entry per line: ``instances`` maps a uuid to its
    content hash and rendered colour, ``swatches`` "colour/material" to a rendered colour."""

    def block(items: dict) -> str:
        lines = (
            f"{json.dumps(k)}: {json.dumps(v, sort_keys=True)}" for k, v in sorted(items.items())
        )
        return "{\n" + ",\n".join(lines) + "\n}"

    return write_text(
        path, f'{{"instances": {block(instances)},\n"swatches": {block(swatches)}}}\n'
    )


def rehash_table(path: Path, old: dict[str, str], instances: list[Instance]) -> int:
    """Move table ``path`` to the instances' current content hashes, where its entry was
    measured on the content whose former hash ``old`` gives (uuid -> hash); other entries
    are dropped (rendered again on use). Returns how many entries it kept."""
    table = json.loads(path.read_text())
    rows = {
        inst.uuid: {**table["instances"][inst.uuid], "hash": content_hash(inst)}
        for inst in instances
        if table["instances"].get(inst.uuid, {}).get("hash") == old.get(inst.uuid)
    }
    write_table_file(path, rows, table["swatches"])
    _table.cache_clear()
    lab_of.cache_clear()
    return len(rows)


@cache
def _table(snapshot: str = DEFAULT_SNAPSHOT) -> dict:
    path = table_path(snapshot)
    return json.loads(path.read_text()) if path.is_file() else {"instances": {}, "swatches": {}}


def stored_lab(instance: Instance) -> tuple[float, ...] | None:
    """The instance's colour from a shipped table measured on this very content."""
    digest = content_hash(instance)
    for path in sorted(table_path().parent.glob("*.json")):
        entry = _table(path.stem)["instances"].get(instance.uuid)
        if entry is not None and entry["hash"] == digest:
            return tuple(entry["lab"])
    return None


#: How to measure what the stored table lacks: ``photometry`` registers its renderers
#: here when imported (the envs import it; the core itself renders nothing).
MEASURES: dict[str, Callable] = {}


def _measured(kind: str, *args) -> tuple[float, ...]:
    if kind not in MEASURES:
        raise LookupError(
            f"no stored rendered colour for {args}: import instructmove_ms.assets.photometry "
            "to render it, or rebuild the table with `instructmove assets build`"
        )
    return MEASURES[kind](*args)


@cache
def lab_of(instance: Instance) -> tuple[float, ...]:
    """The instance's rendered colour: from a shipped table where it was measured on this
    very content (the same on every machine), else rendered now."""
    stored = stored_lab(instance)
    return stored if stored is not None else _measured("instance", instance)


@cache
def swatch(color: str, material: str) -> tuple[float, ...]:
    """The rendered colour of a 4 cm sphere of vocabulary ``color`` and ``material``."""
    stored = _table()["swatches"].get(f"{color}/{material}")
    return tuple(stored) if stored is not None else _measured("swatch", color, material)


def _material(instance: Instance, color: str) -> str:
    return next(p.material for p in instance.parts if p.color == color)


def color_match(instance: Instance) -> tuple[str, float]:
    """The stated colour whose swatch (in that colour's material) is nearest the
    instance's rendered colour, and how near."""
    lab = lab_of(instance)
    return min(
        ((c, delta_e(lab, swatch(c, _material(instance, c)))) for c in instance.colors),
        key=lambda pair: pair[1],
    )


def shown_color(instance: Instance) -> str | None:
    """The stated colour the camera shows (within ``MATCH`` of the rendered colour), None
    where it shows none of them: instructions name an object only by a colour it shows."""
    color, distance = color_match(instance)
    return color if distance <= MATCH else None


def look_differs(a: str, b: str) -> bool:
    """Whether materials ``a`` and ``b`` render differently: metallic or transmissive
    against not, or roughness ``ROUGHNESS_STEP`` apart."""
    ma, mb = MATERIALS[a], MATERIALS[b]
    return (
        abs(ma.metallic - mb.metallic) >= 0.5
        or abs(ma.transmission - mb.transmission) >= 0.5
        or abs(ma.roughness - mb.roughness) >= ROUGHNESS_STEP
    )
