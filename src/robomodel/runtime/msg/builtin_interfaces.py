"""builtin_interfaces: Time and Duration."""

from __future__ import annotations

from dataclasses import dataclass

from robomodel.runtime.msg._schema import Message

__all__ = ["Duration", "Time"]


@dataclass(slots=True)
class Time(Message):
    """A point in time: ``sec`` [s] and ``nanosec`` [ns] since the epoch (or sim start)."""

    sec: int = 0
    nanosec: int = 0
    __typename__ = "builtin_interfaces/msg/Time"
    __fields__ = (("sec", "int32"), ("nanosec", "uint32"))

    @classmethod
    def from_seconds(cls, t_s: float) -> Time:
        total_ns = round(t_s * 1e9)
        return cls(total_ns // 1_000_000_000, total_ns % 1_000_000_000)

    def to_seconds(self) -> float:
        return self.sec + self.nanosec * 1e-9

    def to_nanoseconds(self) -> int:
        return self.sec * 1_000_000_000 + self.nanosec


@dataclass(slots=True)
class Duration(Message):
    """A time span: ``sec`` [s] and ``nanosec`` [ns]."""

    sec: int = 0
    nanosec: int = 0
    __typename__ = "builtin_interfaces/msg/Duration"
    __fields__ = (("sec", "int32"), ("nanosec", "uint32"))

    @classmethod
    def from_seconds(cls, t_s: float) -> Duration:
        total_ns = round(t_s * 1e9)
        return cls(total_ns // 1_000_000_000, total_ns % 1_000_000_000)

    def to_seconds(self) -> float:
        return self.sec + self.nanosec * 1e-9
