"""service_msgs: ServiceEventInfo, the header of every service's ``_Event`` message.

robomodel does not publish service events (introspection is off by default in ROS 2); the type
is here because every service's RIHS01 hash covers its event message.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from robomodel.runtime.msg._schema import Array, Message
from robomodel.runtime.msg.builtin_interfaces import Time

__all__ = ["ServiceEventInfo"]


@dataclass(slots=True)
class ServiceEventInfo(Message):
    """What happened (request sent/received, response sent/received), when and to whom."""

    REQUEST_SENT: ClassVar[int] = 0
    REQUEST_RECEIVED: ClassVar[int] = 1
    RESPONSE_SENT: ClassVar[int] = 2
    RESPONSE_RECEIVED: ClassVar[int] = 3

    event_type: int = 0
    stamp: Time = field(default_factory=Time)
    client_gid: list[int] = field(default_factory=lambda: [0] * 16)
    sequence_number: int = 0
    __typename__ = "service_msgs/msg/ServiceEventInfo"
    __fields__ = (
        ("event_type", "uint8"),
        ("stamp", Time),
        ("client_gid", Array("char", 16)),
        ("sequence_number", "int64"),
    )
