"""A request or message typed with ROS 1's field names, as ``rosservice call`` and ``rostopic
pub`` take it, turned into robomodel's (ROS 2) field names before it is built.

ROS 1's ``time``/``duration`` have ``secs``/``nsecs`` where builtin_interfaces has
``sec``/``nanosec``; the fields :mod:`ros1_fields` maps (controller_manager_msgs'
``start_controllers``, ``timeout`` in seconds, ...) are renamed and converted as the ROS 1
codec decodes them. ROS 2 names pass unchanged, so either spelling works.
"""

from __future__ import annotations

from typing import Any

from robomodel.runtime.msg.schema import Array, Message, Seq, Spec
from robomodel.runtime.transport.ros1.ros1_fields import special_field

__all__ = ["from_ros1_fields"]

_TIME_FIELDS = {"secs": "sec", "nsecs": "nanosec"}
_TIME_TYPES = ("builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration")


def _ros1_typename(cls: type[Message]) -> str:
    """``pkg/srv/Name_Request`` -> ``pkg/msg/NameRequest`` (ros1_fields' keys); messages as is."""
    package, kind, name = cls.__typename__.split("/")
    if kind == "srv":
        return f"{package}/msg/{name.replace('_', '')}"
    return cls.__typename__


def _value(spec: Spec, value: Any) -> Any:
    if isinstance(spec, str):
        return value
    if isinstance(spec, Seq | Array):
        if not isinstance(value, list):
            return value  # message_from_dict says what is wrong
        return [_value(spec.item, item) for item in value]
    return from_ros1_fields(spec, value) if isinstance(value, dict) else value


def from_ros1_fields(cls: type[Message], data: Any) -> Any:
    """``data`` (a dict for a ``cls`` message) with ROS 1 field names turned into ``cls``'s."""
    if not isinstance(data, dict):
        return data
    specs = dict(cls.__fields__)
    ros1_name = _ros1_typename(cls)
    out: dict[str, Any] = {}
    for key, value in data.items():
        name, converted = key, value
        field = special_field(ros1_name, str(key))
        # a ROS 1 name, or a shared name holding a ROS 1 value (a timeout as seconds)
        if field is not None and (key not in specs or not isinstance(value, dict)):
            name, converted = field.name, _converted(field.from_ros1, value)
        elif key not in specs and cls.__typename__ in _TIME_TYPES and key in _TIME_FIELDS:
            name = _TIME_FIELDS[key]
        out[name] = _value(specs[name], converted) if name in specs else converted
    return out


def _converted(from_ros1: Any, value: Any) -> Any:
    if from_ros1 is None:
        return value
    try:
        return from_ros1(value)
    except (TypeError, ValueError, AttributeError):
        return value  # not a ROS 1 value after all: message_from_dict says what is wrong
