"""Bridges to the field's training and evaluation tools, each behind an optional import; the
core and ``tasks/`` never import them."""

from __future__ import annotations

import importlib
from types import ModuleType


class MissingExtra(ImportError):
    """An optional dependency is not installed; the message names the extra to install."""


def require(module: str, extra: str, what: str) -> ModuleType:
    """``module`` imported, or ``MissingExtra`` naming the extra that installs it."""
    try:
        return importlib.import_module(module)
    except MissingExtra:
        raise
    except ImportError as exc:
        raise MissingExtra(
            f"{what} needs {module.split('.')[0]}, which is not installed: "
            f"pip install 'instructmove-ms[{extra}]' ({exc})"
        ) from None
