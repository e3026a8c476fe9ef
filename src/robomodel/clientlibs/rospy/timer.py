"""rospy's ``sleep``, ``Rate`` and ``Timer``, in ROS time. As rospy's: a sleep in wall-clock
time sleeps its whole duration even when the node shuts down meanwhile (a loop
``while not rospy.is_shutdown()`` then ends), a sleep in simulated time ends early at shutdown,
raising ROSInterruptException; each Timer is a thread of its own.

Bound: at most ``MAX_TIMER_THREADS`` Timers alive at once in a process; one more raises
ROSException naming the bound (:func:`timer_threads` counts them)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.exceptions import (
    ROSException,
    ROSInterruptException,
    ROSTimeMovedBackwardsException,
)
from robomodel.clientlibs.rospy.rostime import Duration, Time
from robomodel.runtime.clock import SystemClock

__all__ = ["MAX_TIMER_THREADS", "Rate", "Timer", "TimerEvent", "sleep", "timer_threads"]

_SIM_POLL_S = 0.001  # how often a sleep in sim time (or any clock but the wall's) looks at it
# rospy's Timers are threads without bound; a node has a few. 256 threads cost a few MiB.
MAX_TIMER_THREADS = 256
_alive_timers = 0
_count_lock = threading.Lock()


def timer_threads() -> int:
    """The Timer threads alive in this process now."""
    return _alive_timers


def _seconds(duration: Any) -> float:
    return float(duration.to_sec()) if hasattr(duration, "to_sec") else float(duration)


def sleep(duration: Any) -> None:
    """Sleep ``duration`` (seconds, or a Duration) of ROS time. ROSInterruptException if the
    node shuts down meanwhile, ROSTimeMovedBackwardsException if ``/clock`` jumps back."""
    _sleep_until(core.state().node.get_clock().now_s() + _seconds(duration))


def _sleep_until(end_s: float) -> None:
    clock = core.state().node.get_clock()
    if isinstance(clock, SystemClock):
        remaining_s = end_s - clock.now_s()
        while remaining_s > 0:  # as rospy's wall-clock sleep: shutdown does not end it
            time.sleep(remaining_s)
            remaining_s = end_s - clock.now_s()
        return
    stop = core.shutdown_event()
    start_s = clock.now_s()
    while True:
        now_s = clock.now_s()
        if stop.is_set():
            raise ROSInterruptException("ROS shutdown request")
        if now_s < start_s:
            raise ROSTimeMovedBackwardsException(start_s - now_s)
        if now_s >= end_s:
            return
        stop.wait(_SIM_POLL_S)


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


class Timer(threading.Thread):
    """Calls ``callback(TimerEvent)`` every ``period`` (a Duration) of ROS time, on a thread of
    its own (rospy's Timer is a thread), until :meth:`shutdown` or the node's shutdown (or
    once, with ``oneshot``). A Timer shut down ends at its next tick, without calling."""

    def __init__(
        self,
        period: Any,
        callback: Callable[[TimerEvent], Any],
        oneshot: bool = False,
        reset: bool = False,
    ) -> None:
        period_s = _seconds(period)
        if not period_s > 0:
            raise ValueError(f"Timer needs a period > 0 s, got {period_s}")
        super().__init__(name="rospy-timer", daemon=True)
        self._period = period if isinstance(period, Duration) else Duration.from_sec(period_s)
        self._callback = callback
        self._oneshot = oneshot
        self._shutdown = False
        self._rate = Rate(1.0 / period_s, reset=reset)
        self._first_expected = self._rate.last_time + self._period
        _take_timer()
        try:
            self.start()
        except BaseException:
            _give_timer()
            raise

    def shutdown(self) -> None:
        """Stop calling the callback."""
        self._shutdown = True

    def run(self) -> None:
        try:
            self._loop()
        finally:
            _give_timer()

    def _loop(self) -> None:
        expected = self._first_expected
        last_expected: Time | None = None
        last_real: Time | None = None
        last_duration: float | None = None
        while not (core.is_shutdown() or self._shutdown):
            try:
                self._rate.sleep()
            except ROSInterruptException:
                return
            if core.is_shutdown() or self._shutdown:
                return
            real = Time(0, core.state().node.get_clock().now_ns())
            started = time.monotonic()
            self._callback(TimerEvent(last_expected, last_real, expected, real, last_duration))
            if self._oneshot:
                return
            last_duration = time.monotonic() - started
            last_expected, last_real = expected, real
            expected = expected + self._period


def _take_timer() -> None:
    global _alive_timers
    with _count_lock:
        if _alive_timers >= MAX_TIMER_THREADS:
            raise ROSException(
                f"more than {MAX_TIMER_THREADS} rospy Timers alive at once in this process "
                "(MAX_TIMER_THREADS): shut some down first"
            )
        _alive_timers += 1


def _give_timer() -> None:
    global _alive_timers
    with _count_lock:
        _alive_timers -= 1
