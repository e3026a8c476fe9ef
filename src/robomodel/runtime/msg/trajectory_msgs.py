"""trajectory_msgs: JointTrajectory, JointTrajectoryPoint and their multi-DOF counterparts."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq
from robomodel.runtime.msg.builtin_interfaces import Duration
from robomodel.runtime.msg.geometry_msgs import Transform, Twist
from robomodel.runtime.msg.std_msgs import Header

__all__ = [
    "JointTrajectory",
    "JointTrajectoryPoint",
    "MultiDOFJointTrajectory",
    "MultiDOFJointTrajectoryPoint",
]


@dataclass(slots=True)
class JointTrajectoryPoint(Message):
    """One waypoint; any of the arrays may be empty."""

    positions: list[float] = field(default_factory=list)
    velocities: list[float] = field(default_factory=list)
    accelerations: list[float] = field(default_factory=list)
    effort: list[float] = field(default_factory=list)
    time_from_start: Duration = field(default_factory=Duration)
    __typename__ = "trajectory_msgs/msg/JointTrajectoryPoint"
    __fields__ = (
        ("positions", Seq("float64")),
        ("velocities", Seq("float64")),
        ("accelerations", Seq("float64")),
        ("effort", Seq("float64")),
        ("time_from_start", Duration),
    )


@dataclass(slots=True)
class JointTrajectory(Message):
    """Waypoints for ``joint_names``; a zero ``header.stamp`` means "start on reception"."""

    header: Header = field(default_factory=Header)
    joint_names: list[str] = field(default_factory=list)
    points: list[JointTrajectoryPoint] = field(default_factory=list)
    __typename__ = "trajectory_msgs/msg/JointTrajectory"
    __fields__ = (
        ("header", Header),
        ("joint_names", Seq("string")),
        ("points", Seq(JointTrajectoryPoint)),
    )


@dataclass(slots=True)
class MultiDOFJointTrajectoryPoint(Message):
    """A waypoint of multi-DOF joints (floating, planar): poses and twists."""

    transforms: list[Transform] = field(default_factory=list)
    velocities: list[Twist] = field(default_factory=list)
    accelerations: list[Twist] = field(default_factory=list)
    time_from_start: Duration = field(default_factory=Duration)
    __typename__ = "trajectory_msgs/msg/MultiDOFJointTrajectoryPoint"
    __fields__ = (
        ("transforms", Seq(Transform)),
        ("velocities", Seq(Twist)),
        ("accelerations", Seq(Twist)),
        ("time_from_start", Duration),
    )


@dataclass(slots=True)
class MultiDOFJointTrajectory(Message):
    """Waypoints of multi-DOF joints (FollowJointTrajectory's ``multi_dof_trajectory``)."""

    header: Header = field(default_factory=Header)
    joint_names: list[str] = field(default_factory=list)
    points: list[MultiDOFJointTrajectoryPoint] = field(default_factory=list)
    __typename__ = "trajectory_msgs/msg/MultiDOFJointTrajectory"
    __fields__ = (
        ("header", Header),
        ("joint_names", Seq("string")),
        ("points", Seq(MultiDOFJointTrajectoryPoint)),
    )
