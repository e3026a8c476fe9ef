"""Helpers shared by the Zenoh transport's modules."""

from __future__ import annotations

import logging
from typing import Any

from robomodel.errors import MissingDependencyError

__all__ = ["import_zenoh", "log", "mangle", "unmangle"]

log = logging.getLogger("robomodel.runtime")


def mangle(name: str) -> str:
    return name.replace("/", "%") or "%"


def unmangle(text: str) -> str:
    return text.replace("%", "/")


def import_zenoh() -> Any:
    try:
        import zenoh
    except ImportError:
        raise MissingDependencyError("eclipse-zenoh", "bus", "the zenoh bus") from None
    return zenoh
