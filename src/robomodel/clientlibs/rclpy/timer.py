"""``rclpy.timer``: :class:`Timer` over a robomodel node's timer (on the node's clock: wall
time, or /clock under ``use_sim_time``), and :class:`Rate`."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy.clock import Clock
from robomodel.clientlibs.rclpy.duration import Duration
from robomodel.clientlibs.rclpy.exceptions import ROSInterruptException
from robomodel.clientlibs.rclpy.time import Time

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.context import Context
    from robomodel.runtime.executor import Timer as RobomodelTimer
    from robomodel.runtime.node import Node as RobomodelNode

__all__ = ["Rate", "Timer"]


class Timer:
    """Calls ``callback()`` every ``timer_period_ns`` (made by ``Node.create_timer``)."""

    def __init__(
        self,
        node: RobomodelNode,
        fire: Callable[[], None],
        callback: Callable[[], Any],
        callback_group: CallbackGroup,
        timer_period_ns: int,
        clock: Clock,
        *,
        autostart: bool = True,
    ) -> None:
        self._node = node
        self._fire = fire
        self.callback = callback
        self.callback_group = callback_group
        self.clock = clock
        self._period_ns = int(timer_period_ns)
        if self._period_ns <= 0:
            raise ValueError(f"timer period must be > 0, got {timer_period_ns} ns")
        self._timer: RobomodelTimer | None = self._start() if autostart else None
        self._last_call_ns = self._now_ns()

    def _start(self) -> RobomodelTimer:
        return self._node.create_timer(self._period_ns / 1e9, self._tick)

    def _tick(self) -> None:
        self._last_call_ns = self._now_ns()
        self._fire()

    def _now_ns(self) -> int:
        return self._node.get_clock().now_ns()

    @property
    def timer_period_ns(self) -> int:
        return self._period_ns

    @timer_period_ns.setter
    def timer_period_ns(self, value: int) -> None:
        self._period_ns = int(value)
        if self._timer is not None:
            self._timer.period_s = self._period_ns / 1e9
            self._timer.reset()

    def is_canceled(self) -> bool:
        return self._timer is None or self._timer.cancelled

    def cancel(self) -> None:
        if self._timer is not None:
            self._timer.cancel()

    def reset(self) -> None:
        """Start the period again from now (a cancelled timer runs again)."""
        if self._timer is None or self._timer.cancelled:
            self._timer = self._start()
        else:
            self._timer.reset()

    def is_ready(self) -> bool:
        return self.time_until_next_call() == 0

    def time_since_last_call(self) -> int:
        return self._now_ns() - self._last_call_ns

    def time_until_next_call(self) -> int | None:
        """Nanoseconds to the next call (0 if due); None if cancelled."""
        timer = self._timer
        if timer is None or timer.cancelled:
            return None
        return max(0, round(timer.next_s * 1e9) - self._now_ns())

    def destroy(self) -> None:
        self.cancel()

    def __enter__(self) -> Timer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy()


class Rate:
    """Sleeps so that a loop runs at ``frequency`` Hz on ``clock`` (``Node.create_rate``)."""

    def __init__(self, frequency: float, clock: Clock, context: Context) -> None:
        if frequency <= 0:
            raise ValueError(f"rate must be > 0 Hz, got {frequency}")
        self._period = Duration(seconds=1.0 / frequency)
        self._clock = clock
        self._context = context
        self._start_ns = clock.now().nanoseconds
        self._destroyed = False

    def sleep(self) -> None:
        """Sleep until the next period boundary; ROSInterruptException on shutdown."""
        if self._destroyed:
            raise ROSInterruptException()
        period_ns = self._period.nanoseconds
        now_ns = self._clock.now().nanoseconds
        ticks = (now_ns - self._start_ns) // period_ns + 1
        until = Time(nanoseconds=self._start_ns + ticks * period_ns,
                     clock_type=self._clock.clock_type)  # fmt: skip
        if not self._clock.sleep_until(until, self._context):
            raise ROSInterruptException()

    def destroy(self) -> None:
        self._destroyed = True
