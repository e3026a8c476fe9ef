"""Parameter values as they travel: rcl_interfaces ``ParameterValue`` to and from Python."""

from __future__ import annotations

from typing import Any

from robomodel.runtime.msg.types.rcl_interfaces import ParameterType, ParameterValue
from robomodel.runtime.params import ParameterError, parameter_type_name

__all__ = ["TYPE_NAMES", "from_parameter_value", "to_parameter_value", "type_code"]

_T = ParameterType
TYPE_NAMES = {
    _T.PARAMETER_NOT_SET: "not set",
    _T.PARAMETER_BOOL: "bool",
    _T.PARAMETER_INTEGER: "integer",
    _T.PARAMETER_DOUBLE: "double",
    _T.PARAMETER_STRING: "string",
    _T.PARAMETER_BYTE_ARRAY: "byte_array",
    _T.PARAMETER_BOOL_ARRAY: "bool_array",
    _T.PARAMETER_INTEGER_ARRAY: "integer_array",
    _T.PARAMETER_DOUBLE_ARRAY: "double_array",
    _T.PARAMETER_STRING_ARRAY: "string_array",
}
_CODES = {name: code for code, name in TYPE_NAMES.items()}
# An empty list has no element to tell its type by; ROS 2 YAML files give [] as a string array.
_CODES["array"] = _T.PARAMETER_STRING_ARRAY


def type_code(value: Any) -> int:
    """The ``ParameterType`` constant of a Python parameter value."""
    if isinstance(value, bytes | bytearray):
        return _T.PARAMETER_BYTE_ARRAY
    return _CODES[parameter_type_name(value)]


def to_parameter_value(value: Any) -> ParameterValue:
    """A Python value (bool, int, float, str, bytes or a list of one of them) as a message."""
    code = type_code(value)
    msg = ParameterValue(type=code)
    if code == _T.PARAMETER_BOOL:
        msg.bool_value = bool(value)
    elif code == _T.PARAMETER_INTEGER:
        msg.integer_value = int(value)
    elif code == _T.PARAMETER_DOUBLE:
        msg.double_value = float(value)
    elif code == _T.PARAMETER_STRING:
        msg.string_value = str(value)
    elif code == _T.PARAMETER_BYTE_ARRAY:
        msg.byte_array_value = bytes(value)
    elif code == _T.PARAMETER_BOOL_ARRAY:
        msg.bool_array_value = [bool(v) for v in value]
    elif code == _T.PARAMETER_INTEGER_ARRAY:
        msg.integer_array_value = [int(v) for v in value]
    elif code == _T.PARAMETER_DOUBLE_ARRAY:
        msg.double_array_value = [float(v) for v in value]
    else:
        msg.string_array_value = [str(v) for v in value]
    return msg


def from_parameter_value(msg: ParameterValue) -> Any:
    """The Python value of a message; ParameterError for NOT_SET or an unknown type."""
    fields = {
        _T.PARAMETER_BOOL: "bool_value",
        _T.PARAMETER_INTEGER: "integer_value",
        _T.PARAMETER_DOUBLE: "double_value",
        _T.PARAMETER_STRING: "string_value",
        _T.PARAMETER_BYTE_ARRAY: "byte_array_value",
        _T.PARAMETER_BOOL_ARRAY: "bool_array_value",
        _T.PARAMETER_INTEGER_ARRAY: "integer_array_value",
        _T.PARAMETER_DOUBLE_ARRAY: "double_array_value",
        _T.PARAMETER_STRING_ARRAY: "string_array_value",
    }
    name = fields.get(msg.type)
    if name is None:
        raise ParameterError(
            "parameter is not set"
            if msg.type == _T.PARAMETER_NOT_SET
            else f"unknown parameter type {msg.type}"
        )
    value = getattr(msg, name)
    if msg.type == _T.PARAMETER_BYTE_ARRAY:
        return bytes(value)
    return list(value) if isinstance(value, list) else value
