"""control_msgs (Jazzy) services and actions: QueryTrajectoryState and FollowJointTrajectory
(the joint_trajectory_controller's ``~/query_state`` and ``~/follow_joint_trajectory``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from robomodel.runtime.msg._schema import Message, Seq, Service
from robomodel.runtime.msg.action import make_action
from robomodel.runtime.msg.builtin_interfaces import Duration, Time
from robomodel.runtime.msg.std_msgs import Header
from robomodel.runtime.msg.trajectory_msgs import (
    JointTrajectory,
    JointTrajectoryPoint,
    MultiDOFJointTrajectory,
    MultiDOFJointTrajectoryPoint,
)

__all__ = [
    "FollowJointTrajectory",
    "FollowJointTrajectory_Feedback",
    "FollowJointTrajectory_Goal",
    "FollowJointTrajectory_Result",
    "JointComponentTolerance",
    "JointTolerance",
    "QueryTrajectoryState",
    "QueryTrajectoryState_Request",
    "QueryTrajectoryState_Response",
]


@dataclass(slots=True)
class JointTolerance(Message):
    """Per-joint tolerances [rad or m, /s, /s^2]; 0 is the default, negative is none."""

    name: str = ""
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0
    __typename__ = "control_msgs/msg/JointTolerance"
    __fields__ = (
        ("name", "string"),
        ("position", "float64"),
        ("velocity", "float64"),
        ("acceleration", "float64"),
    )


@dataclass(slots=True)
class JointComponentTolerance(Message):
    X_AXIS: ClassVar[int] = 1
    Y_AXIS: ClassVar[int] = 2
    Z_AXIS: ClassVar[int] = 3
    TRANSLATION: ClassVar[int] = 4
    ROTATION: ClassVar[int] = 5

    joint_name: str = ""
    component: int = 0
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0
    __typename__ = "control_msgs/msg/JointComponentTolerance"
    __fields__ = (
        ("joint_name", "string"),
        ("component", "uint16"),
        ("position", "float64"),
        ("velocity", "float64"),
        ("acceleration", "float64"),
    )


@dataclass(slots=True)
class QueryTrajectoryState_Request(Message):
    time: Time = field(default_factory=Time)
    __typename__ = "control_msgs/srv/QueryTrajectoryState_Request"
    __fields__ = (("time", Time),)


@dataclass(slots=True)
class QueryTrajectoryState_Response(Message):
    success: bool = False
    message: str = ""
    name: list[str] = field(default_factory=list)
    position: list[float] = field(default_factory=list)
    velocity: list[float] = field(default_factory=list)
    acceleration: list[float] = field(default_factory=list)
    __typename__ = "control_msgs/srv/QueryTrajectoryState_Response"
    __fields__ = (
        ("success", "bool"),
        ("message", "string"),
        ("name", Seq("string")),
        ("position", Seq("float64")),
        ("velocity", Seq("float64")),
        ("acceleration", Seq("float64")),
    )


class QueryTrajectoryState(Service):
    __typename__ = "control_msgs/srv/QueryTrajectoryState"
    Request = QueryTrajectoryState_Request
    Response = QueryTrajectoryState_Response


@dataclass(slots=True)
class FollowJointTrajectory_Goal(Message):
    trajectory: JointTrajectory = field(default_factory=JointTrajectory)
    multi_dof_trajectory: MultiDOFJointTrajectory = field(default_factory=MultiDOFJointTrajectory)
    path_tolerance: list[JointTolerance] = field(default_factory=list)
    component_path_tolerance: list[JointComponentTolerance] = field(default_factory=list)
    goal_tolerance: list[JointTolerance] = field(default_factory=list)
    component_goal_tolerance: list[JointComponentTolerance] = field(default_factory=list)
    goal_time_tolerance: Duration = field(default_factory=Duration)
    __typename__ = "control_msgs/action/FollowJointTrajectory_Goal"
    __fields__ = (
        ("trajectory", JointTrajectory),
        ("multi_dof_trajectory", MultiDOFJointTrajectory),
        ("path_tolerance", Seq(JointTolerance)),
        ("component_path_tolerance", Seq(JointComponentTolerance)),
        ("goal_tolerance", Seq(JointTolerance)),
        ("component_goal_tolerance", Seq(JointComponentTolerance)),
        ("goal_time_tolerance", Duration),
    )


@dataclass(slots=True)
class FollowJointTrajectory_Result(Message):
    SUCCESSFUL: ClassVar[int] = 0
    INVALID_GOAL: ClassVar[int] = -1
    INVALID_JOINTS: ClassVar[int] = -2
    OLD_HEADER_TIMESTAMP: ClassVar[int] = -3
    PATH_TOLERANCE_VIOLATED: ClassVar[int] = -4
    GOAL_TOLERANCE_VIOLATED: ClassVar[int] = -5

    error_code: int = 0
    error_string: str = ""
    __typename__ = "control_msgs/action/FollowJointTrajectory_Result"
    __fields__ = (("error_code", "int32"), ("error_string", "string"))


@dataclass(slots=True)
class FollowJointTrajectory_Feedback(Message):
    header: Header = field(default_factory=Header)
    joint_names: list[str] = field(default_factory=list)
    desired: JointTrajectoryPoint = field(default_factory=JointTrajectoryPoint)
    actual: JointTrajectoryPoint = field(default_factory=JointTrajectoryPoint)
    error: JointTrajectoryPoint = field(default_factory=JointTrajectoryPoint)
    multi_dof_joint_names: list[str] = field(default_factory=list)
    multi_dof_desired: MultiDOFJointTrajectoryPoint = field(
        default_factory=MultiDOFJointTrajectoryPoint
    )
    multi_dof_actual: MultiDOFJointTrajectoryPoint = field(
        default_factory=MultiDOFJointTrajectoryPoint
    )
    multi_dof_error: MultiDOFJointTrajectoryPoint = field(
        default_factory=MultiDOFJointTrajectoryPoint
    )
    __typename__ = "control_msgs/action/FollowJointTrajectory_Feedback"
    __fields__ = (
        ("header", Header),
        ("joint_names", Seq("string")),
        ("desired", JointTrajectoryPoint),
        ("actual", JointTrajectoryPoint),
        ("error", JointTrajectoryPoint),
        ("multi_dof_joint_names", Seq("string")),
        ("multi_dof_desired", MultiDOFJointTrajectoryPoint),
        ("multi_dof_actual", MultiDOFJointTrajectoryPoint),
        ("multi_dof_error", MultiDOFJointTrajectoryPoint),
    )


FollowJointTrajectory = make_action(
    "control_msgs/action/FollowJointTrajectory",
    FollowJointTrajectory_Goal,
    FollowJointTrajectory_Result,
    FollowJointTrajectory_Feedback,
)
