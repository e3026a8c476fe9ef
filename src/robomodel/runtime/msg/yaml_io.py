"""Conversion between messages and dicts/YAML, in the syntax of ``ros2 topic pub`` / ``echo``.

``message_from_yaml(Twist, "{linear: {x: 0.2}, angular: {z: 0.5}}")`` fills the named fields
and leaves the rest at their defaults, as rosidl_runtime_py's ``set_message_fields`` does.
``message_to_yaml`` renders what ``ros2 topic echo`` prints for one message (block style).
"""

from __future__ import annotations

import functools
import math
import sys
from typing import TYPE_CHECKING, Any, TypeVar

from robomodel._yaml_bounded import load_yaml
from robomodel.errors import close_matches
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    MessageTypeError,
    Seq,
    Spec,
    is_byte_array,
)

__all__ = ["message_from_dict", "message_from_yaml", "message_to_dict", "message_to_yaml"]

if TYPE_CHECKING:
    import yaml

_M = TypeVar("_M", bound=Message)
_INT_RANGES = {
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "byte": (0, 2**8 - 1),
    "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}


def _spec_name(spec: Spec) -> str:
    if isinstance(spec, str):
        return spec
    if isinstance(spec, Seq):
        return f"{_spec_name(spec.item)}[]"
    if isinstance(spec, Array):
        return f"{_spec_name(spec.item)}[{spec.size}]"
    return spec.__typename__


def _at(where: str) -> str:
    """The field path as a message prefix; nothing for the message itself."""
    return f"{where}: " if where else ""


def _convert(spec: Spec, value: Any, where: str) -> Any:
    if isinstance(spec, str):
        return _primitive(spec, value, where)
    if isinstance(spec, (Seq, Array)):
        if is_byte_array(spec) and isinstance(value, (bytes, bytearray)):
            value = list(value)
        if not isinstance(value, (list, tuple)):
            raise MessageTypeError(
                f"{_at(where)}expected a list ({_spec_name(spec)}), got {value!r}"
            )
        if isinstance(spec, Array) and len(value) != spec.size:
            raise MessageTypeError(f"{_at(where)}expected {spec.size} values, got {len(value)}")
        items = [_convert(spec.item, v, f"{where}[{i}]") for i, v in enumerate(value)]
        return bytes(items) if is_byte_array(spec) else items  # as the codecs decode them
    if isinstance(value, spec):
        return value
    if not isinstance(value, dict):
        raise MessageTypeError(
            f"{_at(where)}expected a mapping for {spec.__typename__}, got {value!r}"
        )
    return _fill(spec, value, where)


def _primitive(name: str, value: Any, where: str) -> Any:
    name, _, bound = name.partition("<=")  # string<=N: at most N characters
    if name == "string":
        if not isinstance(value, str):
            raise MessageTypeError(f"{_at(where)}expected a string, got {value!r}")
        if bound and len(value) > int(bound):
            raise MessageTypeError(f"{_at(where)}longer than {bound} characters: {value!r}")
        return value
    if name == "bool":
        if not isinstance(value, bool):
            raise MessageTypeError(f"{_at(where)}expected true or false, got {value!r}")
        return value
    if name in ("float32", "float64"):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise MessageTypeError(f"{_at(where)}expected a number ({name}), got {value!r}")
        return float(value)
    if isinstance(value, bool) or not isinstance(value, int):
        raise MessageTypeError(f"{_at(where)}expected an integer ({name}), got {value!r}")
    low, high = _INT_RANGES[name]
    if not low <= value <= high:
        raise MessageTypeError(f"{_at(where)}{value} is out of range for {name} [{low}, {high}]")
    return value


def _fill(cls: type[_M], data: dict[str, Any], where: str) -> _M:
    specs = dict(cls.__fields__)
    values: dict[str, Any] = {}
    for key, value in data.items():
        if key not in specs:
            fields = ", ".join(f"{n} ({_spec_name(s)})" for n, s in cls.__fields__) or "(none)"
            hint = close_matches(str(key), tuple(specs))
            mean = f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else ""
            raise MessageTypeError(
                f"{_at(where)}{cls.__typename__} has no field '{key}'{mean}; "
                f"its fields are: {fields}"
            )
        values[key] = _convert(specs[key], value, f"{where}.{key}" if where else key)
    return cls(**values)


def message_from_dict(cls: type[_M], data: dict[str, Any] | None) -> _M:
    """Build a ``cls`` message from a (possibly partial) dict; MessageTypeError if it does not fit."""
    if data is None:
        return cls()
    if not isinstance(data, dict):
        raise MessageTypeError(
            f"{cls.__typename__} needs a mapping such as 'field: value', got {data!r}"
        )
    return _fill(cls, data, "")


def message_from_yaml(cls: type[_M], text: str) -> _M:
    """Parse ``ros2 topic pub``-style YAML (``"data: 1.5"``, ``"{linear: {x: 0.2}}"``)."""
    import yaml  # here, not at import: the bus verbs that never read YAML skip its 20 ms

    try:
        data = load_yaml(text, what="the message") if text.strip() else None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise MessageTypeError(f"invalid YAML{where}: {getattr(exc, 'problem', exc)}") from None
    return message_from_dict(cls, data)


_PLAIN = frozenset({int, float, str, bool})


def message_to_dict(msg: Message) -> dict[str, Any]:
    """The message as nested dicts and lists (field order kept)."""
    out: dict[str, Any] = {}
    for name, spec in msg.__fields__:
        out[name] = _to_plain(spec, getattr(msg, name))
    return out


def _to_plain(spec: Spec, value: Any) -> Any:
    if isinstance(spec, str):
        if value.__class__ in _PLAIN:
            return value
        if spec == "byte" and value.__class__ is bytes:  # rclpy's octet: bytes of length 1
            return value[0]
        return value.item() if hasattr(value, "item") else value  # a numpy array's number
    if isinstance(spec, (Seq, Array)):
        return [_to_plain(spec.item, v) for v in value]
    return message_to_dict(value)


@functools.cache
def _echo_dumper() -> type[yaml.SafeDumper]:
    """PyYAML's dumper with insertion-ordered mappings, as rosidl_runtime_py registers, and
    NaN written ``.nan`` (made on first use: PyYAML is imported only by what prints YAML)."""
    import yaml

    class EchoDumper(yaml.SafeDumper):
        pass

    def represent_float(dumper: yaml.SafeDumper, value: float) -> yaml.ScalarNode:
        if math.isnan(value):
            return dumper.represent_scalar("tag:yaml.org,2002:float", ".nan")
        return dumper.represent_float(value)

    EchoDumper.add_representer(float, represent_float)
    return EchoDumper


def message_to_yaml(msg: Message) -> str:
    """What ``ros2 topic echo`` prints for one message (without the ``---`` separator)."""
    import yaml

    return yaml.dump(
        message_to_dict(msg),
        Dumper=_echo_dumper(),
        sort_keys=False,
        default_flow_style=False,
        allow_unicode=True,
        width=sys.maxsize,
    )
