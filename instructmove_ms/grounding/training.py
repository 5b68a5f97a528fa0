"""Training a chooser on rendered decisions, resumable epoch by epoch, and scoring it.

Every ``held_out``-th training seed is kept out of training to validate on: after each
epoch the model is scored there, and the model kept is the one of the epoch with the lowest
validation loss (the stored sets are never looked at). A fixed seed gives the same model on
one machine: the initial weights come from it and each epoch's order from (seed, epoch), so
a run resumed from its checkpoint after any epoch ends where an uninterrupted one does.
Across machines the weights differ in their last bits (torch picks CPU kernels at run
time); figures measured with them are measurements, never identities.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
import torch
from threadpoolctl import threadpool_limits
from torch import nn
from tqdm import tqdm

from ..files import atomic_path
from .crops import Decisions
from .network import Chooser, Inputs, batch
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
    held_out: int = 10  # seeds divisible by it validate, never train (0: none; last epoch kept)
    mirror: bool = True  # mirror each training crop left to right at random (where it lay stays)

    def __post_init__(self) -> None:
        for name in ("epochs", "batch", "threads"):
            if getattr(self, name) < 1:
                raise ValueError(f"{name} must be 1 or more, got {getattr(self, name)}")
        if self.learning_rate <= 0:
            raise ValueError(f"learning_rate must be above 0, got {self.learning_rate}")
        if self.held_out < 0 or self.held_out == 1:
            raise ValueError(f"held_out must be 0 (none) or 2 or more, got {self.held_out}")

    def split(self, d: Decisions) -> tuple[np.ndarray, np.ndarray]:
        """The rows of ``d`` to train on and to validate on (whole seeds, so both robots'
        views of one layout fall on one side)."""
        validate = (d.seed % self.held_out == 0) if self.held_out else np.zeros(len(d), bool)
        train, held = np.flatnonzero(~validate), np.flatnonzero(validate)
        if len(train) == 0 or (self.held_out and len(held) == 0):
            raise ValueError(
                f"held_out={self.held_out} leaves {len(train)} decisions to train on and "
                f"{len(held)} to validate on; give seeds on both sides or held_out=0"
            )
        return train, held


@dataclass(frozen=True)
class History:
    """How a training went: the mean training loss and (with held-out seeds) the mean
    validation loss and choice accuracy per epoch, and the epoch whose model is kept."""

    losses: list[float]
    validation: list[float]
    accuracy: list[float]

    @property
    def kept(self) -> int:
        """The epoch (from 0) whose model is kept: the lowest validation loss, else the last."""
        return int(np.argmin(self.validation)) if self.validation else len(self.losses) - 1


def _chunks(order: np.ndarray, size: int) -> list[np.ndarray]:
    return [order[i : i + size] for i in range(0, len(order), size)]


def _resumable(schedule: dict) -> dict:
    """What a checkpoint must share with a schedule to go on from it (more epochs may)."""
    return {k: v for k, v in schedule.items() if k != "epochs"}


def _resumed(
    path: Path | None, schedule: Schedule, data: str, model: Chooser, optimizer
) -> tuple[History, dict | None]:
    """The history and kept model state of the checkpoint at ``path`` (its state loaded into
    ``model`` and ``optimizer``) when it was trained on the same ``data`` (a
    ``Decisions.fingerprint``) and schedule, for no more epochs; else an empty start."""
    empty = History([], [], [])
    if path is None or not path.is_file():
        return empty, None
    state = torch.load(path, weights_only=True)
    same = _resumable(state["schedule"]) == _resumable(asdict(schedule))
    same = same and state.get("data") == data and "optimizer" in state  # not a shipped one
    if not same or len(state["losses"]) > schedule.epochs:
        return empty, None
    model.load_state_dict(state["model"])
    optimizer.load_state_dict(state["optimizer"])
    history = History(*(list(state[k]) for k in ("losses", "validation", "accuracy")))
    return history, state["kept"]


def save(
    path: Path,
    model: Chooser,
    schedule: Schedule,
    history: History,
    kept: dict,
    data: str,
    optimizer,
) -> Path:
    """Write the checkpoint atomically: the model now and the ``kept`` one, with what
    resuming needs."""
    vocabulary = model.vocabulary
    state = {
        "model": model.state_dict(),
        "kept": kept,
        "vocabulary": None if vocabulary is None else list(vocabulary.known),
        "schedule": asdict(schedule),
        **asdict(history),
        "data": data,
        "optimizer": optimizer.state_dict(),
    }
    with atomic_path(path) as tmp:
        torch.save(state, tmp)
    return path


def _mirrored(inputs: Inputs, rng: np.random.Generator) -> Inputs:
    """``inputs`` with each crop mirrored left to right at random: an object seen mirrored
    is the same object, so the chooser learns what does not hang on its pose. Where the crop
    lay (the geometry) is kept, so left and right keep their meaning."""
    crops = inputs.crops
    flip = torch.from_numpy(rng.random(crops.shape[:3]) < 0.5)[..., None, None, None]
    return replace(inputs, crops=torch.where(flip, crops.flip(-1), crops))


def _copy(model: Chooser) -> dict:
    return {k: v.detach().clone() for k, v in model.state_dict().items()}


@torch.no_grad()
def _scored(model: Chooser, d: Decisions, rows: np.ndarray, size: int = 256):
    """(scores, answers) of decisions ``rows`` of ``d``, a chunk of ``size`` at a time."""
    model.eval()
    for chunk in _chunks(rows, size):
        inputs, answers = batch(d, chunk, model.vocabulary)
        yield model(inputs), answers


def _validated(model: Chooser, d: Decisions, rows: np.ndarray, loss_of) -> tuple[float, float]:
    """``model``'s mean loss and choice accuracy on decisions ``rows`` of ``d``."""
    loss = correct = 0.0
    for scores, answers in _scored(model, d, rows):
        loss += loss_of(scores, answers).item() * len(answers)
        correct += (scores.argmax(dim=1) == answers).sum().item()
    return loss / len(rows), correct / len(rows)


