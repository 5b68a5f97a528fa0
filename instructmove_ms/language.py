"""Instructions: paraphrase templates filled with referring expressions."""

from __future__ import annotations

import numpy as np

from .assets.catalog import Instance
from .assets.expressions import expressions

UNSEEN_SPLITS = ("unseen_instance", "unseen_category")


def referring_expression(rng: np.random.Generator, instance: Instance, split: str) -> str:
    """A phrase for ``instance`` from its seen pool, or its unseen pool on unseen splits."""
    seen, unseen = expressions(instance)
    pool = unseen if split in UNSEEN_SPLITS and unseen else seen
    return pool[int(rng.integers(len(pool)))]


def render(rng: np.random.Generator, templates: tuple[str, ...], **slots: str) -> str:
    """Fill a randomly chosen template; every slot must be used by the templates."""
    template = templates[int(rng.integers(len(templates)))]
    return template.format(**slots)
