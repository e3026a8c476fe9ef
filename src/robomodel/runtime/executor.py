"""A single-threaded executor: queued callbacks and timers, run by spin calls.

Transports post callbacks from any thread; the executor runs them one at a time on the thread
that spins, in the order they were posted, as rclpy's SingleThreadedExecutor does. A callback
that raises is logged and the executor goes on: a bad message never kills a node.
"""

from __future__ import annotations

import collections
import logging
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from robomodel.runtime.clock import Clock, ManualClock

__all__ = ["Executor", "Timer"]

log = logging.getLogger("robomodel.runtime")


def _noop() -> None:
    """Posted to wake the spinning thread (a new timer, a stop request)."""


@dataclass(eq=False)
class Timer:
    """A periodic callback on a clock (the node's clock: wall or sim time)."""

    period_s: float
    callback: Callable[[], None]
    clock: Clock
    start_s: float
    ticks: int = 1
    cancelled: bool = False

    @property
    def next_s(self) -> float:
        # start + k * period, never accumulated, so the 1000th tick is still exact.
        return self.start_s + self.ticks * self.period_s

    @property
    def last_s(self) -> float:
        """When the timer last ticked (its start before the first tick) [s]."""
        return self.start_s + (self.ticks - 1) * self.period_s

    def cancel(self) -> None:
        self.cancelled = True

    def reset(self) -> None:
        self.start_s = self.clock.now_s()
        self.ticks = 1

    def consume(self, now_s: float) -> None:
        """Mark the current tick done; if far behind, skip missed ticks (as rclpy does)."""
        self.ticks += 1
        if self.next_s <= now_s:
            self.ticks = int((now_s - self.start_s) // self.period_s) + 1


# How far back a clock must go to count as a jump [s]: more than the rounding of a tick's time
# (a float near the epoch's 1.7e9 s is exact to about 2e-7 s)
_JUMP_TOLERANCE_S = 1e-4


def _next_s(timer: Timer) -> float:
    return timer.next_s


class Executor:
    """Runs posted callbacks and due timers."""

    def __init__(self) -> None:
        # Producers append (atomic under the GIL) and ring the bell only when it is not rung
        # already. The bell is a bare lock, held while silent: ringing releases it, and the
        # spinning thread's acquire both waits for a ring and silences it again. That is
        # threading.Event without its Condition (a waiter list, a lock per wait, notify_all),
        # which cost ~10 us a message at 1 kHz. The spinning thread
        # waits in lock.acquire, never in queue.SimpleQueue.get with a timeout: on CPython
        # 3.11/3.12 that get blocks forever once a signal handler (Ctrl-C's) runs past its
        # deadline (tests/runtime/test_executor_signals.py), where lock.acquire checks the
        # deadline again.
        self._queue: collections.deque[Callable[[], None]] = collections.deque()
        self._bell = threading.Lock()
        self._bell.acquire()  # silent
        self._timers: list[Timer] = []
        # Bells of others that wait for posts (rclpy's executors, each waiting on its own so
        # that work parked for one wakes that one): rung by every post, set by add_ring.
        self._rings: tuple[Callable[[], None], ...] = ()
        self._rings_lock = threading.Lock()
        self._stopped = False
        self.spinner: int | None = None  # the ident of the thread that spins, once one did

    # -- producers (any thread) ----------------------------------------------------------
    def post(self, callback: Callable[[], None]) -> None:
        self._queue.append(callback)
        if self._bell.locked():  # a stale answer is harmless: the waiter silences, then looks
            try:  # noqa: SIM105 (contextlib.suppress costs a Python-level __exit__ per post)
                self._bell.release()
            except RuntimeError:  # another producer rang it in between
                pass
        for ring in self._rings:
            ring()

    def add_ring(self, ring: Callable[[], None]) -> None:
        """Call ``ring()`` (cheap, any thread) at every post from now on, until
        :meth:`remove_ring`: how a waiter with a bell of its own hears of work."""
        with self._rings_lock:
            self._rings = (*self._rings, ring)

    def remove_ring(self, ring: Callable[[], None]) -> None:
        with self._rings_lock:
            rings = list(self._rings)
            if ring in rings:
                rings.remove(ring)
            self._rings = tuple(rings)

    def wake(self) -> None:
        """Wake whoever waits for work to look again; no work itself (not counted as run)."""
        self.post(_noop)

    def answer(
        self,
        handler: Callable[[dict[str, Any]], dict[str, Any]],
        request: dict[str, Any],
        timeout_s: float,
    ) -> dict[str, Any] | None:
        """Run ``handler(request)`` on the spinning thread and wait for its reply (a service or
        parameter request from another thread). An exception becomes ``{"error": text}``;
        ``None`` if no reply came within ``timeout_s``."""
        done = threading.Event()
        box: dict[str, dict[str, Any]] = {}

        def run() -> None:
            try:
                box["reply"] = handler(request)
            except Exception as exc:
                box["reply"] = {"error": str(exc)}
            done.set()

        self.post(run)
        return box["reply"] if done.wait(timeout_s) else None

    def add_timer(self, period_s: float, callback: Callable[[], None], clock: Clock) -> Timer:
        if not period_s > 0:
            raise ValueError(f"timer period must be > 0 s, got {period_s}")
        timer = Timer(period_s, callback, clock, clock.now_s())
        self._timers.append(timer)
        self.wake()
        return timer

    def stop(self) -> None:
        self._stopped = True
        self.wake()

    @property
    def stopped(self) -> bool:
        return self._stopped

    # -- consumers (the spinning thread) ---------------------------------------------------
    def _run(self, callback: Callable[[], None]) -> None:
        try:
            callback()
        except Exception:
            log.exception("callback failed; the node keeps running")

    def run_pending(self) -> int:
        """Run every queued callback (including ones queued meanwhile); return how many were
        work (not wake-ups)."""
        count = 0
        while True:
            try:
                callback = self._queue.popleft()
            except IndexError:
                return count
            self._run(callback)
            count += callback is not _noop  # a wake-up is no work

    def run_due_timers(self) -> int:
        count = 0
        self._timers = [t for t in self._timers if not t.cancelled]
        for timer in list(self._timers):
            now = timer.clock.now_s()
            if now < timer.last_s - _JUMP_TOLERANCE_S:
                # The clock went back past the timer's last tick (/clock of a simulation that
                # was reset, of a bag played again): its next tick is a period from now, as
                # rcl's timers do after a backward jump (and roscpp's), not when the clock
                # is back where it was.
                timer.reset()
            if timer.cancelled or timer.next_s > now + 1e-12:
                continue
            timer.consume(now)
            self._run(timer.callback)
            count += 1
        return count

    def spin_once(self, timeout_s: float = 0.0) -> int:
        """Run what is ready; if nothing is, wait up to ``timeout_s`` for work. Returns how
        many callbacks ran (a wake-up is none)."""
        self.spinner = threading.get_ident()
        done = self.run_pending() + self.run_due_timers()
        if done or timeout_s <= 0 or self._stopped:
            return done
        wait = self.wait_s(timeout_s)
        self._bell.acquire(blocking=False)  # silence, then look: a later post rings again
        if not self._queue and wait > 0:
            self._bell.acquire(timeout=wait)
        return self.run_pending() + self.run_due_timers()

    def wait_s(self, timeout_s: float) -> float:
        """``timeout_s``, or less when a timer on a running clock is due sooner: how long a
        waiter for work may sleep."""
        live = [t for t in self._timers if not t.cancelled and not isinstance(t.clock, ManualClock)]
        if live:
            return min(timeout_s, max(0.0, min(t.next_s - t.clock.now_s() for t in live)))
        return timeout_s

    def spin(
        self, *, duration_s: float | None = None, until: Callable[[], bool] | None = None
    ) -> None:
        """Spin until stopped, ``until()`` is true, or ``duration_s`` of wall time passed."""
        end = None if duration_s is None else time.monotonic() + duration_s
        while not self._stopped:
            if until is not None and until():
                return
            remaining = 0.05 if end is None else end - time.monotonic()
            if remaining <= 0:
                return
            self.spin_once(min(remaining, 0.05))

    def advance(self, clock: ManualClock, dt_s: float) -> None:
        """Move a manual clock forward by ``dt_s``, firing timers at their exact times in order."""
        target = clock.now_s() + dt_s
        limit = target + 1e-12
        self.run_pending()
        while True:
            # the earliest due timer; min keeps the first of equals: registration order
            timer = min(
                (
                    t
                    for t in self._timers
                    if t.next_s <= limit and t.clock is clock and not t.cancelled
                ),
                key=_next_s,
                default=None,
            )
            if timer is None:
                break
            clock.set(max(timer.next_s, clock.now_s()))
            timer.ticks += 1
            self._run(timer.callback)
            self.run_pending()
        # A timer due within the 1e-12 s tolerance may have moved the clock just past target.
        clock.set(max(target, clock.now_s()))
        self.run_pending()
