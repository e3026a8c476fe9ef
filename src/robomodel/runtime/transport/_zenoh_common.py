"""Helpers shared by the Zenoh transport's modules."""

from __future__ import annotations

import logging
from typing import Any

from robomodel.errors import MissingDependencyError

__all__ = ["import_zenoh", "log", "undeclare_all"]

log = logging.getLogger("robomodel.runtime")


def import_zenoh() -> Any:
    try:
        import zenoh
        import zenoh.ext
    except ImportError:
        raise MissingDependencyError("eclipse-zenoh", "bus", "the zenoh bus") from None
    return zenoh


def undeclare_all(*handles: Any) -> None:
    """Undeclare Zenoh entities, in order; one already gone (session closed) is skipped."""
    for handle in handles:
        if handle is None:
            continue
        try:
            handle.undeclare()
        except Exception:
            log.debug("undeclare failed", exc_info=True)
