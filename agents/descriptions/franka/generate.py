"""Writes this folder's light Franka Panda description from ManiSkill's (``panda_v2.urdf``).

    pip install trimesh fast-simplification   # the tools this script needs, not the package
    python agents/descriptions/franka/generate.py

The URDF is ManiSkill's with two changes only: its visual meshes are ours, each part of each
link's mesh decimated to ``KEEP`` of its triangles (at least ``MIN_TRIANGLES``) with its own
material drawn one-sided, and its mesh paths point into this folder. Collision meshes are
copied byte for byte, the SRDF beside it (the link pairs that never collide) is ManiSkill's,
and joints, inertials and limits are ManiSkill's text, so physics is unchanged (the same
bits); only what the cameras show is lighter (a 224 x 224 picture cannot show 135k
triangles). The meshes and PROVENANCE.md are committed; ``tests/test_franka_visuals.py``
holds them to the full meshes' pictures and to ManiSkill's URDF.

ManiSkill's meshes declare their materials double-sided, so a renderer draws every back face
too; the links are shells seen from outside, whose back faces a camera never shows, and a CPU
rasteriser pays for them (about a third of the robot's render): ours are one-sided.
"""

from __future__ import annotations

import hashlib
import re
import shutil
from pathlib import Path

import fast_simplification
import numpy as np
import trimesh
from mani_skill.agents.robots.panda.panda import Panda

HERE = Path(__file__).resolve().parent
SOURCE = Path(Panda.urdf_path)
URDF = HERE / "panda_light.urdf"
#: The fraction of each visual part's triangles kept (by mesh; the arm's links ``KEEP``), and
#: the fewest any part keeps. The hand, which the wrist camera sees from a few centimetres,
#: keeps more, and so do the fingers, small already; links 1-4, smooth housings whose surface
#: moved least at ``KEEP`` (0.3-0.4 mm on average, against up to 1.3 mm for the others),
#: keep less.
KEEP = 0.08
KEEP_OF = {"hand.glb": 0.3, "finger.glb": 0.5} | {f"link{k}.glb": 0.05 for k in range(1, 5)}
MIN_TRIANGLES = 64
#: Edges sharper than this keep a crease (split normals); gentler ones are smooth-shaded.
CREASE = np.deg2rad(30.0)
MESH = re.compile(r'filename="franka_description/meshes/(visual|collision)/([^"]+)"')


def one_sided(part: trimesh.Trimesh) -> trimesh.Trimesh:
    """``part`` (changed in place) with its material drawn one-sided (back faces culled)."""
    part.visual.material = part.visual.material.copy()
    part.visual.material.doubleSided = False
    return part


def decimated(part: trimesh.Trimesh, keep: float) -> trimesh.Trimesh:
    """``part`` with ``keep`` of its triangles, its material (one-sided), and normals creased
    at edges sharper than ``CREASE``."""
    target = max(MIN_TRIANGLES, int(len(part.faces) * keep))
    if target >= len(part.faces):
        return one_sided(part.copy())
    welded = part.copy()  # the file repeats a vertex per corner: weld them to collapse edges
    welded.merge_vertices(merge_tex=True, merge_norm=True)
    points, faces = fast_simplification.simplify(
        np.asarray(welded.vertices, np.float64), np.asarray(welded.faces), target_count=target
    )
    light = trimesh.graph.smooth_shade(trimesh.Trimesh(points, faces), angle=CREASE)
    light.visual = trimesh.visual.TextureVisuals(material=part.visual.material)
    return one_sided(light)


def light_glb(source: Path, target: Path) -> tuple[int, int]:
    """Write the decimated copy of visual mesh ``source``; (triangles before, after)."""
    keep = KEEP_OF.get(source.name, KEEP)
    scene = trimesh.load(source, force="scene")
    out = trimesh.Scene()
    before = after = 0
    for k, node in enumerate(sorted(scene.graph.nodes_geometry, key=lambda n: scene.graph[n][1])):
        transform, name = scene.graph[node]
        part = scene.geometry[name]
        light = decimated(part, keep)
        before, after = before + len(part.faces), after + len(light.faces)
        # node names of their own: the loader's carry random suffixes
        out.add_geometry(light, node_name=f"{source.stem}_{k}", geom_name=name, transform=transform)
    target.write_bytes(out.export(file_type="glb"))
    return before, after


def main() -> None:
    text = SOURCE.read_text()
    meshes = sorted(set(MESH.findall(text)))
    rows = []
    for kind, name in meshes:
        source = SOURCE.parent / "franka_description" / "meshes" / kind / name
        target = HERE / "meshes" / kind / name
        target.parent.mkdir(parents=True, exist_ok=True)
        if kind == "collision":
            shutil.copyfile(source, target)
            continue
        before, after = light_glb(source, target)
        digest = hashlib.sha256(source.read_bytes()).hexdigest()[:16]
        rows.append(f"| {name} | {before:,} | {after:,} | `{digest}` |")
    URDF.write_text(MESH.sub(r'filename="meshes/\1/\2"', text))
    # the loader reads the SRDF beside a URDF (the link pairs that never collide)
    shutil.copyfile(SOURCE.with_suffix(".srdf"), URDF.with_suffix(".srdf"))
    totals = [int(r.split("|")[i].replace(",", "")) for r in rows for i in (2, 3)]
    (HERE / "PROVENANCE.md").write_text(
        PROVENANCE.format(
            keep=KEEP,
            hand=KEEP_OF["hand.glb"],
            finger=KEEP_OF["finger.glb"],
            smooth=KEEP_OF["link1.glb"],
            floor=MIN_TRIANGLES,
            rows="\n".join(rows),
            before=f"{sum(totals[0::2]):,}",
            after=f"{sum(totals[1::2]):,}",
        )
    )
    print(f"wrote {URDF.name}: visual triangles {sum(totals[0::2]):,} -> {sum(totals[1::2]):,}")


PROVENANCE = """# Light Franka Panda description: provenance

Source: ManiSkill 3.0.1's `mani_skill/assets/robots/panda/panda_v2.urdf` and its
`franka_description` meshes, which come from Franka Emika's `franka_ros` description,
Apache License 2.0 (Copyright Franka Emika GmbH); these derived files keep that licence.

Made by `generate.py` in this folder: the URDF text is ManiSkill's with mesh paths pointing
here, and the SRDF beside it is ManiSkill's; collision meshes are copied byte for byte; each
part of each visual mesh is decimated by quadric edge collapse (fast-simplification) to
{keep:.0%} of its triangles (the hand, seen from a few centimetres by the wrist camera, to
{hand:.0%}, the fingers to {finger:.0%}, the smooth links 1-4 to {smooth:.0%}), at least
{floor}, keeping its material but drawn one-sided (ManiSkill's are double-sided: a renderer
draws the back faces of every shell, which no camera sees), with normals creased at edges
sharper than 30 degrees.

| visual mesh | triangles | light | source sha256 (16) |
|---|---|---|---|
{rows}
| all | {before} | {after} | |
"""


if __name__ == "__main__":
    main()
