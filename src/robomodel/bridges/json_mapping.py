"""Messages as rosbridge's JSON: the mapping ``rosbridge_library.internal.message_conversion``
makes, both ways.

Fields by name in declaration order; ``uint8[]``/``byte[]``/``char[]`` (fixed or not) as one
base64 string; ``time``/``duration`` as ``{"secs", "nsecs"}`` on ROS 1 and ``{"sec",
"nanosec"}`` on ROS 2. Non-finite floats, which JSON cannot hold, go out as ``null`` (what
browsers' ``JSON.parse`` accepts). Coming in, a byte array may be base64 or a list of numbers,
fields left out keep their defaults, and ROS 1's ``secs``/``nsecs`` are taken on either bus.
"""

from __future__ import annotations

import base64
import binascii
import math
from typing import Any, Literal

from robomodel.bridges.exceptions import ClientError
from robomodel.runtime.msg import Message, message_from_dict
from robomodel.runtime.msg.schema import Array, MessageTypeError, Seq, Spec, is_byte_array

__all__ = ["Dialect", "message_from_json", "message_to_json"]

Dialect = Literal["ros1", "ros2"]
_TIME_TYPES = ("builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration")


def message_to_json(msg: Message, dialect: Dialect) -> dict[str, Any]:
    """``msg`` as the dict rosbridge sends (``json.dumps``-able)."""
    if dialect == "ros1" and msg.__typename__ in _TIME_TYPES:
        return {"secs": msg.sec, "nsecs": msg.nanosec}  # type: ignore[attr-defined]
    return {name: _plain(spec, getattr(msg, name), dialect) for name, spec in msg.__fields__}


def _plain(spec: Spec, value: Any, dialect: Dialect) -> Any:
    if isinstance(spec, str):
        if isinstance(value, float) and not math.isfinite(value):
            return None
        return value
    if is_byte_array(spec):
        return base64.b64encode(bytes(value)).decode("ascii")
    if isinstance(spec, Seq | Array):
        return [_plain(spec.item, item, dialect) for item in value]
    return message_to_json(value, dialect)


def message_from_json(cls: type[Message], data: Any, dialect: Dialect) -> Message:
    """A ``cls`` message from a client's JSON; :class:`ClientError` saying what does not fit."""
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise ClientError(f"a {cls.__typename__} must be a JSON object, got {data!r:.80}")
    try:
        fields = _native(cls, data)
        if dialect == "ros1":
            from robomodel.runtime.transport.ros1.ros1_yaml import from_ros1_fields

            fields = from_ros1_fields(cls, fields)
        return message_from_dict(cls, fields)
    except MessageTypeError as exc:
        raise ClientError(f"{cls.__typename__}: {exc}") from None


def _native(cls: type[Message], data: dict[str, Any]) -> dict[str, Any]:
    """``data`` with base64 byte arrays decoded and time fields named as robomodel's classes."""
    specs = dict(cls.__fields__)
    out: dict[str, Any] = {}
    for key, value in data.items():
        if cls.__typename__ in _TIME_TYPES and key in ("secs", "nsecs"):
            key = "sec" if key == "secs" else "nanosec"
        spec = specs.get(key)
        out[key] = value if spec is None else _native_value(spec, value, key)
    return out


def _native_value(spec: Spec, value: Any, where: str) -> Any:
    if is_byte_array(spec) and isinstance(value, str):
        try:
            return base64.b64decode(value, validate=True)
        except (binascii.Error, ValueError):
            raise ClientError(f"{where}: not base64 for a byte array: {value!r:.40}") from None
    if isinstance(spec, str) or value is None:
        return value
    if isinstance(spec, Seq | Array):
        if not isinstance(value, list):
            return value  # message_from_dict says what is wrong
        return [_native_value(spec.item, item, where) for item in value]
    return _native(spec, value) if isinstance(value, dict) else value
