"""Instructions: paraphrase templates filled with referring expressions."""

from __future__ import annotations

import numpy as np

from .assets.catalog import Instance


def noun_phrase(rng: np.random.Generator, instance: Instance) -> str:
    """A category-level referring expression: one of the category's nouns."""
    return instance.nouns[int(rng.integers(len(instance.nouns)))]


def render(rng: np.random.Generator, templates: tuple[str, ...], **slots: str) -> str:
    """Fill a randomly chosen template; every slot must be used by the templates."""
    template = templates[int(rng.integers(len(templates)))]
    return template.format(**slots)
