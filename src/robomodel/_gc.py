"""Pausing the cyclic garbage collector while a parser builds many small objects."""

from __future__ import annotations

import contextlib
import gc
from collections.abc import Iterator

__all__ = ["paused_gc"]


@contextlib.contextmanager
def paused_gc() -> Iterator[None]:
    """Pause the cyclic collector while a tree of objects grows (it would traverse the growing
    tree again and again: ~15% of a URDF parse), then hand the survivors to the oldest
    generation (``gc.freeze()`` + ``gc.unfreeze()``, O(1)), so the next young collection does
    not traverse them all at once. Nothing is leaked: cyclic garbage made meanwhile is
    collected by the next full collection. The freeze is skipped if the application uses
    ``gc.freeze()`` itself, and nothing changes if the collector was already off."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            if gc.get_freeze_count() == 0:
                gc.freeze()
                gc.unfreeze()
            gc.enable()
