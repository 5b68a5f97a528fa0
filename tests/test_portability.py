"""The same benchmark on every machine: what another BLAS kernel, numpy's optional CPU
features or another CPU may change in the last bits of a float changes no asset identity, no
stored held-out episode and no sampled episode.

These tests carry the ``portability`` marker: ``scripts/portability.sh`` (part of the test
command) runs them again with OpenBLAS left to pick its kernel, forced to an FMA and to a
non-FMA kernel, and with numpy's optional CPU features turned off. Their references were
recorded on one machine (``tests/data/sampled_reference.json``, the stored held-out sets
and the shipped snapshot), so each run compares this machine with that one.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from floatnoise import ROBOTS, nudged_instance, opening, stored_sets
from instructmove_ms.assets import snapshot as snap
from instructmove_ms.assets.catalog import Instance, generate_instance
from instructmove_ms.assets.identity import content_hash
from instructmove_ms.assets.parts import Part
from instructmove_ms.heldout import load_set
from instructmove_ms.sampler import SAMPLERS
from instructmove_ms.splits import EVAL_SPLITS
from instructmove_ms.tasks import FAMILIES, TASKS
from instructmove_ms.verify import certificate, verify

pytestmark = pytest.mark.portability

SAMPLED = Path(__file__).parent / "data" / "sampled_reference.json"
#: How far a sampled episode's numbers (poses in m, joints in rad) may land from the
#: recording machine's: far above last-bit noise, far below anything a scene shows.
SAMPLED_TOLERANCE = 1e-9


def _snapshot_data(name: str = snap.DEFAULT_SNAPSHOT) -> dict:
    return json.loads(snap.snapshot_path(name).read_text())


# Asset identity ------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(snap.SHIPPED))
def test_each_shipped_snapshot_loads_and_every_hash_matches_here(name):
    snap.load_snapshot.cache_clear()
    catalog = snap.load_snapshot(name)
    assert len(catalog) == len(_snapshot_data(name)["instances"]) == 1140


@pytest.mark.parametrize("ulps", [1, -3, 4])
def test_a_few_ulps_on_every_float_of_every_instance_keep_the_snapshot_valid(ulps, monkeypatch):
    """What another kernel does to a generator's output (62 of 1,140 instances differ in a
    last bit between OpenBLAS's Sandybridge and Haswell kernels) does not make it stale."""
    monkeypatch.setattr(
        snap,
        "generate_instance",
        lambda cat, i, library: nudged_instance(generate_instance(cat, i, library), ulps),
    )
    data = _snapshot_data()  # the newest snapshot: revised builds too
    instances = snap._checked(snap.DEFAULT_SNAPSHOT, data)  # raises for a stale instance
    first = data["instances"][0]
    assert instances[0] != generate_instance(first["category"], first["index"]), "nudged"


def _moved(inst: Instance, **change) -> Instance:
    first = inst.parts[0]
    values = {k: v(getattr(first, k)) for k, v in change.items()}
    return dataclasses.replace(inst, parts=(Part(**{**first.__dict__, **values}), *inst.parts[1:]))


@pytest.mark.parametrize(
    "change",
    [
        {"pos": lambda p: (p[0], p[1], p[2] + 1e-4)},  # a part raised by 0.1 mm
        {"size": lambda s: (s[0] + 1e-4, *s[1:])},  # a part 0.1 mm larger
        {"rgb": lambda c: (c[0] + 1 / 255, *c[1:]) if c[0] < 0.9 else (c[0] - 1 / 255, *c[1:])},
        {"material": lambda m: "metal" if m != "metal" else "wood"},  # density and look
    ],
    ids=["raised-0.1mm", "larger-0.1mm", "one-8-bit-step-of-red", "another-material"],
)
def test_a_generator_change_of_a_tenth_of_a_millimetre_or_a_colour_step_is_stale(
    change, monkeypatch
):
    def generate(category: str, index: int, library: int) -> Instance:
        inst = generate_instance(category, index, library)
        return _moved(inst, **change) if (category, index) == ("mug", 5) else inst

    monkeypatch.setattr(snap, "generate_instance", generate)
    with pytest.raises(ValueError, match=r"stale: mug #5 \("):
        snap._checked(snap.DEFAULT_SNAPSHOT, _snapshot_data())


def test_the_mass_a_material_gives_is_part_of_identity(monkeypatch):
    from instructmove_ms.assets import vocab

    inst = generate_instance("mug", 5)
    before = content_hash(inst)
    material = inst.parts[0].material
    heavier = dataclasses.replace(vocab.MATERIALS[material], density=1.01 * inst.parts[0].density)
    monkeypatch.setitem(vocab.MATERIALS, material, heavier)
    assert content_hash(inst) != before


