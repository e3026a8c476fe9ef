"""Ctrl-C and SIGTERM as a flag for the verbs whose loops end cleanly (bag, log, master, run)."""

from __future__ import annotations

import signal
from collections.abc import Callable, Iterator
from contextlib import contextmanager

__all__ = ["stop_on_signals"]


@contextmanager
def stop_on_signals() -> Iterator[Callable[[], bool]]:
    """SIGINT and SIGTERM set a flag the caller's loop checks (files closed, exit 0); the
    previous handlers come back on leaving."""
    stopped: list[bool] = []  # a flag, not an Event: a second signal must not wait on a lock
    handlers = {
        sig: signal.signal(sig, lambda *_: stopped.append(True))
        for sig in (signal.SIGINT, signal.SIGTERM)
    }
    try:
        yield lambda: bool(stopped)
    finally:
        for sig, previous in handlers.items():
            signal.signal(sig, previous)
