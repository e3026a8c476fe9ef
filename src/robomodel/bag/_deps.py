"""The bag extra's libraries, imported when a bag is opened (never at ``robomodel`` import)."""

from __future__ import annotations

import importlib
from types import ModuleType

from robomodel.errors import MissingDependencyError

__all__ = ["require"]

_DISTRIBUTION = {"mcap": "mcap", "rosbags": "rosbags"}


def require(module: str, purpose: str) -> ModuleType:
    """Import ``module`` (``mcap.writer``, ``rosbags.rosbag1``, ...) or say which extra has it."""
    try:
        return importlib.import_module(module)
    except ImportError:
        top = module.split(".")[0]
        raise MissingDependencyError(_DISTRIBUTION.get(top, top), "bag", purpose) from None
