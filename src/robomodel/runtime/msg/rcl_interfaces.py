"""rcl_interfaces (Jazzy): parameter values, descriptors and events, the six parameter
services every ROS 2 node offers (``~/get_parameters``, ``~/set_parameters``, ...), and the
``/rosout`` Log message."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from robomodel.runtime.msg._schema import Message, Seq, Service
from robomodel.runtime.msg.builtin_interfaces import Time

__all__ = [
    "DescribeParameters",
    "FloatingPointRange",
    "GetParameterTypes",
    "GetParameters",
    "IntegerRange",
    "ListParameters",
    "ListParametersResult",
    "Log",
    "Parameter",
    "ParameterDescriptor",
    "ParameterEvent",
    "ParameterType",
    "ParameterValue",
    "SetParameters",
    "SetParametersAtomically",
    "SetParametersResult",
]


class ParameterType:
    """rcl_interfaces/msg/ParameterType: the constants of ``ParameterValue.type``."""

    PARAMETER_NOT_SET: ClassVar[int] = 0
    PARAMETER_BOOL: ClassVar[int] = 1
    PARAMETER_INTEGER: ClassVar[int] = 2
    PARAMETER_DOUBLE: ClassVar[int] = 3
    PARAMETER_STRING: ClassVar[int] = 4
    PARAMETER_BYTE_ARRAY: ClassVar[int] = 5
    PARAMETER_BOOL_ARRAY: ClassVar[int] = 6
    PARAMETER_INTEGER_ARRAY: ClassVar[int] = 7
    PARAMETER_DOUBLE_ARRAY: ClassVar[int] = 8
    PARAMETER_STRING_ARRAY: ClassVar[int] = 9


@dataclass(slots=True)
class ParameterValue(Message):
    type: int = 0
    bool_value: bool = False
    integer_value: int = 0
    double_value: float = 0.0
    string_value: str = ""
    byte_array_value: list[int] = field(default_factory=list)
    bool_array_value: list[bool] = field(default_factory=list)
    integer_array_value: list[int] = field(default_factory=list)
    double_array_value: list[float] = field(default_factory=list)
    string_array_value: list[str] = field(default_factory=list)
    __typename__ = "rcl_interfaces/msg/ParameterValue"
    __fields__ = (
        ("type", "uint8"),
        ("bool_value", "bool"),
        ("integer_value", "int64"),
        ("double_value", "float64"),
        ("string_value", "string"),
        ("byte_array_value", Seq("byte")),
        ("bool_array_value", Seq("bool")),
        ("integer_array_value", Seq("int64")),
        ("double_array_value", Seq("float64")),
        ("string_array_value", Seq("string")),
    )


@dataclass(slots=True)
class Parameter(Message):
    name: str = ""
    value: ParameterValue = field(default_factory=ParameterValue)
    __typename__ = "rcl_interfaces/msg/Parameter"
    __fields__ = (("name", "string"), ("value", ParameterValue))


@dataclass(slots=True)
class FloatingPointRange(Message):
    from_value: float = 0.0
    to_value: float = 0.0
    step: float = 0.0
    __typename__ = "rcl_interfaces/msg/FloatingPointRange"
    __fields__ = (("from_value", "float64"), ("to_value", "float64"), ("step", "float64"))


@dataclass(slots=True)
class IntegerRange(Message):
    from_value: int = 0
    to_value: int = 0
    step: int = 0
    __typename__ = "rcl_interfaces/msg/IntegerRange"
    __fields__ = (("from_value", "int64"), ("to_value", "int64"), ("step", "uint64"))


@dataclass(slots=True)
class ParameterDescriptor(Message):
    name: str = ""
    type: int = 0
    description: str = ""
    additional_constraints: str = ""
    read_only: bool = False
    dynamic_typing: bool = False
    floating_point_range: list[FloatingPointRange] = field(default_factory=list)
    integer_range: list[IntegerRange] = field(default_factory=list)
    __typename__ = "rcl_interfaces/msg/ParameterDescriptor"
    __fields__ = (
        ("name", "string"),
        ("type", "uint8"),
        ("description", "string"),
        ("additional_constraints", "string"),
        ("read_only", "bool"),
        ("dynamic_typing", "bool"),
        ("floating_point_range", Seq(FloatingPointRange, bound=1)),
        ("integer_range", Seq(IntegerRange, bound=1)),
    )


@dataclass(slots=True)
class SetParametersResult(Message):
    successful: bool = False
    reason: str = ""
    __typename__ = "rcl_interfaces/msg/SetParametersResult"
    __fields__ = (("successful", "bool"), ("reason", "string"))


@dataclass(slots=True)
class ListParametersResult(Message):
    names: list[str] = field(default_factory=list)
    prefixes: list[str] = field(default_factory=list)
    __typename__ = "rcl_interfaces/msg/ListParametersResult"
    __fields__ = (("names", Seq("string")), ("prefixes", Seq("string")))


@dataclass(slots=True)
class ParameterEvent(Message):
    """What changed on one node (``/parameter_events``)."""

    stamp: Time = field(default_factory=Time)
    node: str = ""
    new_parameters: list[Parameter] = field(default_factory=list)
    changed_parameters: list[Parameter] = field(default_factory=list)
    deleted_parameters: list[Parameter] = field(default_factory=list)
    __typename__ = "rcl_interfaces/msg/ParameterEvent"
    __fields__ = (
        ("stamp", Time),
        ("node", "string"),
        ("new_parameters", Seq(Parameter)),
        ("changed_parameters", Seq(Parameter)),
        ("deleted_parameters", Seq(Parameter)),
    )


# -- services ---------------------------------------------------------------------------------


@dataclass(slots=True)
class GetParameters_Request(Message):
    names: list[str] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/GetParameters_Request"
    __fields__ = (("names", Seq("string")),)


@dataclass(slots=True)
class GetParameters_Response(Message):
    values: list[ParameterValue] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/GetParameters_Response"
    __fields__ = (("values", Seq(ParameterValue)),)


class GetParameters(Service):
    __typename__ = "rcl_interfaces/srv/GetParameters"
    Request = GetParameters_Request
    Response = GetParameters_Response


@dataclass(slots=True)
class SetParameters_Request(Message):
    parameters: list[Parameter] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/SetParameters_Request"
    __fields__ = (("parameters", Seq(Parameter)),)


@dataclass(slots=True)
class SetParameters_Response(Message):
    results: list[SetParametersResult] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/SetParameters_Response"
    __fields__ = (("results", Seq(SetParametersResult)),)


class SetParameters(Service):
    __typename__ = "rcl_interfaces/srv/SetParameters"
    Request = SetParameters_Request
    Response = SetParameters_Response


@dataclass(slots=True)
class SetParametersAtomically_Request(Message):
    parameters: list[Parameter] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/SetParametersAtomically_Request"
    __fields__ = (("parameters", Seq(Parameter)),)


@dataclass(slots=True)
class SetParametersAtomically_Response(Message):
    result: SetParametersResult = field(default_factory=SetParametersResult)
    __typename__ = "rcl_interfaces/srv/SetParametersAtomically_Response"
    __fields__ = (("result", SetParametersResult),)


class SetParametersAtomically(Service):
    __typename__ = "rcl_interfaces/srv/SetParametersAtomically"
    Request = SetParametersAtomically_Request
    Response = SetParametersAtomically_Response


@dataclass(slots=True)
class ListParameters_Request(Message):
    DEPTH_RECURSIVE: ClassVar[int] = 0

    prefixes: list[str] = field(default_factory=list)
    depth: int = 0
    __typename__ = "rcl_interfaces/srv/ListParameters_Request"
    __fields__ = (("prefixes", Seq("string")), ("depth", "uint64"))


@dataclass(slots=True)
class ListParameters_Response(Message):
    result: ListParametersResult = field(default_factory=ListParametersResult)
    __typename__ = "rcl_interfaces/srv/ListParameters_Response"
    __fields__ = (("result", ListParametersResult),)


class ListParameters(Service):
    __typename__ = "rcl_interfaces/srv/ListParameters"
    Request = ListParameters_Request
    Response = ListParameters_Response


@dataclass(slots=True)
class DescribeParameters_Request(Message):
    names: list[str] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/DescribeParameters_Request"
    __fields__ = (("names", Seq("string")),)


@dataclass(slots=True)
class DescribeParameters_Response(Message):
    descriptors: list[ParameterDescriptor] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/DescribeParameters_Response"
    __fields__ = (("descriptors", Seq(ParameterDescriptor)),)


class DescribeParameters(Service):
    __typename__ = "rcl_interfaces/srv/DescribeParameters"
    Request = DescribeParameters_Request
    Response = DescribeParameters_Response


@dataclass(slots=True)
class GetParameterTypes_Request(Message):
    names: list[str] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/GetParameterTypes_Request"
    __fields__ = (("names", Seq("string")),)


@dataclass(slots=True)
class GetParameterTypes_Response(Message):
    types: list[int] = field(default_factory=list)
    __typename__ = "rcl_interfaces/srv/GetParameterTypes_Response"
    __fields__ = (("types", Seq("uint8")),)


class GetParameterTypes(Service):
    __typename__ = "rcl_interfaces/srv/GetParameterTypes"
    Request = GetParameterTypes_Request
    Response = GetParameterTypes_Response


@dataclass(slots=True)
class Log(Message):
    """``rcl_interfaces/msg/Log`` (/rosout): ``level`` DEBUG 10, INFO 20, WARN 30, ERROR 40,
    FATAL 50."""

    stamp: Time = field(default_factory=Time)
    level: int = 0
    name: str = ""
    msg: str = ""
    file: str = ""
    function: str = ""
    line: int = 0
    __typename__ = "rcl_interfaces/msg/Log"
    __fields__ = (
        ("stamp", Time),
        ("level", "uint8"),
        ("name", "string"),
        ("msg", "string"),
        ("file", "string"),
        ("function", "string"),
        ("line", "uint32"),
    )
