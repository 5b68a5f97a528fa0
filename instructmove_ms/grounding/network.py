"""A chooser: scores each option of a decision from its crops and where they lay, and
(given a vocabulary) the instruction.

Each camera's crop passes a small convolutional encoder; with its geometry it becomes one
vector per camera, and the cameras' vectors (in a fixed order) one vector per option. The
score of an option reads that vector beside its difference from the mean of the decision's
options, so an option that stands out from the others (larger, another colour, the odd one
out) can be scored on that alone. Without an instruction the chooser is a language-blind
adversary: whatever it finds above chance, the scene gives away.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch
from torch import nn

from .crops import CAMERAS, GEOMETRY, Decisions
from .text import BUCKETS, Vocabulary

#: Width of every hidden vector.
WIDTH = 64


def _encoder() -> nn.Module:
    def block(a: int, b: int) -> list[nn.Module]:
        return [nn.Conv2d(a, b, 3, padding=1), nn.BatchNorm2d(b), nn.ReLU(), nn.MaxPool2d(2)]

    return nn.Sequential(
        *block(4, 16), *block(16, 32), *block(32, WIDTH), nn.AdaptiveAvgPool2d(1), nn.Flatten()
    )


class Reader(nn.Module):
    """An instruction as two vectors: each word's learned vector plus its trigrams', read in
    order by a bidirectional GRU, then averaged over the words (what the instruction asks)
    and pooled by a learned attention over them (the words that name a reference)."""

    def __init__(self, vocabulary: Vocabulary) -> None:
        super().__init__()
        self.words = nn.Embedding(len(vocabulary.known) + 2, WIDTH, padding_idx=0)
        self.grams = nn.Embedding(BUCKETS, WIDTH, padding_idx=0)
        self.gru = nn.GRU(WIDTH, WIDTH, batch_first=True, bidirectional=True)
        self.out = nn.Linear(2 * WIDTH, WIDTH)
        self.focus = nn.Linear(2 * WIDTH, 1)
        self.query = nn.Linear(2 * WIDTH, WIDTH)

    def forward(
        self, word_ids: torch.Tensor, gram_ids: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor]:
        present = (gram_ids > 0).sum(-1, keepdim=True).clamp(min=1)
        x = self.words(word_ids) + self.grams(gram_ids).sum(2) / present
        read, _ = self.gru(x)
        mask = (word_ids > 0).unsqueeze(-1)
        pooled = (read * mask).sum(1) / mask.sum(1).clamp(min=1)
        focus = torch.softmax(self.focus(read).masked_fill(~mask, -1e9), dim=1)
        return torch.relu(self.out(pooled)), self.query((focus * read).sum(1))


class Chooser(nn.Module):
    """Scores (batch x options) of padded decisions; padding scores minus infinity. With a
    ``vocabulary`` it reads the instruction too: the words weigh each option, and point at
    the scene object (never an option) they name as a reference, whose place each option is
    compared with."""

    def __init__(self, vocabulary: Vocabulary | None = None) -> None:
        super().__init__()
        self.vocabulary = vocabulary
        self.crop = _encoder()
        self.camera = nn.Sequential(nn.Linear(WIDTH + len(GEOMETRY), WIDTH), nn.ReLU())
        self.object = nn.Sequential(nn.Linear(CAMERAS * WIDTH, WIDTH), nn.ReLU())
        place = CAMERAS * len(GEOMETRY)
        extra = 0 if vocabulary is None else 2 * WIDTH + 2 * place
        self.score = nn.Sequential(
            nn.Linear(2 * WIDTH + extra, WIDTH), nn.ReLU(), nn.Linear(WIDTH, 1)
        )
        if vocabulary is not None:
            self.reader = Reader(vocabulary)
            self.pointer = nn.Linear(WIDTH, WIDTH)

    def _reference(self, h: torch.Tensor, query: torch.Tensor, inputs: Inputs) -> torch.Tensor:
        """Where the object the words point at lay (B, CAMERAS * len(GEOMETRY)): a soft
        choice among the scene's objects that are not options (zeros where there are none)."""
        others = inputs.objects.clone()
        others[:, : inputs.options.shape[1]] &= ~inputs.options
        named = torch.einsum("bnw,bw->bn", h, self.pointer(query))
        weight = torch.softmax(named.masked_fill(~others, -1e9), dim=1) * others
        return torch.einsum("bn,bnp->bp", weight, inputs.geometry.flatten(2))

    def forward(self, inputs: Inputs) -> torch.Tensor:
        b, n, c = inputs.crops.shape[:3]
        seen = self.crop(inputs.crops.flatten(0, 2)).view(b, n, c, WIDTH)
        h = self.object(self.camera(torch.cat([seen, inputs.geometry], dim=-1)).flatten(2))
        m = inputs.options.shape[1]
        options = inputs.options.unsqueeze(-1).float()
        mean = (h[:, :m] * options).sum(1, keepdim=True) / options.sum(1, keepdim=True)
        parts = [h[:, :m], h[:, :m] - mean]
        if self.vocabulary is not None:
            t, query = self.reader(inputs.words, inputs.grams)
            away = inputs.geometry[:, :m].flatten(2) - self._reference(h, query, inputs)[:, None]
            words = t[:, None].expand(-1, m, -1)
            parts += [words, h[:, :m] * words, away, away.abs()]
        scores = self.score(torch.cat(parts, dim=-1)).squeeze(-1)
        return scores.masked_fill(~inputs.options, float("-inf"))


@dataclass(frozen=True)
class Inputs:
    """A padded batch of decisions: every object's crops (B, N, CAMERAS, 4, CROP, CROP) in
    [0, 1] and geometry (B, N, CAMERAS, len(GEOMETRY)), the options first; which of the N
    slots hold an object (B, N) and which of the first M an option (B, M); the instruction's
    word and trigram ids (see ``text.Vocabulary.encode``; empty without a vocabulary)."""

    crops: torch.Tensor
    geometry: torch.Tensor
    objects: torch.Tensor
    options: torch.Tensor
    words: torch.Tensor
    grams: torch.Tensor


def batch(
    d: Decisions, rows: np.ndarray, vocabulary: Vocabulary | None = None
) -> tuple[Inputs, torch.Tensor]:
    """(inputs, answers) of decisions ``rows`` of ``d``, padded to the most objects and the
    most options among them."""
    starts, objects, count = d.starts[rows], d.objects[rows], d.count[rows]
    n, m = int(objects.max()), int(count.max())
    present = np.arange(n)[None, :] < objects[:, None]
    slots = np.where(present, starts[:, None] + np.arange(n)[None, :], starts[:, None])
    crops = torch.from_numpy(d.crops[slots]).float().div_(255)
    crops[torch.from_numpy(~present)] = 0
    geometry = torch.from_numpy(d.geometry[slots]) * torch.from_numpy(present[..., None, None])
    options = torch.from_numpy(np.arange(m)[None, :] < count[:, None])
    if vocabulary is None:
        words = grams = torch.zeros(len(rows), 0, dtype=torch.long)
    else:
        words, grams = vocabulary.encode([str(t) for t in d.instruction[rows]])
    inputs = Inputs(crops, geometry, torch.from_numpy(present), options, words, grams)
    return inputs, torch.from_numpy(d.answer[rows].astype(int))
