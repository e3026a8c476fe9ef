"""geometry_msgs: vectors, quaternions, poses, transforms and twists."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Array, Message
from robomodel.runtime.msg.std_msgs import Header

__all__ = [
    "Point",
    "Pose",
    "PoseWithCovariance",
    "Quaternion",
    "Transform",
    "TransformStamped",
    "Twist",
    "TwistStamped",
    "TwistWithCovariance",
    "Vector3",
    "Wrench",
]


@dataclass(slots=True)
class Vector3(Message):
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    __typename__ = "geometry_msgs/msg/Vector3"
    __fields__ = (("x", "float64"), ("y", "float64"), ("z", "float64"))


@dataclass(slots=True)
class Point(Message):
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    __typename__ = "geometry_msgs/msg/Point"
    __fields__ = (("x", "float64"), ("y", "float64"), ("z", "float64"))


@dataclass(slots=True)
class Quaternion(Message):
    """A rotation quaternion in ROS order (x, y, z, w); the default is the identity."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    w: float = 1.0
    __typename__ = "geometry_msgs/msg/Quaternion"
    __fields__ = (("x", "float64"), ("y", "float64"), ("z", "float64"), ("w", "float64"))


@dataclass(slots=True)
class Pose(Message):
    position: Point = field(default_factory=Point)
    orientation: Quaternion = field(default_factory=Quaternion)
    __typename__ = "geometry_msgs/msg/Pose"
    __fields__ = (("position", Point), ("orientation", Quaternion))


@dataclass(slots=True)
class Transform(Message):
    translation: Vector3 = field(default_factory=Vector3)
    rotation: Quaternion = field(default_factory=Quaternion)
    __typename__ = "geometry_msgs/msg/Transform"
    __fields__ = (("translation", Vector3), ("rotation", Quaternion))


@dataclass(slots=True)
class TransformStamped(Message):
    """The pose of ``child_frame_id`` in ``header.frame_id``."""

    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    transform: Transform = field(default_factory=Transform)
    __typename__ = "geometry_msgs/msg/TransformStamped"
    __fields__ = (("header", Header), ("child_frame_id", "string"), ("transform", Transform))


@dataclass(slots=True)
class Twist(Message):
    """Linear [m/s] and angular [rad/s] velocity."""

    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)
    __typename__ = "geometry_msgs/msg/Twist"
    __fields__ = (("linear", Vector3), ("angular", Vector3))


@dataclass(slots=True)
class TwistStamped(Message):
    header: Header = field(default_factory=Header)
    twist: Twist = field(default_factory=Twist)
    __typename__ = "geometry_msgs/msg/TwistStamped"
    __fields__ = (("header", Header), ("twist", Twist))


@dataclass(slots=True)
class Wrench(Message):
    """Force [N] and torque [N m]."""

    force: Vector3 = field(default_factory=Vector3)
    torque: Vector3 = field(default_factory=Vector3)
    __typename__ = "geometry_msgs/msg/Wrench"
    __fields__ = (("force", Vector3), ("torque", Vector3))


@dataclass(slots=True)
class PoseWithCovariance(Message):
    pose: Pose = field(default_factory=Pose)
    covariance: list[float] = field(default_factory=lambda: [0.0] * 36)
    __typename__ = "geometry_msgs/msg/PoseWithCovariance"
    __fields__ = (("pose", Pose), ("covariance", Array("float64", 36)))


@dataclass(slots=True)
class TwistWithCovariance(Message):
    twist: Twist = field(default_factory=Twist)
    covariance: list[float] = field(default_factory=lambda: [0.0] * 36)
    __typename__ = "geometry_msgs/msg/TwistWithCovariance"
    __fields__ = (("twist", Twist), ("covariance", Array("float64", 36)))
