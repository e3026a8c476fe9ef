"""A byte budget shared by the readers of one process (XML-RPC bodies, TCPROS frames)."""

from __future__ import annotations

import threading

__all__ = ["ByteBudget"]


class ByteBudget:
    """Bytes charged by what is being read right now, at most ``limit``: one budget per kind
    of input, so that many peers together cannot hold more than it, whatever each may send."""

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.used = 0
        self._lock = threading.Lock()

    def take(self, size: int) -> bool:
        """Charge ``size`` bytes; False (nothing charged) when they do not fit."""
        with self._lock:
            if self.used + size > self.limit:
                return False
            self.used += size
            return True

    def give(self, size: int) -> None:
        """Give back what :meth:`take` charged."""
        with self._lock:
            self.used -= size
