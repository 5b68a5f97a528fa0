"""Training a chooser on rendered decisions, resumable epoch by epoch, and scoring it.

A fixed seed gives the same model on one machine: the initial weights come from it and each
epoch's order from (seed, epoch), so a run resumed from its checkpoint after any epoch ends
where an uninterrupted one does. Across machines the weights differ in their last bits
(torch picks CPU kernels at run time); figures measured with them are measurements, never
identities.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch
from threadpoolctl import threadpool_limits
from torch import nn
from tqdm import tqdm

from ..files import atomic_path
from .crops import Decisions
from .network import Chooser, batch
from .text import Vocabulary


@dataclass(frozen=True)
class Schedule:
    """How a chooser is trained."""

    epochs: int = 12
    batch: int = 32
    learning_rate: float = 2e-3
    weight_decay: float = 1e-4
    seed: int = 0
    threads: int = 1  # torch's CPU threads (more spin idle beside other busy processes)
    text: bool = False  # whether the chooser reads the instruction

    def __post_init__(self) -> None:
        for name in ("epochs", "batch", "threads"):
            if getattr(self, name) < 1:
                raise ValueError(f"{name} must be 1 or more, got {getattr(self, name)}")
        if self.learning_rate <= 0:
            raise ValueError(f"learning_rate must be above 0, got {self.learning_rate}")


def _chunks(order: np.ndarray, size: int) -> list[np.ndarray]:
    return [order[i : i + size] for i in range(0, len(order), size)]


def _resumable(schedule: dict) -> dict:
    """What a checkpoint must share with a schedule to go on from it (more epochs may)."""
    return {k: v for k, v in schedule.items() if k != "epochs"}


def _resumed(
    path: Path | None, schedule: Schedule, data: str, model: Chooser, optimizer
) -> list[float]:
    """The epoch losses of the checkpoint at ``path`` (its state loaded into ``model`` and
    ``optimizer``) when it was trained on the same ``data`` (a ``Decisions.fingerprint``)
    and schedule, for no more epochs; else none."""
    if path is None or not path.is_file():
        return []
    state = torch.load(path, weights_only=True)
    same = _resumable(state["schedule"]) == _resumable(asdict(schedule))
    same = same and state.get("data") == data and "optimizer" in state  # not a shipped one
    if not same or len(state["losses"]) > schedule.epochs:
        return []
    model.load_state_dict(state["model"])
    optimizer.load_state_dict(state["optimizer"])
    return list(state["losses"])


def save(
    path: Path, model: Chooser, schedule: Schedule, losses: list[float], data: str, optimizer
) -> Path:
    """Write the checkpoint atomically, with what resuming needs."""
    vocabulary = model.vocabulary
    state = {
        "model": model.state_dict(),
        "vocabulary": None if vocabulary is None else list(vocabulary.known),
        "schedule": asdict(schedule),
        "losses": losses,
        "data": data,
        "optimizer": optimizer.state_dict(),
    }
    with atomic_path(path) as tmp:
        torch.save(state, tmp)
    return path


def fit(
    d: Decisions,
    schedule: Schedule | None = None,
    checkpoint: Path | None = None,
    progress: bool = True,
) -> tuple[Chooser, list[float]]:
    """A chooser trained to score each decision's answer highest, and its mean loss per
    epoch; with ``checkpoint``, resumed from it and saved there after every epoch."""
    if len(d) == 0:
        raise ValueError("no decisions to train on")
    schedule = schedule or Schedule()
    threads = torch.get_num_threads()
    with threadpool_limits(schedule.threads), torch.random.fork_rng():
        torch.set_num_threads(schedule.threads)
        torch.manual_seed(schedule.seed)
        model = Chooser(Vocabulary.of(list(map(str, d.instruction))) if schedule.text else None)
        optimizer = torch.optim.AdamW(
            model.parameters(), lr=schedule.learning_rate, weight_decay=schedule.weight_decay
        )
        data = d.fingerprint() if checkpoint is not None else ""
        losses = _resumed(checkpoint, schedule, data, model, optimizer)
        loss_of = nn.CrossEntropyLoss()
        epochs = range(len(losses), schedule.epochs)
        for epoch in tqdm(epochs, desc="training", disable=not progress, initial=len(losses)):
            model.train()
            order = np.random.default_rng([schedule.seed, epoch]).permutation(len(d))
            total = 0.0
            for rows in _chunks(order, schedule.batch):
                inputs, answers = batch(d, rows, model.vocabulary)
                loss = loss_of(model(inputs), answers)
                optimizer.zero_grad()
                loss.backward()
                optimizer.step()
                total += loss.item() * len(rows)
            losses.append(total / len(d))
            if checkpoint is not None:
                save(checkpoint, model, schedule, losses, data, optimizer)
        torch.set_num_threads(threads)
    model.eval()
    return model, losses


def slim(path: Path, to: Path) -> Path:
    """Write the checkpoint at ``path`` to ``to`` with what choosing needs alone (the
    model, its vocabulary, how it was trained), atomically."""
    state = torch.load(path, weights_only=True)
    kept = {k: state[k] for k in ("model", "vocabulary", "schedule", "losses")}
    with atomic_path(to) as tmp:
        torch.save(kept, tmp)
    return Path(to)


def load(path: Path) -> Chooser:
    """The chooser of the checkpoint at ``path``."""
    if not Path(path).is_file():
        raise ValueError(f"no grounding checkpoint at {path}")
    state = torch.load(path, weights_only=True)
    known = state["vocabulary"]
    model = Chooser(None if known is None else Vocabulary(tuple(known)))
    model.load_state_dict(state["model"])
    return model.eval()


@torch.no_grad()
def choose(model: Chooser, d: Decisions, size: int = 256) -> np.ndarray:
    """The option ``model`` scores highest in each decision of ``d``."""
    model.eval()
    picked = [
        model(batch(d, rows, model.vocabulary)[0]).argmax(dim=1).numpy()
        for rows in _chunks(np.arange(len(d)), size)
    ]
    return np.concatenate(picked) if picked else np.zeros(0, int)
