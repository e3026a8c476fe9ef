"""sensor_msgs: JointState, LaserScan, Imu."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Array, Message, Seq
from robomodel.runtime.msg.geometry_msgs import Quaternion, Vector3
from robomodel.runtime.msg.std_msgs import Header

__all__ = ["Imu", "JointState", "LaserScan"]


@dataclass(slots=True)
class JointState(Message):
    """Joint positions [rad or m], velocities and efforts, by name (any may be empty)."""

    header: Header = field(default_factory=Header)
    name: list[str] = field(default_factory=list)
    position: list[float] = field(default_factory=list)
    velocity: list[float] = field(default_factory=list)
    effort: list[float] = field(default_factory=list)
    __typename__ = "sensor_msgs/msg/JointState"
    __fields__ = (
        ("header", Header),
        ("name", Seq("string")),
        ("position", Seq("float64")),
        ("velocity", Seq("float64")),
        ("effort", Seq("float64")),
    )


@dataclass(slots=True)
class LaserScan(Message):
    """A planar range scan; angles [rad], times [s], ranges [m]."""

    header: Header = field(default_factory=Header)
    angle_min: float = 0.0
    angle_max: float = 0.0
    angle_increment: float = 0.0
    time_increment: float = 0.0
    scan_time: float = 0.0
    range_min: float = 0.0
    range_max: float = 0.0
    ranges: list[float] = field(default_factory=list)
    intensities: list[float] = field(default_factory=list)
    __typename__ = "sensor_msgs/msg/LaserScan"
    __fields__ = (
        ("header", Header),
        ("angle_min", "float32"),
        ("angle_max", "float32"),
        ("angle_increment", "float32"),
        ("time_increment", "float32"),
        ("scan_time", "float32"),
        ("range_min", "float32"),
        ("range_max", "float32"),
        ("ranges", Seq("float32")),
        ("intensities", Seq("float32")),
    )


@dataclass(slots=True)
class Imu(Message):
    header: Header = field(default_factory=Header)
    orientation: Quaternion = field(default_factory=Quaternion)
    orientation_covariance: list[float] = field(default_factory=lambda: [0.0] * 9)
    angular_velocity: Vector3 = field(default_factory=Vector3)
    angular_velocity_covariance: list[float] = field(default_factory=lambda: [0.0] * 9)
    linear_acceleration: Vector3 = field(default_factory=Vector3)
    linear_acceleration_covariance: list[float] = field(default_factory=lambda: [0.0] * 9)
    __typename__ = "sensor_msgs/msg/Imu"
    __fields__ = (
        ("header", Header),
        ("orientation", Quaternion),
        ("orientation_covariance", Array("float64", 9)),
        ("angular_velocity", Vector3),
        ("angular_velocity_covariance", Array("float64", 9)),
        ("linear_acceleration", Vector3),
        ("linear_acceleration_covariance", Array("float64", 9)),
    )
