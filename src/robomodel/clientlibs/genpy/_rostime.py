"""genpy's ``Time`` and ``Duration``: a whole number of seconds and of nanoseconds.

As genpy keeps them: ``nsecs`` is canonical (``0 <= nsecs < 1e9``, the seconds carry the rest),
a float given as ``secs`` is split into both, a ``Time`` is never negative, a ``Duration`` may
be. ``Time - Time`` is a ``Duration``, ``Time +/- Duration`` a ``Time``; a ``Duration`` scales
by a number and divides by a number or a ``Duration``.
"""

from __future__ import annotations

import numbers
from typing import Any, TypeVar

__all__ = ["Duration", "TVal", "Time"]

_NS_PER_S = 1_000_000_000

T = TypeVar("T", bound="TVal")


def _split(secs: Any, nsecs: Any) -> tuple[int, int]:
    """Whole seconds and nanoseconds; a float's fraction truncated to nanoseconds, as genpy."""
    if not isinstance(secs, numbers.Integral):
        if nsecs != 0:
            raise ValueError(f"if secs is a float ({secs!r}), nsecs cannot be set ({nsecs!r})")
        whole = int(secs)
        return whole, int((float(secs) - whole) * _NS_PER_S)
    return int(secs), int(nsecs)


def _nsec(value: Any) -> int:
    return int(value.secs) * _NS_PER_S + int(value.nsecs)


class _Kind(type):
    """``isinstance(stamp, genpy.Time)`` also holds for a message class's face of
    ``builtin_interfaces/msg/Time`` (``Duration``) that has genpy's ``secs``/``nsecs``: the
    stamps of received genpy-flavoured messages are genpy times, as under ROS 1."""

    _face = ""

    def __instancecheck__(cls, instance: object) -> bool:
        if type.__instancecheck__(cls, instance):
            return True
        kind = type(instance)
        return (
            bool(cls._face)
            and getattr(kind, "__typename__", "") == cls._face
            and hasattr(instance, "secs")
            and "_face" in cls.__dict__  # genpy's own Time/Duration, not rospy's subclasses
        )


class TVal(metaclass=_Kind):
    """A time value: ``secs`` [s] and ``nsecs`` [ns], canonical after every change."""

    __slots__ = ("nsecs", "secs")

    def __init__(self, secs: Any = 0, nsecs: Any = 0) -> None:
        self.secs, self.nsecs = _split(secs, nsecs)
        self.canon()

    @classmethod
    def from_sec(cls: type[T], float_secs: float) -> T:
        """The value of ``float_secs`` seconds."""
        secs = int(float_secs)
        return cls(secs, int((float_secs - secs) * _NS_PER_S))

    def canon(self) -> None:
        """Carry whole seconds out of ``nsecs`` so that ``0 <= nsecs < 1e9``."""
        carry, self.nsecs = divmod(self.nsecs, _NS_PER_S)
        self.secs += carry

    def set(self, secs: int, nsecs: int) -> None:
        self.secs, self.nsecs = int(secs), int(nsecs)
        self.canon()

    def is_zero(self) -> bool:
        return self.secs == 0 and self.nsecs == 0

    def to_sec(self) -> float:
        """The value in seconds, as a float."""
        return float(self.secs) + float(self.nsecs) / 1e9

    def to_nsec(self) -> int:
        """The value in nanoseconds."""
        return self.secs * _NS_PER_S + self.nsecs

    # robomodel's builtin_interfaces names, so a value can stand where a ROS 2 stamp is read
    @property
    def sec(self) -> int:
        return self.secs

    @property
    def nanosec(self) -> int:
        return self.nsecs

    def __bool__(self) -> bool:
        return not self.is_zero()

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __str__(self) -> str:
        return str(self.to_nsec())

    def __getstate__(self) -> tuple[int, int]:
        return self.secs, self.nsecs

    def __setstate__(self, state: tuple[int, int]) -> None:
        self.secs, self.nsecs = state

    def _same_kind(self, other: object) -> bool:
        base = Time if isinstance(self, Time) else Duration
        return isinstance(other, base)

    def __eq__(self, other: object) -> bool:
        if not self._same_kind(other):
            return False
        return self.to_nsec() == _nsec(other)

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    def _compare(self, other: object) -> int:
        if not self._same_kind(other):
            raise TypeError(
                f"cannot compare {type(self).__name__} with {type(other).__name__}"
                " (a Time compares with a Time, a Duration with a Duration)"
            )
        mine, theirs = self.to_nsec(), _nsec(other)
        return (mine > theirs) - (mine < theirs)

    def __lt__(self, other: object) -> bool:
        return self._compare(other) < 0

    def __le__(self, other: object) -> bool:
        return self._compare(other) <= 0

    def __gt__(self, other: object) -> bool:
        return self._compare(other) > 0

    def __ge__(self, other: object) -> bool:
        return self._compare(other) >= 0


