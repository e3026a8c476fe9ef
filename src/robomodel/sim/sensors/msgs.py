"""Messages the simulator publishes that the runtime does not define: sensor_msgs/Range and
gazebo_msgs/ContactsState (field names as the ROS definitions)."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq
from robomodel.runtime.msg.geometry_msgs import Vector3
from robomodel.runtime.msg.std_msgs import Header

__all__ = ["ContactState", "ContactsState", "Range"]


@dataclass(slots=True)
class Range(Message):
    """One range reading [m] of a sonar/IR sensor with a field of view [rad]."""

    header: Header = field(default_factory=Header)
    radiation_type: int = 0  # ULTRASOUND
    field_of_view: float = 0.0
    min_range: float = 0.0
    max_range: float = 0.0
    range: float = 0.0
    __typename__ = "sensor_msgs/msg/Range"
    __fields__ = (
        ("header", Header),
        ("radiation_type", "uint8"),
        ("field_of_view", "float32"),
        ("min_range", "float32"),
        ("max_range", "float32"),
        ("range", "float32"),
    )


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
