"""``roslib.message``: message and service classes by name, of rospy's (genpy's) flavour,
and genpy's names that roslib re-exports (``roslib.message.Message``: ROS 1's
``sensor_msgs.point_cloud2`` checks its clouds against it)."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.genpy import (
    DeserializationError,
    Duration,
    Message,
    SerializationError,
    Time,
    TVal,
)

__all__ = [
    "DeserializationError",
    "Duration",
    "Message",
    "SerializationError",
    "TVal",
    "Time",
    "get_message_class",
    "get_service_class",
]


def get_message_class(message_type: str, reload_on_error: bool = False) -> Any:
    """The class of ``pkg/Name`` (genpy-flavoured), or None if robomodel has no such type."""
    from robomodel.clientlibs.messages import message_class
    from robomodel.runtime.msg.schema import MessageTypeError

    try:
        return message_class(message_type, "genpy")
    except MessageTypeError:
        return None


def get_service_class(service_type: str, reload_on_error: bool = False) -> Any:
    """The class of service ``pkg/Name`` (genpy-flavoured), or None if unknown."""
    from robomodel.clientlibs.messages import service_class
    from robomodel.runtime.msg.schema import MessageTypeError

    try:
        return service_class(service_type, "genpy")
    except MessageTypeError:
        return None
