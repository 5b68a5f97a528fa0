"""The data splits and the seeds that separate training from evaluation, defined once.

Training data (demos, ``train`` episodes) use seeds below ``EVAL_SEED_BASE``; the stored
held-out sets use seeds from it on, one block of ``EVAL_SEED_BLOCK`` per evaluation split,
so the two never share an episode.
"""

from __future__ import annotations

from .validation import check_choice

#: Every split an env can draw from: ``train`` and ``seen`` share the seen assets (they
#: differ by their seeds), the unseen splits hold out instances or whole categories.
SPLITS = ("train", "seen", "unseen_instance", "unseen_category")
#: The splits of the stored held-out evaluation sets.
EVAL_SPLITS = ("seen", "unseen_instance", "unseen_category")
#: Splits whose instructions use the unseen expression pool.
UNSEEN_SPLITS = ("unseen_instance", "unseen_category")
EVAL_SEED_BASE = 1_000_000_000
EVAL_SEED_BLOCK = 1_000_000


def eval_seed(split: str, index: int) -> int:
    """The seed of held-out episode ``index`` of ``split``."""
    check_choice("evaluation split", split, EVAL_SPLITS)
    return EVAL_SEED_BASE + EVAL_SPLITS.index(split) * EVAL_SEED_BLOCK + index


def is_training_seed(seed: int) -> bool:
    """Whether ``seed`` lies in the training range (never a held-out episode)."""
    return 0 <= seed < EVAL_SEED_BASE