def test_a_snapshot_of_the_former_exact_scheme_still_loads_and_rehashes(tmp_path, monkeypatch):
    from instructmove_ms.assets.identity import exact_hash

    monkeypatch.setattr(snap, "data_home", lambda: tmp_path)
    monkeypatch.setattr(snap, "user_snapshot_dir", lambda: tmp_path / "snapshots")
    mugs = [generate_instance("mug", i) for i in range(3)]
    entries = [{**snap.entry_of(m), "content_hash": exact_hash(m)} for m in mugs]
    path = tmp_path / "snapshots" / "mine.json"
    path.parent.mkdir()
    path.write_text(json.dumps({"name": "mine", "instances": entries}))  # no "identity"
    snap.load_snapshot.cache_clear()
    assert len(snap.load_snapshot("mine")) == 3
    assert snap.rehash("mine") == (3, 0)
    data = json.loads(path.read_text())
    assert data["identity"] == 2
    assert [e["content_hash"] for e in data["instances"]] == [content_hash(m) for m in mugs]
    snap.load_snapshot.cache_clear()


# Stored held-out episodes --------------------------------------------------------------


def test_every_stored_episode_certifies_here_as_it_wasstored_sets():
    """Every stored held-out episode of every family, robot and split passes the verifier
    on this machine, and the certificate it gets is the stored one (the cue's figures are
    stored to 0.1 mm and 0.0001 degrees)."""
    catalog = snap.load_snapshot()
    count = 0
    for env_id, robot, split, specs in stored_sets():
        task = TASKS[env_id]
        for spec in specs:
            assert verify(spec, catalog, task, opening(robot)) == [], (env_id, robot, split)
            cert = certificate(spec, catalog, task)
            assert cert == spec.certificate, (env_id, robot, split, spec.seed)
            count += 1
    assert count == len(TASKS) * len(ROBOTS) * len(EVAL_SPLITS) * 100


@pytest.mark.parametrize("robot", ROBOTS)
def test_stored_episodes_reset_with_rgb_observations(robot):
    """The first stored episode of every family and split rebuilds with camera images
    (the verifier runs again on load) and shows its stored instruction."""
    from conftest import make_env

    for env_id in sorted(TASKS):
        env = make_env(env_id, robot_uids=robot, obs_mode="rgb", render_backend="cpu")
        for split in EVAL_SPLITS:
            spec = load_set(env_id, robot, split)[0]
            obs, _ = env.reset(options={"episode": spec.to_dict()})
            assert env.unwrapped.get_language_instruction() == [spec.instruction]
            images = [v["rgb"] for v in obs["sensor_data"].values()]
            assert images and all(int(i.float().std()) > 0 for i in images), (env_id, split)
            placed = env.unwrapped.objects[spec.target].pose.p[0, :2].cpu().numpy()
            np.testing.assert_allclose(placed, spec.target_object.pose[:2], atol=1e-5)
        env.close()


# Sampled episodes ----------------------------------------------------------------------
def _assert_close(got, want, where: str) -> None:
    if isinstance(want, float):
        assert isinstance(got, float) and abs(got - want) <= SAMPLED_TOLERANCE, (where, got, want)
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), where
        for k, (g, w) in enumerate(zip(got, want, strict=True)):
            _assert_close(g, w, f"{where}[{k}]")
    elif isinstance(want, dict):
        assert isinstance(got, dict) and got.keys() == want.keys(), where
        for k in want:
            _assert_close(got[k], want[k], f"{where}.{k}")
    else:
        assert got == want, (where, got, want)


@pytest.mark.parametrize("case", sorted(json.loads(SAMPLED.read_text())))
def test_training_seeds_compose_the_recorded_episodes(case):
    """The same seed composes the same episode as on the recording machine: the same
    objects, roles, target, instruction, cue and certificate, every number within 1e-9."""
    import gymnasium as gym

    from instructmove_ms.episode import CONDITIONS

    reference = json.loads(SAMPLED.read_text())[case]
    env_id, robot, sampler = case.split("/")
    env = gym.make(
        env_id, robot_uids=robot, sampler=int(sampler), obs_mode="state", render_backend="none"
    )
    draws = [(s, "normal") for s in (0, 1, 2)] + [(0, c) for c in CONDITIONS if c != "normal"]
    got = [env.unwrapped.sample_episode(seed, cond).to_dict() for seed, cond in draws]
    env.close()
    _assert_close(json.loads(json.dumps(got)), reference, case)


def test_every_family_is_in_the_sampled_reference():
    cases = set(json.loads(SAMPLED.read_text()))
    assert cases == {f"{e}/{r}/{s}" for e in TASKS for r in ROBOTS for s in SAMPLERS}
    assert {TASKS[c.split("/")[0]].family for c in cases} == set(FAMILIES)
