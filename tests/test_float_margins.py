"""Float margins: no decision of the library or of a stored episode sits so near its
threshold that last-bit noise (another BLAS kernel, numpy's CPU features, another CPU)
could flip it. Run once per suite; ``test_portability.py`` runs the comparisons with
recorded references under each floating-point set-up."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from floatnoise import ROBOTS, nudged_instance, opening, stored_sets
from instructmove_ms.assets import snapshot as snap
from instructmove_ms.assets.catalog import Instance
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.tasks import TASKS
from instructmove_ms.verify import certificate, verify

#: The nudge a stored episode's decisions must survive: every pose coordinate moved by this
#: much (m; a million times last-bit noise at 0.3 m) and every asset float by a few ULPs.
POSE_NUDGE = 1e-9
ULPS = 4


def _counted(inst: Instance):
    """(where, value, quantum) of every number the identity hash counts."""
    from instructmove_ms.assets.identity import counted

    for part in inst.parts:
        for key, (values, quantum) in counted(part).items():
            for v in values if isinstance(values, tuple) else (values,):
                yield (inst.category, inst.index, part.name, key), v, quantum


def test_no_number_of_the_library_sits_near_a_boundary_of_its_quantum():
    """Every counted number of the shipped library lies at least 1e-7 of a quantum from a
    boundary between counts, a hundred times what last-bit noise can move it (below 1e-9
    of a quantum), so no machine counts it otherwise (measured: 4.5e-6 at the nearest)."""
    from instructmove_ms.assets.identity import OFFSET

    nearest = (1.0, None)
    for inst in snap.load_snapshot().instances:
        for where, value, quantum in _counted(inst):
            x = value / quantum + OFFSET
            gap = min(x - math.floor(x), math.ceil(x) - x) if x != math.floor(x) else 0.0
            nearest = min(nearest, (gap, where))
    assert nearest[0] >= 1e-7, nearest


def test_grasp_affordances_ignore_float_noise():
    """Every instance offers the same grasps, in the same order, with its floats moved by
    a few ULPs either way (designed parts share faces and heights exactly: no comparison
    of the affordances may hang on the last bit)."""
    from instructmove_ms.assets.affordances import grasp_affordances

    def grasps(inst: Instance, opening: float) -> np.ndarray:
        found = grasp_affordances(inst, opening)
        return np.array([[*g.center, *g.closing, g.width] for g in found]).reshape(-1, 7)

    for inst in snap.load_snapshot().instances:
        for robot in ROBOTS:
            want = grasps(inst, opening(robot))
            for ulps in (ULPS, -ULPS):
                got = grasps(nudged_instance(inst, ulps), opening(robot))
                assert got.shape == want.shape, (inst.category, inst.index, robot, ulps)
                np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)


def _decisions(cert: dict) -> list:
    """What a certificate decides: each candidate's match and name, the destinations'."""
    keys = ("index", "category", "named", "matches", "holds", "opposite_holds")
    candidates = [{k: c.get(k) for k in keys} for c in cert["candidates"]]
    return [cert["goal"], candidates, cert.get("destinations")]


def _nudged_spec(spec: EpisodeSpec, rng: np.random.Generator) -> EpisodeSpec:
    objects = tuple(
        dataclasses.replace(
            o,
            pose=tuple(
                float(v) for v in np.asarray(o.pose[:3]) + rng.choice([-1, 1], 3) * POSE_NUDGE
            )
            + tuple(o.pose[3:]),
        )
        for o in spec.objects
    )
    return dataclasses.replace(spec, objects=objects)


def test_no_stored_decision_hangs_on_float_noise():
    """Every stored episode decides the same with every object moved by 1 nm and every
    asset float moved by a few ULPs: no decision of the verifier (relation cones and
    margins, size ratios, graspability, colour distances) sits on its threshold, so no
    machine whose floats differ in their last bits refuses or re-reads one."""
    catalog = snap.load_snapshot()
    nudged_catalog = snap.Catalog(
        catalog.name, [nudged_instance(i, ULPS) for i in catalog.instances]
    )
    rng = np.random.default_rng(0)
    for env_id, robot, split, specs in stored_sets():
        task = TASKS[env_id]
        for spec in specs:
            moved = _nudged_spec(spec, rng)
            where = (env_id, robot, split, spec.seed)
            assert verify(moved, nudged_catalog, task, opening(robot)) == [], where
            cert = certificate(moved, nudged_catalog, task)
            assert _decisions(cert) == _decisions(spec.certificate), where
