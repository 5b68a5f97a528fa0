"""The chooser's crops, its training (resumable, learns what the pictures hold) and the
pixel adversary on rendered scenes."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from instructmove_ms.audit.pixels import NAME, judge, statistics
from instructmove_ms.grounding import scenes
from instructmove_ms.grounding.crops import CAMERAS, CROP, GEOMETRY, Decisions, crop
from instructmove_ms.grounding.training import Schedule, choose, fit, load, slim
from instructmove_ms.heldout import load_set


def test_crop_cuts_the_object_out_with_its_mask_and_where_it_lay():
    rgb = np.zeros((100, 200, 3), np.uint8)
    rgb[40:60, 120:140] = (200, 10, 10)
    mask = np.zeros((100, 200), bool)
    mask[40:60, 120:140] = True
    cut, figures = crop(rgb, mask)
    assert cut.shape == (4, CROP, CROP) and cut.dtype == np.uint8
    middle = cut[:, CROP // 2, CROP // 2]
    assert middle[0] > 150 and middle[1] < 40 and middle[3] == 255
    assert cut[3, 0, 0] == 0  # the margin around it is not the object
    shown, x, y, side, pixels = figures
    assert shown == 1 and x == pytest.approx(130 / 200) and y == pytest.approx(50 / 100)
    assert side == pytest.approx(20 * 1.3 / 200) and pixels == pytest.approx(20 / 200)
    hidden, none = crop(rgb, np.zeros_like(mask))
    assert not hidden.any() and not none.any()


def _decisions(crops: np.ndarray, answer: np.ndarray, instruction: list[str]) -> Decisions:
    n = len(answer)
    rng = np.random.default_rng(n)
    return Decisions(
        family=np.array(["F"] * n),
        kind=np.array(["object"] * n),
        split=np.array(["seen"] * n),
        robot=np.array(["franka"] * n),
        seed=np.arange(n),
        answer=answer,
        count=np.full(n, 3),
        objects=np.full(n, 3),
        instruction=np.array(instruction),
        crops=crops,
        geometry=rng.random((n * 3, CAMERAS, len(GEOMETRY))).astype(np.float32),
    )


def _planted(n: int, seed: int) -> Decisions:
    """Decisions of 3 options each whose answer alone is bright: a signal in the pixels."""
    rng = np.random.default_rng(seed)
    crops = rng.integers(0, 120, (n * 3, CAMERAS, 4, CROP, CROP), dtype=np.uint8)
    answer = rng.integers(0, 3, n)
    crops[np.arange(n) * 3 + answer, :, :3] += 120
    crops[:, :, 3] = 255  # each crop is all option
    return _decisions(crops, answer, ["pick it"] * n)


COLOURS = ("red", "green", "blue")


def _named(n: int, seed: int) -> Decisions:
    """Decisions of a red, a green and a blue option in random order; the instruction names
    one colour: only the words tell which."""
    rng = np.random.default_rng(seed)
    crops = rng.integers(0, 60, (n * 3, CAMERAS, 4, CROP, CROP), dtype=np.uint8)
    order = np.array([rng.permutation(3) for _ in range(n)])
    for k in range(3):
        crops[np.arange(n) * 3 + k, :, order[:, k]] += 180
    named = rng.integers(0, 3, n)
    answer = np.array([list(order[i]).index(named[i]) for i in range(n)])
    return _decisions(crops, answer, [f"pick up the {COLOURS[c]} block" for c in named])


def test_reading_the_instruction_finds_the_option_only_the_words_name():
    train, held_out = _named(96, 5), _named(60, 6)
    reader, _ = fit(train, Schedule(epochs=12, batch=16, text=True), progress=False)
    assert (choose(reader, held_out) == held_out.answer).mean() > 0.9
    blind, _ = fit(train, Schedule(epochs=12, batch=16), progress=False)
    assert (choose(blind, held_out) == held_out.answer).mean() < 0.55


def test_the_chooser_learns_a_signal_planted_in_the_pixels():
    model, history = fit(_planted(64, 0), Schedule(epochs=6, batch=16), progress=False)
    assert history.losses[-1] < 0.5 * history.losses[0]
    held_out = _planted(60, 1)
    assert (choose(model, held_out) == held_out.answer).mean() > 0.9


def test_training_resumes_to_the_model_an_uninterrupted_run_ends_with(tmp_path):
    d = _planted(32, 2)
    whole, _ = fit(d, Schedule(epochs=3, batch=8), progress=False)
    checkpoint = tmp_path / "model.pt"
    fit(d, Schedule(epochs=1, batch=8), checkpoint, progress=False)
    resumed, history = fit(d, Schedule(epochs=3, batch=8), checkpoint, progress=False)
    assert len(history.losses) == len(history.validation) == 3
    for a, b in zip(whole.state_dict().values(), resumed.state_dict().values(), strict=True):
        assert torch.allclose(a.float(), b.float(), atol=1e-5)
    _, again = fit(_planted(32, 3), Schedule(epochs=3, batch=8), checkpoint, progress=False)
    assert len(again.losses) == 3 and again.losses[0] != history.losses[0]  # trained anew


def test_the_model_kept_is_the_epoch_best_on_the_held_out_seeds(tmp_path):
    d = _planted(40, 10)
    schedule = Schedule(epochs=4, batch=8, held_out=4)
    train, held = schedule.split(d)
    assert set(d.seed[held]) == set(range(0, 40, 4)) and not set(d.seed[train]) & set(d.seed[held])
    checkpoint = tmp_path / "model.pt"
    model, history = fit(d, schedule, checkpoint, progress=False)
    assert len(history.validation) == len(history.accuracy) == 4
    assert history.validation[history.kept] == min(history.validation)
    held_out = d.take(held)
    assert (choose(model, held_out) == held_out.answer).mean() == history.accuracy[history.kept]
    slim(checkpoint, tmp_path / "slim.pt")
    assert (choose(load(tmp_path / "slim.pt"), d) == choose(model, d)).all()
    with pytest.raises(ValueError, match="held_out=4 leaves 0 decisions to train on"):
        fit(d.take(held), schedule, progress=False)
    with pytest.raises(ValueError, match="held_out must be 0 .none. or 2 or more, got 1"):
        Schedule(held_out=1)
    torch.save({"model": {"other": torch.zeros(1)}, "vocabulary": None}, tmp_path / "old.pt")
    with pytest.raises(ValueError, match="does not fit this version's network"):
        load(tmp_path / "old.pt")


def test_decisions_keep_their_rows_and_refuse_other_episodes(tmp_path):
    d = _planted(5, 4)
    part = d.take([3, 1])
    assert list(part.seed) == [3, 1] and len(part.crops) == 6
    assert (part.crops[:3] == d.crops[9:12]).all()
    path = d.save(tmp_path / "d.npz", "episodes a")
    assert Decisions.load(path, "episodes b") is None
    again = Decisions.load(path, "episodes a")
    assert again.fingerprint() == d.fingerprint()
    assert len(Decisions.join([again, part])) == 7


def test_rendered_training_scenes_hold_every_option_of_every_decision(tmp_path):
    family = "PlaceA2B-InstructMove"
    d = scenes.training(tmp_path, 2, families=(family,), progress=False)
    assert set(d.robot) == {"franka", "piperx"} and len(d) == 8  # 2 scenes x 2 robots x 2
    assert sorted(set(d.kind)) == ["object", "receptacle"]
    shown = d.geometry[..., 0] == 1
    assert shown[:, 0].all()  # the first scene camera sees every option
    masks = d.crops[:, :, 3][shown]
    assert (masks[:, CROP // 2 - 2 : CROP // 2 + 2, CROP // 2 - 2 : CROP // 2 + 2] > 0).any(
        axis=(1, 2)
    ).mean() > 0.8
    mtimes = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*.npz")}
    again = scenes.training(tmp_path, 2, families=(family,), progress=False)
    assert again.fingerprint() == d.fingerprint()
    both = scenes.training(tmp_path, 2, families=(family,), progress=False, alternatives=True)
    assert {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*.npz")} == mtimes  # kept
    normal, aimed = both.take(range(0, 4)), both.take(range(4, 8))  # one robot's shard
    assert normal.fingerprint() == d.take(range(0, 4)).fingerprint()
    assert (aimed.crops == normal.crops).all()  # the same pictures, other words
    assert (aimed.instruction != normal.instruction).all()
    goals = normal.answer.reshape(2, 2)  # (object, receptacle) of each scene
    assert (aimed.answer.reshape(2, 2) != goals).any(axis=1).all()  # another goal each


def test_the_pixel_adversaries_judge_every_stored_decision(tmp_path, monkeypatch):
    family = "PickAttribute-InstructMove"
    judged = _planted(40, 8)
    judged = Decisions(
        **{**judged.__dict__, "family": np.array(["pick_attribute"] * 40)},
    )
    monkeypatch.setattr(scenes, "stored", lambda *a, **k: judged)
    schedule = Schedule(epochs=2)
    cells, losses = judge(tmp_path, 4, 2, schedule=schedule, progress=False, families=(family,))
    assert len(losses) == 2
    assert {c.adversary for c in cells} == {
        NAME,
        "pixel statistics, trees trained",
        "pixel statistics, trees within",
    }
    pooled = [c for c in cells if c.split == "pooled" and c.robot == "pooled"]
    assert all(c.episodes == 40 and c.scenes == 40 for c in pooled)
    within = next(c for c in pooled if c.adversary == "pixel statistics, trees within")
    assert within.accuracy > 0.8  # the planted answer is the brightest: the trees find it


def test_image_statistics_hold_only_what_the_pictures_show():
    d = _planted(3, 9)
    found = statistics(d)
    assert [c.answer for c in found] == list(d.answer)
    option = found[0].options[0]
    assert {v for vs in option.values.values() for v in vs} == {""}
    assert set(option.numbers) >= {"r mean 0", "b spread 2", "fill 1", "side 0"}


def test_a_trained_checkpoint_loads_and_its_choice_is_picked_up(tmp_path):
    import gymnasium as gym

    from instructmove_ms.policies import GroundedPolicy
    from instructmove_ms.tasks import TASKS

    family = "PickAttribute-InstructMove"
    taught = scenes.training(tmp_path / "renders", 3, families=(family,), progress=False)
    checkpoint = tmp_path / "grounded.pt"
    schedule = Schedule(epochs=8, batch=4, text=True, held_out=0)
    _, history = fit(taught, schedule, checkpoint, progress=False)
    assert history.losses[-1] < history.losses[0]
    policy = GroundedPolicy(checkpoint)
    spec = load_set(family, "franka", "seen")[0]
    env = gym.make(
        family,
        robot_uids="franka",
        obs_mode=policy.get_obs_mode(),
        control_mode=policy.get_control_mode(),
        sensor_configs=policy.get_sensor_configs(),
    )
    try:
        obs, _ = env.reset(seed=spec.seed, options={"episode": spec})
        policy.bind(env)
        policy.reset(obs, seed=spec.seed)
        chosen, _ = policy.goal
        assert chosen in spec.candidates
        body = env.unwrapped.objects[chosen]
        start = float(body.pose.p[0, 2])
        for _ in range(TASKS[family].max_episode_steps):
            obs, *_ = env.step(policy.act(obs))
        assert float(body.pose.p[0, 2]) > start + 0.05  # the chosen object was lifted
    finally:
        env.close()


def test_the_judge_pools_robots_and_splits_and_counts_chance_per_decision():
    from instructmove_ms.grounding.judge import POOLED, table

    d = _planted(4, 7)
    d = Decisions(
        **{
            **d.__dict__,
            "robot": np.array(["franka", "piperx", "franka", "piperx"]),
            "count": np.array([3, 3, 2, 2]),
        }
    )
    picked = d.answer.copy()
    picked[1] = (picked[1] + 1) % 2
    rows = {(r["split"], r["robot"]): r for r in table(d, picked)}
    assert rows[("seen", "franka")]["accuracy"] == 1.0
    assert rows[("seen", "piperx")]["accuracy"] == 0.5
    whole = rows[(POOLED, POOLED)]
    assert whole["decisions"] == 4 and whole["accuracy"] == 0.75
    assert whole["chance"] == pytest.approx((1 / 3 + 1 / 3 + 1 / 2 + 1 / 2) / 4, abs=1e-4)