def fit(
    d: Decisions,
    schedule: Schedule | None = None,
    checkpoint: Path | None = None,
    progress: bool = True,
) -> tuple[Chooser, History]:
    """A chooser trained to score each decision's answer highest (the epoch kept by
    validation on held-out seeds), and its history; with ``checkpoint``, resumed from it and
    saved there after every epoch."""
    if len(d) == 0:
        raise ValueError("no decisions to train on")
    schedule = schedule or Schedule()
    train, held = schedule.split(d)
    threads = torch.get_num_threads()
    with threadpool_limits(schedule.threads), torch.random.fork_rng():
        torch.set_num_threads(schedule.threads)
        torch.manual_seed(schedule.seed)
        words = list(map(str, d.instruction[train]))
        model = Chooser(Vocabulary.of(words) if schedule.text else None)
        optimizer = torch.optim.AdamW(
            model.parameters(), lr=schedule.learning_rate, weight_decay=schedule.weight_decay
        )
        data = d.fingerprint() if checkpoint is not None else ""
        history, kept = _resumed(checkpoint, schedule, data, model, optimizer)
        loss_of = nn.CrossEntropyLoss()
        epochs = range(len(history.losses), schedule.epochs)
        shown = tqdm(epochs, desc="training", disable=not progress, initial=len(history.losses))
        for epoch in shown:
            model.train()
            rng = np.random.default_rng([schedule.seed, epoch])
            order = train[rng.permutation(len(train))]
            total = 0.0
            for rows in _chunks(order, schedule.batch):
                inputs, answers = batch(d, rows, model.vocabulary)
                if schedule.mirror:
                    inputs = _mirrored(inputs, rng)
                loss = loss_of(model(inputs), answers)
                optimizer.zero_grad()
                loss.backward()
                optimizer.step()
                total += loss.item() * len(rows)
            history.losses.append(total / len(train))
            if len(held):
                loss, accuracy = _validated(model, d, held, loss_of)
                history.validation.append(loss)
                history.accuracy.append(accuracy)
                shown.set_postfix(validation=f"{loss:.3f}", accuracy=f"{accuracy:.2f}")
            if kept is None or history.kept == epoch:
                kept = _copy(model)
            if checkpoint is not None:
                save(checkpoint, model, schedule, history, kept, data, optimizer)
        torch.set_num_threads(threads)
    model.load_state_dict(kept)
    model.eval()
    return model, history


def slim(path: Path, to: Path) -> Path:
    """Write the checkpoint at ``path`` to ``to`` with what choosing needs alone (the kept
    model, its vocabulary, how it was trained), atomically."""
    state = torch.load(path, weights_only=True)
    kept = {k: state[k] for k in ("vocabulary", "schedule", "losses", "validation", "accuracy")}
    kept["model"] = state["kept"]
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
    try:
        model.load_state_dict(state.get("kept", state["model"]))
    except RuntimeError as exc:
        raise ValueError(
            f"the grounding checkpoint at {path} does not fit this version's network; "
            "train one with `instructmove train-grounding`"
        ) from exc
    return model.eval()


def choose(model: Chooser, d: Decisions, size: int = 256) -> np.ndarray:
    """The option ``model`` scores highest in each decision of ``d``."""
    picked = [s.argmax(dim=1).numpy() for s, _ in _scored(model, d, np.arange(len(d)), size)]
    return np.concatenate(picked) if picked else np.zeros(0, int)