class Time(TVal):
    """A point in time since the epoch (ROS 1's ``time``); never negative."""

    __slots__ = ()
    _face = "builtin_interfaces/msg/Time"

    def __init__(self, secs: Any = 0, nsecs: Any = 0) -> None:
        super().__init__(secs, nsecs)
        if self.secs < 0:
            raise TypeError(f"time values must be positive, got {self.secs} s")

    def __repr__(self) -> str:
        return f"genpy.Time[{self.to_nsec()}]"

    def to_time(self) -> float:
        """The time in seconds (``time.time()``'s form); :meth:`to_sec`."""
        return self.to_sec()

    def _duration(self) -> type[Duration]:
        """The Duration class that goes with this Time class (rospy's with rospy's)."""
        return Duration

    def __add__(self, other: object) -> Any:
        if not isinstance(other, Duration):
            return NotImplemented
        return type(self)(self.secs + other.secs, self.nsecs + other.nsecs)

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if isinstance(other, Time):
            return self._duration()(self.secs - other.secs, self.nsecs - other.nsecs)
        if isinstance(other, Duration):
            return type(self)(self.secs - other.secs, self.nsecs - other.nsecs)
        return NotImplemented


class Duration(TVal):
    """A span of time (ROS 1's ``duration``); may be negative (``secs`` carries the sign)."""

    __slots__ = ()
    _face = "builtin_interfaces/msg/Duration"

    def __repr__(self) -> str:
        return f"genpy.Duration[{self.to_nsec()}]"

    def __neg__(self) -> Any:
        return type(self)(-self.secs, -self.nsecs)

    def __abs__(self) -> Any:
        return self if self.secs >= 0 else -self

    def __add__(self, other: object) -> Any:
        if isinstance(other, Time):
            return other + self
        if isinstance(other, Duration):
            return type(self)(self.secs + other.secs, self.nsecs + other.nsecs)
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if not isinstance(other, Duration):
            return NotImplemented
        return type(self)(self.secs - other.secs, self.nsecs - other.nsecs)

    def __mul__(self, val: object) -> Any:
        if isinstance(val, numbers.Integral):
            return type(self)(self.secs * int(val), self.nsecs * int(val))
        if isinstance(val, numbers.Real):
            return type(self).from_sec(self.to_sec() * float(val))
        return NotImplemented

    __rmul__ = __mul__

    # Division and remainder go through float seconds, as genpy computes them.
    def __floordiv__(self, val: object) -> Any:
        if isinstance(val, Duration):
            return int(self.to_sec() // val.to_sec())
        if isinstance(val, numbers.Real):
            return type(self).from_sec(self.to_sec() // float(val))
        return NotImplemented

    def __truediv__(self, val: object) -> Any:
        if isinstance(val, Duration):
            return self.to_sec() / val.to_sec()
        if isinstance(val, numbers.Real):
            return type(self).from_sec(self.to_sec() / float(val))
        return NotImplemented

    def __mod__(self, val: object) -> Any:
        if not isinstance(val, Duration):
            return NotImplemented
        return type(self).from_sec(self.to_sec() % val.to_sec())

    def __divmod__(self, val: object) -> Any:
        if not isinstance(val, Duration):
            return NotImplemented
        quotient, rest = divmod(self.to_sec(), val.to_sec())
        return int(quotient), type(self).from_sec(rest)
