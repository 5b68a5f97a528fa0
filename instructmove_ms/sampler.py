"""Seeded role sampling: which catalog instances play the target and the distractors."""

from __future__ import annotations

import numpy as np

from .assets.catalog import Catalog, Instance, is_held_out_category
from .validation import check_choice

SPLITS = ("train", "seen", "unseen_instance", "unseen_category")


def split_pools(catalog: Catalog, split: str) -> tuple[list[Instance], list[Instance]]:
    """(target pool, distractor pool) of graspable instances for ``split``.

    train / seen: seen categories, seen instances (seen differs from train by its held-out
    episode seeds). unseen_instance: targets are held-out instances of seen categories.
    unseen_category: targets come from held-out categories. Distractors always come from
    seen categories and seen instances.
    """
    check_choice("split", split, SPLITS)
    graspable = [i for i in catalog.instances if i.is_graspable]
    seen = [i for i in graspable if not is_held_out_category(i.category) and not i.held_out]
    if split in ("train", "seen"):
        targets = seen
    elif split == "unseen_instance":
        targets = [i for i in graspable if not is_held_out_category(i.category) and i.held_out]
    else:
        targets = [i for i in graspable if is_held_out_category(i.category)]
    return targets, seen


def _pick(rng: np.random.Generator, items: list):
    return items[int(rng.integers(len(items)))]


def sample_cross_category(
    rng: np.random.Generator, catalog: Catalog, split: str, num_distractors: int
) -> tuple[Instance, list[Instance]]:
    """A target and ``num_distractors`` distractors, all of pairwise different categories."""
    targets, others = split_pools(catalog, split)
    target = _pick(rng, targets)
    by_category: dict[str, list[Instance]] = {}
    for inst in others:
        if inst.category != target.category:
            by_category.setdefault(inst.category, []).append(inst)
    categories = sorted(by_category)
    if len(categories) < num_distractors:
        raise ValueError(
            f"split {split!r} of snapshot {catalog.name!r} has {len(categories)} distractor "
            f"categories, fewer than num_distractors={num_distractors}"
        )
    chosen = rng.choice(len(categories), size=num_distractors, replace=False)
    return target, [_pick(rng, by_category[categories[k]]) for k in chosen]
