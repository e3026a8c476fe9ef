"""genpy's ``Time`` and ``Duration`` (``genpy/rostime.py``) as the genpy flavour's classes of
``builtin_interfaces/msg/Time`` and ``Duration``: ``secs`` and ``nsecs`` over the fields ``sec``
and ``nanosec`` that the codecs read, normalised as genpy's ``TVal.canon`` does."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

__all__ = ["DurationMixin", "TVal", "TimeMixin"]

_NS = 1_000_000_000
# Gives the genpy flavour's Duration class (Time - Time): set by robomodel.clientlibs.messages,
# which makes the classes.
DURATION_FACE: list[Callable[[], Any]] = []


class TVal:
    """genpy's TVal: seconds and nanoseconds; the subclass is a message class with the slots
    ``sec`` and ``nanosec``."""

    if TYPE_CHECKING:  # the message class made from the type's fields has these slots
        __slots__ = ("nanosec", "sec")
        sec: int
        nanosec: int
    else:
        __slots__ = ()

    def __init__(
        self,
        secs: int | float = 0,
        nsecs: int = 0,
        *,
        sec: int | None = None,
        nanosec: int | None = None,
    ) -> None:
        if sec is not None or nanosec is not None:  # the message fields' names, as robomodel's
            secs, nsecs = sec or 0, nanosec or 0
        if secs.__class__ is int and nsecs.__class__ is int and 0 <= nsecs < _NS:
            self.sec, self.nanosec = secs, nsecs  # the decoders' case: already canonical
            return
        if not isinstance(secs, int):
            # float seconds, as genpy accepts them
            whole = math.floor(secs)
            nsecs = int(nsecs) + round((secs - whole) * _NS)
            secs = int(whole)
        self.sec, self.nanosec = _canon(int(secs), int(nsecs))

    @property
    def secs(self) -> int:
        return self.sec

    @secs.setter
    def secs(self, value: int) -> None:
        self.sec = value

    @property
    def nsecs(self) -> int:
        return self.nanosec

    @nsecs.setter
    def nsecs(self, value: int) -> None:
        self.nanosec = value

    @classmethod
    def from_sec(cls, float_secs: float) -> Any:
        return cls(float_secs)

    from_seconds = from_sec

    def set(self, secs: int, nsecs: int) -> None:
        self.sec, self.nanosec = int(secs), int(nsecs)

    def canon(self) -> None:
        self.sec, self.nanosec = _canon(self.sec, self.nanosec)

    def is_zero(self) -> bool:
        return self.sec == 0 and self.nanosec == 0

    def to_sec(self) -> float:
        return float(self.sec) + float(self.nanosec) / 1e9

    def to_nsec(self) -> int:
        return self.sec * _NS + self.nanosec

    def __str__(self) -> str:
        return str(self.to_nsec())

    def __bool__(self) -> bool:
        return not self.is_zero()

    def __hash__(self) -> int:
        return hash(self.to_nsec())

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TVal):
            return False
        return self.to_nsec() == other.to_nsec()

    def __lt__(self, other: Any) -> bool:
        return self.to_nsec() < _nsec_of(other)

    def __le__(self, other: Any) -> bool:
        return self.to_nsec() <= _nsec_of(other)

    def __gt__(self, other: Any) -> bool:
        return self.to_nsec() > _nsec_of(other)

    def __ge__(self, other: Any) -> bool:
        return self.to_nsec() >= _nsec_of(other)

    def __getstate__(self) -> list[int]:
        return [self.sec, self.nanosec]

    def __setstate__(self, state: list[int]) -> None:
        self.sec, self.nanosec = state


def _nsec_of(other: Any) -> int:
    if not isinstance(other, TVal):
        raise TypeError(f"cannot compare to {type(other).__name__}")
    return other.to_nsec()


def _canon(secs: int, nsecs: int) -> tuple[int, int]:
    secs += nsecs // _NS
    return secs, nsecs % _NS


class TimeMixin(TVal):
    """genpy's Time: a point in time; ``Time + Duration``, ``Time - Time -> Duration``."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"genpy.Time[{self.to_nsec()}]"

    def __add__(self, other: Any) -> Any:
        if not isinstance(other, DurationMixin):
            return NotImplemented
        return type(self)(self.sec + other.sec, self.nanosec + other.nanosec)

    __radd__ = __add__

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, TimeMixin):
            return DURATION_FACE[0]()(0, self.to_nsec() - other.to_nsec())
        if isinstance(other, DurationMixin):
            return type(self)(0, self.to_nsec() - other.to_nsec())
        return NotImplemented


class DurationMixin(TVal):
    """genpy's Duration: a signed span of time."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"genpy.Duration[{self.to_nsec()}]"

    def __neg__(self) -> Any:
        return type(self)(0, -self.to_nsec())

    def __abs__(self) -> Any:
        return self if self.to_nsec() >= 0 else -self

    def __add__(self, other: Any) -> Any:
        if isinstance(other, TimeMixin):
            return other + self
        if isinstance(other, DurationMixin):
            return type(self)(0, self.to_nsec() + other.to_nsec())
        return NotImplemented

    def __sub__(self, other: Any) -> Any:
        if not isinstance(other, DurationMixin):
            return NotImplemented
        return type(self)(0, self.to_nsec() - other.to_nsec())

    def __mul__(self, factor: float) -> Any:
        return type(self)(0, round(self.to_nsec() * factor))

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> Any:
        if isinstance(other, DurationMixin):
            return self.to_nsec() / other.to_nsec()
        return type(self)(0, round(self.to_nsec() / other))
