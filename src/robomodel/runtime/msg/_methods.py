"""Helpers of a few message types, mixed into their generated classes (tools/gen_msgs.py's
``MIXINS``): conversions of ``builtin_interfaces`` times and a random ``UUID``.

A mixin has no fields of its own (``__slots__ = ()``): the generated dataclass declares them;
the annotations here only let the type checker see them.
"""

from __future__ import annotations

import uuid
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from typing_extensions import Self  # typing.Self is Python 3.11+

__all__ = ["DurationMethods", "TimeMethods", "UUIDMethods"]


class _Fields:
    __slots__ = ()
    if TYPE_CHECKING:

        def __init__(self, *args: Any, **kwargs: Any) -> None: ...


class TimeMethods(_Fields):
    """``builtin_interfaces/msg/Time``: ``sec`` [s] and ``nanosec`` [ns] since the epoch (or
    the simulation's start)."""

    __slots__ = ()
    sec: int
    nanosec: int

    @classmethod
    def from_seconds(cls, t_s: float) -> Self:
        total_ns = round(t_s * 1e9)
        return cls(total_ns // 1_000_000_000, total_ns % 1_000_000_000)

    def to_seconds(self) -> float:
        return self.sec + self.nanosec * 1e-9

    def to_nanoseconds(self) -> int:
        return self.sec * 1_000_000_000 + self.nanosec


class DurationMethods(_Fields):
    """``builtin_interfaces/msg/Duration``: ``sec`` [s] and ``nanosec`` [ns]."""

    __slots__ = ()
    sec: int
    nanosec: int

    @classmethod
    def from_seconds(cls, t_s: float) -> Self:
        total_ns = round(t_s * 1e9)
        return cls(total_ns // 1_000_000_000, total_ns % 1_000_000_000)

    def to_seconds(self) -> float:
        return self.sec + self.nanosec * 1e-9


class UUIDMethods(_Fields):
    """``unique_identifier_msgs/msg/UUID``: 16 bytes."""

    __slots__ = ()

    @classmethod
    def random(cls) -> Self:
        return cls(uuid.uuid4().bytes)
