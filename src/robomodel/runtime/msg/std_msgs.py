"""std_msgs: Header, String, Float64, Float64MultiArray (with its layout), Bool, Int32, Empty."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq
from robomodel.runtime.msg.builtin_interfaces import Time

__all__ = [
    "Bool",
    "Empty",
    "Float64",
    "Float64MultiArray",
    "Header",
    "Int32",
    "MultiArrayDimension",
    "MultiArrayLayout",
    "String",
]


@dataclass(slots=True)
class Header(Message):
    """Stamp and coordinate frame of a message."""

    stamp: Time = field(default_factory=Time)
    frame_id: str = ""
    __typename__ = "std_msgs/msg/Header"
    __fields__ = (("stamp", Time), ("frame_id", "string"))


@dataclass(slots=True)
class String(Message):
    data: str = ""
    __typename__ = "std_msgs/msg/String"
    __fields__ = (("data", "string"),)


@dataclass(slots=True)
class Float64(Message):
    data: float = 0.0
    __typename__ = "std_msgs/msg/Float64"
    __fields__ = (("data", "float64"),)


@dataclass(slots=True)
class Bool(Message):
    data: bool = False
    __typename__ = "std_msgs/msg/Bool"
    __fields__ = (("data", "bool"),)


@dataclass(slots=True)
class Int32(Message):
    data: int = 0
    __typename__ = "std_msgs/msg/Int32"
    __fields__ = (("data", "int32"),)


@dataclass(slots=True)
class Empty(Message):
    __typename__ = "std_msgs/msg/Empty"
    __fields__ = ()


@dataclass(slots=True)
class MultiArrayDimension(Message):
    label: str = ""
    size: int = 0
    stride: int = 0
    __typename__ = "std_msgs/msg/MultiArrayDimension"
    __fields__ = (("label", "string"), ("size", "uint32"), ("stride", "uint32"))


@dataclass(slots=True)
class MultiArrayLayout(Message):
    dim: list[MultiArrayDimension] = field(default_factory=list)
    data_offset: int = 0
    __typename__ = "std_msgs/msg/MultiArrayLayout"
    __fields__ = (("dim", Seq(MultiArrayDimension)), ("data_offset", "uint32"))


@dataclass(slots=True)
class Float64MultiArray(Message):
    layout: MultiArrayLayout = field(default_factory=MultiArrayLayout)
    data: list[float] = field(default_factory=list)
    __typename__ = "std_msgs/msg/Float64MultiArray"
    __fields__ = (("layout", MultiArrayLayout), ("data", Seq("float64")))
