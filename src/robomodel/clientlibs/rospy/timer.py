"""rospy's ``sleep``, ``Rate`` and ``Timer``, in ROS time: a sleep ends early, raising
ROSInterruptException, when the node shuts down."""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.exceptions import (
    ROSInterruptException,
    ROSTimeMovedBackwardsException,
)
from robomodel.clientlibs.rospy.rostime import Duration, Time
from robomodel.runtime.clock import SystemClock

__all__ = ["Rate", "Timer", "TimerEvent", "sleep"]

_SIM_POLL_S = 0.001  # how often a sleep in sim time (or any clock but the wall's) looks at it


def _seconds(duration: Any) -> float:
    return float(duration.to_sec()) if hasattr(duration, "to_sec") else float(duration)


def sleep(duration: Any) -> None:
    """Sleep ``duration`` (seconds, or a Duration) of ROS time. ROSInterruptException if the
    node shuts down meanwhile, ROSTimeMovedBackwardsException if ``/clock`` jumps back."""
    _sleep_until(core.state().node.get_clock().now_s() + _seconds(duration))


def _sleep_until(end_s: float) -> None:
    clock = core.state().node.get_clock()
    stop = core.shutdown_event()
    start_s = clock.now_s()
    sim = not isinstance(clock, SystemClock)
    while True:
        now_s = clock.now_s()
        if stop.is_set():
            raise ROSInterruptException("ROS shutdown request")
        if now_s < start_s:
            raise ROSTimeMovedBackwardsException(start_s - now_s)
        if now_s >= end_s:
            return
        stop.wait(_SIM_POLL_S if sim else end_s - now_s)


class Rate:
    """Sleeps so that a loop runs at ``hz`` (``r = rospy.Rate(10); r.sleep()``). Times are
    whole nanoseconds, as rospy's (its period is ``Duration(0, int(1e9 / hz))``)."""

    def __init__(self, hz: float, reset: bool = False) -> None:
        if not hz > 0:
            raise ValueError(f"Rate needs a rate > 0 Hz, got {hz}")
        self.sleep_dur = Duration(0, int(1e9 / hz))
        self._period_ns = self.sleep_dur.to_nsec()
        self._last_ns = core.state().node.get_clock().now_ns()
        self._reset = reset

    @property
    def last_time(self) -> Time:
        """The time of the last tick."""
        return Time(0, self._last_ns)

    def _remaining_ns(self, now_ns: int) -> int:
        if self._last_ns > now_ns:  # time went back (a bag or a simulator restarted)
            self._last_ns = now_ns
        return self._period_ns - (now_ns - self._last_ns)

    def remaining(self) -> Duration:
        """The time left before the next tick."""
        return Duration(0, self._remaining_ns(core.state().node.get_clock().now_ns()))

    def sleep(self) -> None:
        """Sleep until one period after the last tick (at once if that has passed); a loop
        that fell behind by more than two periods starts afresh. ROSInterruptException when the
        node shuts down."""
        clock = core.state().node.get_clock()
        now_ns = clock.now_ns()
        try:
            _sleep_until((now_ns + max(0, self._remaining_ns(now_ns))) / 1e9)
        except ROSTimeMovedBackwardsException:
            if not self._reset:
                raise
            self._last_ns = clock.now_ns()
            return
        self._last_ns += self._period_ns
        if now_ns - self._last_ns > 2 * self._period_ns:  # as rospy: a loop more than two
            self._last_ns = now_ns  # periods late starts its schedule again from the sleep's start


@dataclass(frozen=True)
class TimerEvent:
    """What a Timer's callback gets: the expected and real times of the last and the current
    call, and how long the last call took."""

    last_expected: Time | None
    last_real: Time | None
    current_expected: Time
    current_real: Time
    last_duration: float | None


class Timer:
    """Calls ``callback(TimerEvent)`` every ``period`` (a Duration) of ROS time, on the node's
    callback thread, until :meth:`shutdown` (or once, with ``oneshot``)."""

    def __init__(
        self,
        period: Any,
        callback: Callable[[TimerEvent], Any],
        oneshot: bool = False,
        reset: bool = False,
    ) -> None:
        self._period = period
        self._period_s = _seconds(period)
        if not self._period_s > 0:
            raise ValueError(f"Timer needs a period > 0 s, got {self._period_s}")
        self._callback = callback
        self._oneshot = oneshot
        self._last_expected: Time | None = None
        self._last_real: Time | None = None
        self._last_duration: float | None = None
        self._lock = threading.Lock()
        node = core.state().node
        self._clock = node.get_clock()
        self._start_s = self._clock.now_s()
        self._ticks = 0
        self._timer = node.create_timer(self._period_s, self._fire)

    def _fire(self) -> None:
        if core.is_shutdown():
            self.shutdown()
            return
        self._ticks += 1
        expected = Time.from_sec(self._start_s + self._ticks * self._period_s)
        real = Time.from_sec(self._clock.now_s())
        event = TimerEvent(
            self._last_expected, self._last_real, expected, real, self._last_duration
        )
        if self._oneshot:
            self.shutdown()
        started_s = self._clock.now_s()
        self._callback(event)
        self._last_duration = self._clock.now_s() - started_s
        self._last_expected, self._last_real = expected, real

    def shutdown(self) -> None:
        """Stop calling the callback."""
        self._timer.cancel()

    def is_alive(self) -> bool:
        """Whether the timer still calls its callback (rospy's Timer is a thread)."""
        return not self._timer.cancelled and not core.is_shutdown()

    def join(self, timeout: float | None = None) -> None:
        """Wait until the timer is shut down, at most ``timeout`` seconds (rospy's Timer is a
        thread)."""
        import time

        end = None if timeout is None else time.monotonic() + timeout
        while self.is_alive() and (end is None or time.monotonic() < end):
            core.shutdown_event().wait(0.05)
