"""nav_msgs: Odometry; tf2_msgs: TFMessage; rosgraph_msgs: Clock and (ROS 1) Log."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq
from robomodel.runtime.msg.builtin_interfaces import Time
from robomodel.runtime.msg.geometry_msgs import (
    PoseWithCovariance,
    TransformStamped,
    TwistWithCovariance,
)
from robomodel.runtime.msg.std_msgs import Header

__all__ = ["Clock", "Odometry", "RosgraphLog", "TFMessage"]


@dataclass(slots=True)
class Odometry(Message):
    """Pose in ``header.frame_id`` and twist in ``child_frame_id``."""

    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)
    twist: TwistWithCovariance = field(default_factory=TwistWithCovariance)
    __typename__ = "nav_msgs/msg/Odometry"
    __fields__ = (
        ("header", Header),
        ("child_frame_id", "string"),
        ("pose", PoseWithCovariance),
        ("twist", TwistWithCovariance),
    )


@dataclass(slots=True)
class TFMessage(Message):
    transforms: list[TransformStamped] = field(default_factory=list)
    __typename__ = "tf2_msgs/msg/TFMessage"
    __fields__ = (("transforms", Seq(TransformStamped)),)


@dataclass(slots=True)
class Clock(Message):
    clock: Time = field(default_factory=Time)
    __typename__ = "rosgraph_msgs/msg/Clock"
    __fields__ = (("clock", Time),)


@dataclass(slots=True)
class RosgraphLog(Message):
    """ROS 1's ``rosgraph_msgs/Log`` (/rosout); ROS 2's is ``rcl_interfaces/msg/Log``.

    ``level`` is one of DEBUG 1, INFO 2, WARN 4, ERROR 8, FATAL 16; ``topics`` the node's
    advertised topics (roscpp fills them).
    """

    header: Header = field(default_factory=Header)
    level: int = 0
    name: str = ""
    msg: str = ""
    file: str = ""
    function: str = ""
    line: int = 0
    topics: list[str] = field(default_factory=list)
    __typename__ = "rosgraph_msgs/msg/Log"
    __fields__ = (
        ("header", Header),
        ("level", "int8"),
        ("name", "string"),
        ("msg", "string"),
        ("file", "string"),
        ("function", "string"),
        ("line", "uint32"),
        ("topics", Seq("string")),
    )
