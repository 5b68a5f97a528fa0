"""What readers are shown, drawn from a seed: close-ups of a random instance of every
category, the same categories boxed in stored scenes as the policy's cameras see them,
a random sample of instructions, and random stored episodes from every camera.

Each writes the reader's material to ``OUT/reader/`` (with the brief, ``BRIEF.txt``) and
what the scorer needs to ``OUT/key.json``, which readers never see.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from tqdm import tqdm

from ..assets.catalog import Catalog
from ..episode import EpisodeSpec
from ..files import write_json, write_text
from ..heldout import SET_VERSION, load_set
from ..splits import EVAL_SEED_BASE, EVAL_SPLITS
from . import CAMERAS, POLICY_RESOLUTION, SOURCES
from .briefs import brief
from .pictures import (
    PAGE_COLUMNS,
    PAGE_ROWS,
    boxed,
    cell_key,
    numbered,
    ruled,
    write_pages,
    write_png,
)

#: The smallest and largest square side in-scene material is drawn at (pixels).
MIN_SIDE, MAX_SIDE = 64, 720


def _reader(out: Path, kind: str, side: int = POLICY_RESOLUTION) -> Path:
    folder = Path(out) / "reader"
    write_text(folder / "BRIEF.txt", brief(kind, side))
    return folder


def _write_key(out: Path, kind: str, seed: int, items: list[dict], **about) -> Path:
    return write_json(Path(out) / "key.json", {"kind": kind, "seed": seed, **about, "items": items})


def stored_sets(version: int | None = None) -> Iterator[tuple[str, str, str]]:
    """Every stored (env id, robot, split) of ``version``."""
    from ..tasks import TASKS

    for env_id, task in TASKS.items():
        for robot in task.supported_robots:
            for split in EVAL_SPLITS:
                yield env_id, robot, split


def _categories(catalog: Catalog, only: list[str] | None) -> list[str]:
    """``only`` (every category of ``catalog`` if None), checked against the catalog."""
    for category in only or ():
        if category not in catalog.categories:
            raise ValueError(
                f"unknown category {category!r}; {catalog.name} has {catalog.categories}"
            )
    return [c for c in catalog.categories if only is None or c in only]


def at_revision(catalog: Catalog, library: int) -> Catalog:
    """``catalog``'s instances (categories and indices) as library revision ``library``
    builds them."""
    from ..assets.catalog import generate_instance

    rebuilt = [generate_instance(i.category, i.index, library) for i in catalog.instances]
    return Catalog(f"{catalog.name}@r{library}", rebuilt)


def close_ups(
    catalog: Catalog,
    seed: int,
    out: Path,
    only: list[str] | None = None,
    every_instance: bool = False,
) -> Path:
    """A close-up of a random instance of every category of ``catalog`` (or of ``only``),
    in a random order, numbered: pages ``close_ups_N.png``. ``every_instance`` shows every
    instance of those categories instead (a screen of a library, instance by instance)."""
    from ..assets.sheet import photograph

    rng = np.random.default_rng(seed)
    if every_instance:
        chosen = [i for c in _categories(catalog, only) for i in catalog.of_category(c)]
    else:
        chosen = [
            catalog.of_category(c)[int(rng.integers(len(catalog.of_category(c))))]
            for c in _categories(catalog, only)
        ]
    chosen = [chosen[k] for k in rng.permutation(len(chosen))]
    tiles = photograph(chosen, progress="close-ups")
    folder = _reader(out, "close_ups")
    write_pages([numbered(t, k + 1) for k, t in enumerate(tiles)], folder, "close_ups")
    items = [{"n": k + 1, "category": i.category, "uuid": i.uuid} for k, i in enumerate(chosen)]
    return _write_key(out, "close_ups", seed, items, snapshot=catalog.name)


@dataclass(frozen=True)
class Views:
    """Every camera's RGB image and segmentation (per-scene ids) of one scene: ``cameras``
    lists the ``scene`` scene cameras first; ``ids`` maps a per-scene id to its object."""

    cameras: tuple[str, ...]
    scene: int
    rgb: dict[str, np.ndarray]
    segmentation: dict[str, np.ndarray]
    ids: dict[int, int]

    def mask(self, camera: str, k: int) -> np.ndarray:
        sid = next(s for s, j in self.ids.items() if j == k)
        return self.segmentation[camera] == sid


def views_of(env, sensor_data: dict | None = None) -> Views:
    """What every camera of ``env`` shows: ``sensor_data`` of its latest observation (an rgb
    env's ``obs["sensor_data"]``) or, without, what the cameras capture now; with each
    camera's segmentation of the same moment."""
    unwrapped = env.unwrapped
    agent = unwrapped.agent
    cameras = list(agent.scene_cameras) + [
        c.uid for c in agent._sensor_configs if c.uid not in agent.scene_cameras
    ]
    if sensor_data is None:
        sensor_data = unwrapped._get_obs_sensor_data()
    rgb = {c: sensor_data[c]["rgb"][0].cpu().numpy() for c in cameras}
    segmentation = {}
    for c in cameras:
        camera = unwrapped._sensors[c]
        seg = camera.get_obs(rgb=False, depth=False, position=False, segmentation=True)
        segmentation[c] = seg["segmentation"][0, ..., 0].cpu().numpy()
    ids = {int(o.per_scene_id[0]): k for k, o in enumerate(unwrapped.objects)}
    return Views(tuple(cameras), len(agent.scene_cameras), rgb, segmentation, ids)


class SceneRenderer:
    """Episodes reset in rgb envs at ``side`` x ``side`` (the policy's resolution by
    default), one env per (env id, robot), with the segmentation of every camera; ``options``
    go to every env made (a ``split`` and ``sampler`` for the scenes it composes)."""

    def __init__(self, side: int = POLICY_RESOLUTION, **options) -> None:
        self.side = side
        self.options = options
        self._envs: dict[tuple, object] = {}

    def env(self, env_id: str, robot: str):
        from ..perturb_sheet import sheet_env

        key = (env_id, robot)
        if key not in self._envs:
            self._envs[key] = sheet_env(env_id, robot, self.side, self.side, **self.options)
        return self._envs[key]

    def views(self, env_id: str, spec: EpisodeSpec) -> Views:
        """What every camera of ``spec``'s robot sees of its scene after the reset."""
        env = self.env(env_id, spec.robot)
        obs, _ = env.reset(options={"episode": spec})
        return views_of(env, obs["sensor_data"])

    def state_env(self, env_id: str, robot: str):
        """A state env of (``env_id``, ``robot``) that only composes episodes."""
        import gymnasium as gym

        key = (env_id, robot, "state")
        if key not in self._envs:
            self._envs[key] = gym.make(env_id, robot_uids=robot, obs_mode="state", split="train")
        return self._envs[key]

    def close(self) -> None:
        for env in self._envs.values():
            env.close()
        self._envs.clear()


def _occurrences(version: int | None) -> dict[str, list[tuple[str, str, str, int, int]]]:
    """Category -> every (env id, robot, split, episode index, object index) of a stored
    episode holding it where its visibility is certified (``tasks.visibility.watched``)."""
    from ..tasks.visibility import watched

    found: dict[str, list] = {}
    for env_id, robot, split in stored_sets(version):
        for e, spec in enumerate(load_set(env_id, robot, split, version=version)):
            for k in watched(spec):
                found.setdefault(spec.objects[k].category, []).append((env_id, robot, split, e, k))
    return found


def best_camera(views, k: int, cameras: str = "scene") -> str:
    """The camera of ``views`` (a ``SceneRenderer.views``) that shows most of object ``k``,
    among ``cameras`` (one of ``CAMERAS``)."""
    if cameras not in CAMERAS:
        raise ValueError(f"cameras {cameras!r} is not one of {CAMERAS}")
    pool = views.cameras[: views.scene]
    if cameras == "every" or not any(views.mask(c, k).any() for c in pool):
        pool = views.cameras
    return max(pool, key=lambda c: int(views.mask(c, k).sum()))


def in_scene(
    catalog: Catalog,
    seed: int,
    out: Path,
    version: int | None = None,
    only: list[str] | None = None,
    cameras: str = "scene",
    side: int = POLICY_RESOLUTION,
) -> Path:
    """Every category of ``catalog`` (or of ``only``) that a stored set holds, in a random
    stored episode holding it, boxed in the camera that shows most of it (``best_camera``)
    at ``side`` x ``side`` (the policy's resolution; a larger one tells what an object shows
    from what the policy's pixels keep of it), in a random order: pages ``in_scene_N.png``
    no larger than the policy's resolution makes them. The key names the categories no
    stored episode holds (``absent``)."""
    if not MIN_SIDE <= side <= MAX_SIDE:
        raise ValueError(f"resolution {side} is not between {MIN_SIDE} and {MAX_SIDE} pixels")
    rng = np.random.default_rng(seed)
    found = _occurrences(version)
    wanted = _categories(catalog, only)
    shown = [c for c in wanted if c in found]
    categories = [shown[k] for k in rng.permutation(len(shown))]
    renderer = SceneRenderer(side)
    tiles, items = [], []
    try:
        for n, category in enumerate(tqdm(categories, desc="in-scene", unit="object"), 1):
            places = found[category]
            env_id, robot, split, e, k = places[int(rng.integers(len(places)))]
            spec = load_set(env_id, robot, split, version=version)[e]
            source = f"v{version or SET_VERSION}/{env_id}/{robot}/{split}#{e}"
            views = renderer.views(env_id, spec)
            best = best_camera(views, k, cameras)
            tiles.append(numbered(boxed(views.rgb[best], views.mask(best, k)), n))
            items.append(
                {
                    "n": n,
                    "category": category,
                    "source": source,
                    "camera": best,
                    "uuid": spec.objects[k].uuid,
                }
            )
    finally:
        renderer.close()
    scale = max(1, side // POLICY_RESOLUTION)
    write_pages(
        tiles,
        _reader(out, "in_scene", side),
        "in_scene",
        max(1, PAGE_COLUMNS // scale),
        max(1, PAGE_ROWS // scale),
    )
    absent = sorted(set(wanted) - set(found))
    return _write_key(
        out,
        "in_scene",
        seed,
        items,
        set_version=version or SET_VERSION,
        absent=absent,
        cameras=cameras,
        side=side,
    )


def _random_stored(rng, count: int, version: int | None) -> list[tuple[str, str, EpisodeSpec]]:
    """``count`` distinct stored episodes drawn uniformly from every set of ``version``:
    (env id, source, spec)."""
    pool = [
        (env_id, f"v{version or SET_VERSION}/{env_id}/{robot}/{split}#{e}", spec)
        for env_id, robot, split in stored_sets(version)
        for e, spec in enumerate(load_set(env_id, robot, split, version=version))
    ]
    return [pool[k] for k in rng.choice(len(pool), size=count, replace=False)]


def episodes(seed: int, out: Path, count: int = 40, version: int | None = None) -> Path:
    """``count`` random stored episodes, every camera at the policy's resolution ruled into
    a lettered grid (``episode_N.png``), their instructions in ``episodes.txt``."""
    rng = np.random.default_rng(seed)
    folder = _reader(out, "episodes")
    renderer = SceneRenderer()
    lines, items = [], []
    try:
        chosen = _random_stored(rng, count, version)
        for n, (env_id, source, spec) in enumerate(
            tqdm(chosen, desc="episodes", unit="episode"), 1
        ):
            views = renderer.views(env_id, spec)
            pictures = [ruled(views.rgb[c], f"camera {j + 1}") for j, c in enumerate(views.cameras)]
            write_png(folder / f"episode_{n}.png", np.concatenate(pictures, axis=1))
            lines.append(f"{n}: {spec.instruction}")
            owners, most = zip(
                *(cell_key(views.segmentation[c], views.ids) for c in views.cameras), strict=True
            )
            items.append(
                {
                    "n": n,
                    "source": source,
                    "instruction": spec.instruction,
                    "target": spec.target,
                    "destination": spec.goal_destination,
                    "cameras": list(views.cameras),
                    "owners": list(owners),
                    "most": list(most),
                }
            )
    finally:
        renderer.close()
    write_text(folder / "episodes.txt", "\n".join(lines) + "\n")
    return _write_key(out, "episodes", seed, items, set_version=version or SET_VERSION)


def instructions(
    seed: int, out: Path, count: int = 200, version: int | None = None, source: str = "both"
) -> Path:
    """``count`` instructions in a random order from ``source``: random stored episodes of
    ``version``, episodes of random training seeds, or half of each
    (``instructions.txt``)."""
    from ..tasks import TASKS
    from ..validation import check_choice

    check_choice("source", source, SOURCES)
    rng = np.random.default_rng(seed)
    n_stored = {"both": count // 2, "stored": count, "train": 0}[source]
    stored = [(name, spec) for _, name, spec in _random_stored(rng, n_stored, version)]
    renderer = SceneRenderer()
    trained = []
    try:
        with tqdm(total=count - len(stored), desc="training episodes", unit="episode") as bar:
            while len(trained) < count - len(stored):
                env_id = list(TASKS)[int(rng.integers(len(TASKS)))]
                robots = TASKS[env_id].supported_robots
                robot = robots[int(rng.integers(len(robots)))]
                spec = renderer.state_env(env_id, robot).unwrapped.sample_episode(
                    int(rng.integers(EVAL_SEED_BASE))
                )
                trained.append((f"train/{env_id}/{robot}/seed {spec.seed}", spec))
                bar.update()
    finally:
        renderer.close()
    drawn = stored + trained
    drawn = [drawn[k] for k in rng.permutation(len(drawn))]
    folder = _reader(out, "instructions")
    write_text(
        folder / "instructions.txt",
        "".join(f"{n}: {spec.instruction}\n" for n, (_, spec) in enumerate(drawn, 1)),
    )
    items = [
        {"n": n, "source": source, "instruction": spec.instruction, "family": spec.family}
        for n, (source, spec) in enumerate(drawn, 1)
    ]
    return _write_key(out, "instructions", seed, items, set_version=version or SET_VERSION)
