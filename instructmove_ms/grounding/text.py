"""Instructions as a grounding model reads them: words, and the letters they are made of.

No pretrained weights are reachable, so the words are learned from the training
instructions alone: a word never seen there (an unseen category's name) reads as unknown,
and only its character trigrams (hashed into ``BUCKETS``) say anything of it.
"""

from __future__ import annotations

import re
import zlib
from collections.abc import Sequence
from dataclasses import dataclass

import torch

#: Hash buckets of character trigrams (0 is padding).
BUCKETS = 4096
#: A word's id when the vocabulary lacks it; 0 is padding.
UNKNOWN = 1


def words(text: str) -> list[str]:
    """The lower-cased words of ``text``."""
    return re.findall(r"[a-z0-9]+", text.lower())


def trigrams(word: str) -> list[int]:
    """The hashed character trigrams of ``word`` (with its edges marked), 1..BUCKETS-1."""
    marked = f"<{word}>"
    grams = [marked[i : i + 3] for i in range(max(len(marked) - 2, 1))]
    return [1 + zlib.crc32(g.encode()) % (BUCKETS - 1) for g in grams]


@dataclass(frozen=True)
class Vocabulary:
    """The words a model learned, in id order from 2."""

    known: tuple[str, ...]

    @staticmethod
    def of(texts: Sequence[str]) -> Vocabulary:
        return Vocabulary(tuple(sorted({w for t in texts for w in words(t)})))

    def encode(self, texts: Sequence[str]) -> tuple[torch.Tensor, torch.Tensor]:
        """(word ids (B, L), trigram ids (B, L, K)) of ``texts``, zero-padded."""
        ids = {w: i + 2 for i, w in enumerate(self.known)}
        split = [words(t) or [""] for t in texts]
        longest = max(len(s) for s in split)
        grams = [[trigrams(w) for w in s] for s in split]
        widest = max(len(g) for s in grams for g in s)
        word_ids = torch.zeros(len(texts), longest, dtype=torch.long)
        gram_ids = torch.zeros(len(texts), longest, widest, dtype=torch.long)
        for b, s in enumerate(split):
            for i, w in enumerate(s):
                word_ids[b, i] = ids.get(w, UNKNOWN)
                gram_ids[b, i, : len(grams[b][i])] = torch.tensor(grams[b][i])
        return word_ids, gram_ids
