"""``rclpy.parameter.Parameter``: a named, typed parameter value (rcl_interfaces' types)."""

from __future__ import annotations

import array
import enum
from typing import Any

from robomodel.clientlibs.rclpy._support import interface

__all__ = ["Parameter", "parameter_dict_from_yaml_file", "parameter_value_to_python"]


class _Type(enum.IntEnum):
    """rcl_interfaces/ParameterType's values."""

    NOT_SET = 0
    BOOL = 1
    INTEGER = 2
    DOUBLE = 3
    STRING = 4
    BYTE_ARRAY = 5
    BOOL_ARRAY = 6
    INTEGER_ARRAY = 7
    DOUBLE_ARRAY = 8
    STRING_ARRAY = 9

    @classmethod
    def from_parameter_value(cls, value: Any) -> _Type:
        """The type of a Python value, as rclpy infers it (a list's first element decides)."""
        if value is None:
            return cls.NOT_SET
        if isinstance(value, bool):
            return cls.BOOL
        if isinstance(value, int):
            return cls.INTEGER
        if isinstance(value, float):
            return cls.DOUBLE
        if isinstance(value, str):
            return cls.STRING
        if isinstance(value, (bytes, bytearray)):
            return cls.BYTE_ARRAY
        if isinstance(value, (list, tuple, array.array)) or hasattr(value, "tolist"):
            items = list(value.tolist() if hasattr(value, "tolist") else value)
            if all(isinstance(v, bytes) for v in items) and items:
                return cls.BYTE_ARRAY
            if all(isinstance(v, bool) for v in items):
                return cls.BOOL_ARRAY
            if all(isinstance(v, int) and not isinstance(v, bool) for v in items):
                return cls.INTEGER_ARRAY
            if all(isinstance(v, float) for v in items):
                return cls.DOUBLE_ARRAY
            if all(isinstance(v, str) for v in items):
                return cls.STRING_ARRAY
            raise TypeError(f"The given value is not a list of one of the allowed types '{value}'.")
        raise TypeError(f"The given value is not one of the allowed types '{value}'.")

    def check(self, value: Any) -> bool:
        if self == _Type.NOT_SET:
            return value is None
        try:
            return _Type.from_parameter_value(value) == self or (
                self in _ARRAYS and isinstance(value, (list, tuple)) and not value
            )
        except TypeError:
            return False


_ARRAYS = {_Type.BYTE_ARRAY, _Type.BOOL_ARRAY, _Type.INTEGER_ARRAY, _Type.DOUBLE_ARRAY,
           _Type.STRING_ARRAY}  # fmt: skip
_VALUE_FIELDS = {
    _Type.BOOL: "bool_value", _Type.INTEGER: "integer_value", _Type.DOUBLE: "double_value",
    _Type.STRING: "string_value", _Type.BYTE_ARRAY: "byte_array_value",
    _Type.BOOL_ARRAY: "bool_array_value", _Type.INTEGER_ARRAY: "integer_array_value",
    _Type.DOUBLE_ARRAY: "double_array_value", _Type.STRING_ARRAY: "string_array_value",
}  # fmt: skip


class Parameter:
    """``Parameter(name, Parameter.Type.DOUBLE, 1.5)`` or ``Parameter(name, value=1.5)``."""

    Type = _Type

    def __init__(self, name: str, type_: Any = None, value: Any = None) -> None:
        if type_ is None:
            type_ = _Type.from_parameter_value(value)
        elif not isinstance(type_, _Type):
            if isinstance(type_, int):
                type_ = _Type(type_)
            else:  # rclpy also takes the value in the type's place
                value, type_ = type_, _Type.from_parameter_value(type_)
        if not type_.check(value):
            raise ValueError(f"Type {type_!r} and value {value!r} do not agree")
        self._name = name
        self._type: _Type = type_
        self._value = _plain(value)

    @property
    def name(self) -> str:
        return self._name

    @property
    def type_(self) -> _Type:
        return self._type

    @property
    def value(self) -> Any:
        return self._value

    def __repr__(self) -> str:
        return f"Parameter(name={self._name!r}, type_={self._type!r}, value={self._value!r})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Parameter):
            return NotImplemented
        return (self._name, self._type, self._value) == (other._name, other._type, other._value)

    def __hash__(self) -> int:
        return hash((self._name, self._type))

    def get_parameter_value(self) -> Any:
        """The value as ``rcl_interfaces/ParameterValue``."""
        message = interface("rcl_interfaces.msg", "ParameterValue")()
        message.type = int(self._type)
        field = _VALUE_FIELDS.get(self._type)
        if field is not None:
            setattr(message, field, self._value)
        return message

    def to_parameter_msg(self) -> Any:
        """The parameter as ``rcl_interfaces/Parameter``."""
        cls = interface("rcl_interfaces.msg", "Parameter")
        return cls(name=self._name, value=self.get_parameter_value())

    @classmethod
    def from_parameter_msg(cls, param_msg: Any) -> Parameter:
        return cls(param_msg.name, _Type(param_msg.value.type),
                   parameter_value_to_python(param_msg.value))  # fmt: skip


def _plain(value: Any) -> Any:
    if isinstance(value, (tuple, array.array)) or hasattr(value, "tolist"):
        return list(value.tolist() if hasattr(value, "tolist") else value)
    return value


def parameter_value_to_python(parameter_value: Any) -> Any:
    """The Python value of an ``rcl_interfaces/ParameterValue``."""
    kind = _Type(parameter_value.type)
    if kind == _Type.NOT_SET:
        return None
    return _plain(getattr(parameter_value, _VALUE_FIELDS[kind]))


def parameter_dict_from_yaml_file(
    parameter_file: str,
    use_wildcard: bool = False,
    target_nodes: list[str] | None = None,
    namespace: str = "",
) -> dict[str, Any]:
    """The parameters of a ROS 2 parameter file as ``rcl_interfaces/Parameter`` messages by
    name, as rclpy reads them: the sections of ``target_nodes`` (every section but ``/**``
    when none are named; ``/**`` first with ``use_wildcard``), nested names dotted, each
    prefixed with ``namespace``.

    Raises:
        RuntimeError: a target node has no section, or a section has no ``ros__parameters``
            (rclpy's errors); FileNotFoundError for a file that is not there.
    """
    from robomodel._yaml_bounded import load_yaml_file
    from robomodel.runtime.param_files import flatten

    with open(parameter_file, encoding="utf-8") as stream:
        data = load_yaml_file(stream.read(), where=str(parameter_file))
    if not isinstance(data, dict):
        raise RuntimeError(f"{parameter_file}: a parameter file is a mapping of node names")
    keys: list[str] = ["/**"] if use_wildcard and "/**" in data else []
    if target_nodes:
        for name in target_nodes:
            if name not in data:
                raise RuntimeError(
                    f"Param file does not contain parameters for {name}, "
                    f"only for nodes: {list(data)}"
                )
            keys.append(name)
    else:
        keys.extend(key for key in data if key != "/**")
    if not keys:
        raise RuntimeError("Param file does not contain selected parameters")
    values: dict[str, Any] = {}
    for key in keys:
        section = data[key]
        if not isinstance(section, dict) or "ros__parameters" not in section:
            raise RuntimeError(f"YAML file is not a valid ROS parameter file for node {key}")
        values.update(flatten(section["ros__parameters"], namespace))
    return {name: Parameter(name, value=value).to_parameter_msg() for name, value in values.items()}
