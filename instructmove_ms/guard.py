"""Policy failures during evaluation: guarded calls, action checks and their score.

A policy that raises, or returns an action of the wrong shape or with NaN/inf, ends its
episode with a :class:`PolicyError`. The evaluator records the message and scores the
episode as failed (``EpisodeResult.failed``: every stage false, no grounding or control
error): it stays in every rate's denominator, so a policy cannot raise its rates by
crashing on hard episodes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import torch


class PolicyError(Exception):
    """The policy failed this episode; the message says how."""


class ServerError(Exception):
    """The policy's infrastructure failed (its server cannot be reached, or the connection
    was lost and did not come back): not the policy's fault, so no episode's score."""


def guarded(name: str, fn: Callable[..., Any], *args: Any) -> Any:
    """``fn(*args)``, with any exception but a ``ServerError`` raised again as a
    PolicyError naming ``name``."""
    try:
        return fn(*args)
    except ServerError:
        raise
    except Exception as exc:
        raise PolicyError(f"{name}() raised {type(exc).__name__}: {exc}") from exc


def check_action(action: Any, dim: int, num_envs: int) -> torch.Tensor | np.ndarray:
    """``action`` (a tensor, or else as a float32 array) if it has a shape the env takes
    and only finite values."""
    if not isinstance(action, torch.Tensor):
        try:
            action = np.asarray(action, dtype=np.float32)
        except (TypeError, ValueError) as exc:
            raise PolicyError(f"act() returned a {type(action).__name__}: {exc}") from exc
    shape = tuple(action.shape)
    allowed = [(num_envs, dim)] + ([(dim,)] if num_envs == 1 else [])
    if shape not in allowed:
        expected = " or ".join(str(s) for s in reversed(allowed))
        raise PolicyError(f"act() returned shape {shape}, expected {expected}")
    finite = torch.isfinite if isinstance(action, torch.Tensor) else np.isfinite
    if not finite(action).all():
        raise PolicyError("act() returned NaN or inf")
    return action
