"""``rclpy.clock``: clock types and clocks. A node's clock (``node.get_clock()``) is a
:class:`ROSClock` over its robomodel node's clock, so it follows ``/clock`` under
``use_sim_time`` as rclpy's does."""

from __future__ import annotations

import time as _time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered
from robomodel.clientlibs.rclpy.clock_type import ClockType
from robomodel.clientlibs.rclpy.duration import Duration

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.context import Context
    from robomodel.clientlibs.rclpy.time import Time
    from robomodel.runtime.clock import Clock as RobomodelClock

__all__ = ["Clock", "ClockType", "JumpThreshold", "ROSClock"]


class JumpThreshold:
    """Declared for signatures; jump callbacks are not offered."""

    def __init__(
        self, *, min_forward: Any, min_backward: Any, on_clock_change: bool = True
    ) -> None:
        not_offered("rclpy.clock.JumpThreshold (time jump callbacks)")


class Clock:
    """A clock of ``clock_type``: system (wall) time, steady (monotonic) time or ROS time."""

    def __init__(
        self,
        *,
        clock_type: ClockType = ClockType.SYSTEM_TIME,
        source: Callable[[], int] | None = None,
    ) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        self._clock_type = clock_type
        if source is None:
            source = _time.monotonic_ns if clock_type == ClockType.STEADY_TIME else _time.time_ns
        self._source = source

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    def __repr__(self) -> str:
        return f"Clock(clock_type={self._clock_type.name})"

    def now(self) -> Time:
        from robomodel.clientlibs.rclpy.time import Time

        return Time(nanoseconds=self._source(), clock_type=self._clock_type)

    def create_jump_callback(self, *args: Any, **kwargs: Any) -> Any:
        not_offered("Clock.create_jump_callback()")

    def sleep_until(self, until: Time, context: Context | None = None) -> bool:
        """Sleep until this clock reads ``until``; False if the context shut down first."""
        from robomodel.clientlibs.rclpy.utilities import get_default_context

        if until.clock_type != self._clock_type:
            raise ValueError("until's clock type does not match this clock's type")
        ctx = context or get_default_context()
        while ctx.ok():
            remaining_ns = until.nanoseconds - self._source()
            if remaining_ns <= 0:
                return True
            wait_s = remaining_ns / 1e9
            ctx.wait_shutdown(min(wait_s, 0.01) if self._is_sim() else wait_s)
        return False

    def sleep_for(self, rel_time: Duration, context: Context | None = None) -> bool:
        return self.sleep_until(self.now() + rel_time, context)

    def _is_sim(self) -> bool:
        return False


class ROSClock(Clock):
    """ROS time: the robomodel clock ``clock_of()`` gives (the node's: wall or /clock time)."""

    def __init__(self, clock_of: Callable[[], RobomodelClock] | None = None) -> None:
        if clock_of is None:
            from robomodel.runtime.clock import SystemClock

            system = SystemClock()

            def clock_of() -> RobomodelClock:
                return system

        self._clock_of = clock_of
        super().__init__(clock_type=ClockType.ROS_TIME, source=lambda: self._clock_of().now_ns())

    @property
    def ros_time_is_active(self) -> bool:
        """True while the clock follows /clock (``use_sim_time``)."""
        return self._is_sim()

    def _is_sim(self) -> bool:
        from robomodel.runtime.clock import SimClock

        return isinstance(self._clock_of(), SimClock)

    def _set_ros_time_is_active(self, enabled: bool) -> None:
        not_offered("ROSClock._set_ros_time_is_active()", "set the node's use_sim_time parameter")
