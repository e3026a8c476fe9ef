"""Clocks: wall time, a manually advanced time for deterministic runs, and ROS sim time."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

__all__ = ["BackwardJumps", "Clock", "ManualClock", "SimClock", "SystemClock"]


class Clock:
    """A source of time in seconds. Interface documented once, here."""

    def now_s(self) -> float:
        """The current time [s]."""
        raise NotImplementedError

    def now_ns(self) -> int:
        return round(self.now_s() * 1e9)


class SystemClock(Clock):
    """Wall-clock time (``time.time``), as ROS's system/ROS time without sim time."""

    def now_s(self) -> float:
        return time.time()


class ManualClock(Clock):
    """Time that only moves when told to: makes in-process runs reproducible."""

    def __init__(self, start_s: float = 0.0) -> None:
        self._now_s = start_s
        self._lock = threading.Lock()

    def now_s(self) -> float:
        return self._now_s

    def set(self, t_s: float) -> None:
        with self._lock:
            if t_s < self._now_s:
                raise ValueError(f"time cannot go backwards ({t_s} < {self._now_s})")
            self._now_s = t_s


class SimClock(Clock):
    """ROS time under ``use_sim_time``: the last value received on /clock (0 before any)."""

    def __init__(self) -> None:
        self._now_s = 0.0

    def now_s(self) -> float:
        return self._now_s

    def update(self, t_s: float) -> None:
        self._now_s = t_s


class BackwardJumps:
    """Whether a clock went back since it was last looked at (a simulation reset, a bag played
    again, ``use_sim_time`` switched on): what tf2_ros's listener and RViz check at each
    message or update. ``now_ns`` is read again at each look (a node's clock may change)."""

    def __init__(self, now_ns: Callable[[], int]) -> None:
        self._now_ns = now_ns
        self._last_ns = now_ns()

    def back_ns(self) -> int:
        """How far the clock went back since the last look [ns]; 0 when it did not."""
        now_ns = self._now_ns()
        back_ns = max(0, self._last_ns - now_ns)
        self._last_ns = now_ns
        return back_ns
