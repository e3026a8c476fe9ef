"""``rclpy.duration.Duration``: a signed span of time in integer nanoseconds."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.rclpy._support import interface

__all__ = ["Duration", "Infinite"]

_S = 1_000_000_000


class Duration:
    """A duration (``Duration(seconds=1.5)``, ``Duration(nanoseconds=10)``); the two add up."""

    __slots__ = ("_nanoseconds",)

    def __init__(self, *, seconds: float = 0, nanoseconds: int = 0) -> None:
        total = int(seconds * _S) + int(nanoseconds)
        if not -(2**63) <= total < 2**63:
            raise OverflowError("Total nanoseconds value is too large to store in C duration.")
        self._nanoseconds = total

    @property
    def nanoseconds(self) -> int:
        return self._nanoseconds

    def __repr__(self) -> str:
        return f"Duration(nanoseconds={self._nanoseconds})"

    def __str__(self) -> str:
        if self == Infinite:
            return "Infinite"
        return f"{self._nanoseconds / _S} seconds"

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Duration):
            return self._nanoseconds == other._nanoseconds
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self._nanoseconds)

    def _other(self, other: object, op: str) -> int:
        if not isinstance(other, Duration):
            raise TypeError(f"Can't compare duration with object of type: {type(other)}")
        return other._nanoseconds

    def __lt__(self, other: object) -> bool:
        return self._nanoseconds < self._other(other, "<")

    def __le__(self, other: object) -> bool:
        return self._nanoseconds <= self._other(other, "<=")

    def __gt__(self, other: object) -> bool:
        return self._nanoseconds > self._other(other, ">")

    def __ge__(self, other: object) -> bool:
        return self._nanoseconds >= self._other(other, ">=")

    def __add__(self, other: object) -> Any:
        if isinstance(other, Duration):
            return Duration(nanoseconds=self._nanoseconds + other._nanoseconds)
        return NotImplemented  # Time + Duration is Time's

    def __sub__(self, other: object) -> Duration:
        if isinstance(other, Duration):
            return Duration(nanoseconds=self._nanoseconds - other._nanoseconds)
        return NotImplemented

    def __mul__(self, factor: object) -> Duration:
        if isinstance(factor, (int, float)) and not isinstance(factor, bool):
            return Duration(nanoseconds=int(self._nanoseconds * factor))
        return NotImplemented

    __rmul__ = __mul__

    def __neg__(self) -> Duration:
        return Duration(nanoseconds=-self._nanoseconds)

    def to_msg(self) -> Any:
        """``builtin_interfaces/Duration`` (sec, nanosec with 0 <= nanosec < 1e9)."""
        sec, nanosec = divmod(self._nanoseconds, _S)
        return interface("builtin_interfaces.msg", "Duration")(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg: Any) -> Duration:
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec)

    def get_c_duration(self) -> Any:
        from robomodel.clientlibs.rclpy._support import not_offered

        not_offered("Duration.get_c_duration()", "use .nanoseconds")


Infinite = Duration(nanoseconds=2**63 - 1)
