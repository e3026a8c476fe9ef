"""Helpers shared by the Zenoh transport's modules."""

from __future__ import annotations

import logging
from typing import Any

from robomodel.errors import MissingDependencyError

__all__ = ["direct", "import_zenoh", "log", "undeclare_all"]

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


def direct(callback: Any) -> Any:
    """``callback`` as a Zenoh handler run on Zenoh's own receiving thread.

    zenoh-python otherwise starts a Python thread per subscriber or queryable and hands each
    sample over to it: 120 threads and ~0.4 s for 20 nodes' parameter services, and a thread
    switch on every message. robomodel's callbacks only queue the sample for the executor.
    """
    zenoh = import_zenoh()
    return zenoh.handlers.Callback(callback, indirect=False)
