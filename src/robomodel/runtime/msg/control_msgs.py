"""control_msgs (Humble): DynamicJointState, InterfaceValue, JointControllerState and
JointTrajectoryControllerState."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq
from robomodel.runtime.msg.std_msgs import Header
from robomodel.runtime.msg.trajectory_msgs import (
    JointTrajectoryPoint,
    MultiDOFJointTrajectoryPoint,
)

__all__ = [
    "DynamicJointState",
    "InterfaceValue",
    "JointControllerState",
    "JointTrajectoryControllerState",
]


@dataclass(slots=True)
class InterfaceValue(Message):
    interface_names: list[str] = field(default_factory=list)
    values: list[float] = field(default_factory=list)
    __typename__ = "control_msgs/msg/InterfaceValue"
    __fields__ = (("interface_names", Seq("string")), ("values", Seq("float64")))


@dataclass(slots=True)
class DynamicJointState(Message):
    """Every state interface of every joint or sensor (joint_state_broadcaster, Humble)."""

    header: Header = field(default_factory=Header)
    joint_names: list[str] = field(default_factory=list)
    interface_values: list[InterfaceValue] = field(default_factory=list)
    __typename__ = "control_msgs/msg/DynamicJointState"
    __fields__ = (
        ("header", Header),
        ("joint_names", Seq("string")),
        ("interface_values", Seq(InterfaceValue)),
    )


@dataclass(slots=True)
class JointControllerState(Message):
    """State of a single-joint PID controller (set point, measurement, error, command, gains)."""

    header: Header = field(default_factory=Header)
    set_point: float = 0.0
    process_value: float = 0.0
    process_value_dot: float = 0.0
    error: float = 0.0
    time_step: float = 0.0
    command: float = 0.0
    p: float = 0.0
    i: float = 0.0
    d: float = 0.0
    i_clamp: float = 0.0
    antiwindup: bool = False
    __typename__ = "control_msgs/msg/JointControllerState"
    __fields__ = (
        ("header", Header),
        ("set_point", "float64"),
        ("process_value", "float64"),
        ("process_value_dot", "float64"),
        ("error", "float64"),
        ("time_step", "float64"),
        ("command", "float64"),
        ("p", "float64"),
        ("i", "float64"),
        ("d", "float64"),
        ("i_clamp", "float64"),
        ("antiwindup", "bool"),
    )


def _point() -> JointTrajectoryPoint:
    return JointTrajectoryPoint()


def _multi() -> MultiDOFJointTrajectoryPoint:
    return MultiDOFJointTrajectoryPoint()


@dataclass(slots=True)
class JointTrajectoryControllerState(Message):
    """joint_trajectory_controller's state, in Jazzy's field layout (control_msgs 5: the
    Humble-era ``desired``/``actual`` are gone, ``speed_scaling_factor`` is new)."""

    header: Header = field(default_factory=Header)
    joint_names: list[str] = field(default_factory=list)
    reference: JointTrajectoryPoint = field(default_factory=_point)
    feedback: JointTrajectoryPoint = field(default_factory=_point)
    error: JointTrajectoryPoint = field(default_factory=_point)
    output: JointTrajectoryPoint = field(default_factory=_point)
    multi_dof_joint_names: list[str] = field(default_factory=list)
    multi_dof_reference: MultiDOFJointTrajectoryPoint = field(default_factory=_multi)
    multi_dof_feedback: MultiDOFJointTrajectoryPoint = field(default_factory=_multi)
    multi_dof_error: MultiDOFJointTrajectoryPoint = field(default_factory=_multi)
    multi_dof_output: MultiDOFJointTrajectoryPoint = field(default_factory=_multi)
    speed_scaling_factor: float = 0.0
    __typename__ = "control_msgs/msg/JointTrajectoryControllerState"
    __fields__ = (
        ("header", Header),
        ("joint_names", Seq("string")),
        ("reference", JointTrajectoryPoint),
        ("feedback", JointTrajectoryPoint),
        ("error", JointTrajectoryPoint),
        ("output", JointTrajectoryPoint),
        ("multi_dof_joint_names", Seq("string")),
        ("multi_dof_reference", MultiDOFJointTrajectoryPoint),
        ("multi_dof_feedback", MultiDOFJointTrajectoryPoint),
        ("multi_dof_error", MultiDOFJointTrajectoryPoint),
        ("multi_dof_output", MultiDOFJointTrajectoryPoint),
        ("speed_scaling_factor", "float64"),
    )
