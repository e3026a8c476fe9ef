"""``rclpy.time.Time``: a point in time of one clock type, in integer nanoseconds."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.rclpy._support import interface
from robomodel.clientlibs.rclpy.clock_type import ClockType
from robomodel.clientlibs.rclpy.duration import Duration

__all__ = ["Time"]

_S = 1_000_000_000


class Time:
    """A time (``Time(seconds=1, nanoseconds=5)``); arithmetic with :class:`Duration`, and
    comparisons between times of the same clock type (others raise TypeError, as rclpy)."""

    __slots__ = ("_clock_type", "_nanoseconds")

    def __init__(
        self,
        *,
        seconds: float = 0,
        nanoseconds: int = 0,
        clock_type: ClockType = ClockType.SYSTEM_TIME,
    ) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        if seconds < 0 or nanoseconds < 0:
            raise ValueError("Seconds and nanoseconds must not be negative")
        total = int(seconds * _S) + int(nanoseconds)
        if total >= 2**63:
            raise OverflowError("Total nanoseconds value is too large to store in C time point.")
        self._nanoseconds = total
        self._clock_type = clock_type

    @property
    def nanoseconds(self) -> int:
        return self._nanoseconds

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    def seconds_nanoseconds(self) -> tuple[int, int]:
        """(seconds, nanoseconds) with 0 <= nanoseconds < 1e9."""
        sec, nanosec = divmod(self._nanoseconds, _S)
        return sec, nanosec

    def __repr__(self) -> str:
        return f"Time(nanoseconds={self._nanoseconds}, clock_type={self._clock_type.name})"

    def __str__(self) -> str:
        return repr(self)

    def __add__(self, other: object) -> Time:
        if isinstance(other, Duration):
            total = self._nanoseconds + other.nanoseconds
            if total < 0:
                raise ValueError("The result of the addition would be a negative time")
            return Time(nanoseconds=total, clock_type=self._clock_type)
        raise TypeError("Time can only be added to Duration")

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if isinstance(other, Time):
            if other._clock_type != self._clock_type:
                raise TypeError("Can't subtract times with different clock types")
            return Duration(nanoseconds=self._nanoseconds - other._nanoseconds)
        if isinstance(other, Duration):
            total = self._nanoseconds - other.nanoseconds
            if total < 0:
                raise ValueError("The result of the subtraction would be a negative time")
            return Time(nanoseconds=total, clock_type=self._clock_type)
        raise TypeError(f"Can't subtract {type(other).__name__} from Time")

    def _other(self, other: object) -> int:
        if not isinstance(other, Time):
            raise TypeError("Can't compare time with object of type: ", type(other))
        if other._clock_type != self._clock_type:
            raise TypeError("Can't compare times with different clock types")
        return other._nanoseconds

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Time):
            return self._nanoseconds == self._other(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash((self._nanoseconds, self._clock_type))

    def __lt__(self, other: object) -> bool:
        return self._nanoseconds < self._other(other)

    def __le__(self, other: object) -> bool:
        return self._nanoseconds <= self._other(other)

    def __gt__(self, other: object) -> bool:
        return self._nanoseconds > self._other(other)

    def __ge__(self, other: object) -> bool:
        return self._nanoseconds >= self._other(other)

    def to_msg(self) -> Any:
        """``builtin_interfaces/Time``, of the flavour user code imports."""
        sec, nanosec = self.seconds_nanoseconds()
        return interface("builtin_interfaces.msg", "Time")(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg: Any, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)
