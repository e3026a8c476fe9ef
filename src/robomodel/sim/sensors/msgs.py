"""Messages the simulator publishes that the runtime does not define: gazebo_msgs/ContactsState
(field names as the ROS definition). sensor_msgs/Range is built from its definition for the
chosen distribution (Jazzy's has a ``variance`` that Humble's lacks): :func:`range_type`."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg.schema import Message, Seq
from robomodel.runtime.msg.types.geometry_msgs import Vector3
from robomodel.runtime.msg.types.std_msgs import Header

__all__ = ["ContactState", "ContactsState", "range_type"]


@dataclass(slots=True)
class ContactState(Message):
    """One touching pair (gazebo_msgs/ContactState, reduced to the fields we fill)."""

    info: str = ""
    collision1_name: str = ""
    collision2_name: str = ""
    total_wrench_force: Vector3 = field(default_factory=Vector3)
    depths: list[float] = field(default_factory=list)
    __typename__ = "gazebo_msgs/msg/ContactState"
    __fields__ = (
        ("info", "string"),
        ("collision1_name", "string"),
        ("collision2_name", "string"),
        ("total_wrench_force", Vector3),
        ("depths", Seq("float64")),
    )


@dataclass(slots=True)
class ContactsState(Message):
    """What a bumper sensor publishes: the contacts of its link."""

    header: Header = field(default_factory=Header)
    states: list[ContactState] = field(default_factory=list)
    __typename__ = "gazebo_msgs/msg/ContactsState"
    __fields__ = (("header", Header), ("states", Seq(ContactState)))


def range_type() -> type[Message]:
    """``sensor_msgs/msg/Range`` of the distribution in use (``ROS_DISTRO``, default Jazzy)."""
    from robomodel.runtime.msg.schema import get_message_type

    return get_message_type("sensor_msgs/msg/Range")
