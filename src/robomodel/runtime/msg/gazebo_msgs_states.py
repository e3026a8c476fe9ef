"""gazebo_msgs (gazebo_ros_pkgs): model and link states and properties, the same in ROS 1
(noetic-devel) and ROS 2 (ros2 branch): ``/gazebo/model_states``, ``/gazebo/link_states``,
``get_link_state``, ``set_link_state`` and ``get_model_properties``. Link names are Gazebo's
scoped names, ``model::link``."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq, Service
from robomodel.runtime.msg.geometry_msgs import Pose, Twist

__all__ = [
    "GetLinkState",
    "GetLinkState_Request",
    "GetLinkState_Response",
    "GetModelProperties",
    "GetModelProperties_Request",
    "GetModelProperties_Response",
    "LinkState",
    "LinkStates",
    "ModelStates",
    "SetLinkState",
    "SetLinkState_Request",
    "SetLinkState_Response",
]


@dataclass(slots=True)
class LinkState(Message):
    link_name: str = ""
    pose: Pose = field(default_factory=Pose)
    twist: Twist = field(default_factory=Twist)
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/msg/LinkState"
    __fields__ = (
        ("link_name", "string"),
        ("pose", Pose),
        ("twist", Twist),
        ("reference_frame", "string"),
    )


@dataclass(slots=True)
class ModelStates(Message):
    """Every model's pose and twist in the world frame."""

    name: list[str] = field(default_factory=list)
    pose: list[Pose] = field(default_factory=list)
    twist: list[Twist] = field(default_factory=list)
    __typename__ = "gazebo_msgs/msg/ModelStates"
    __fields__ = (("name", Seq("string")), ("pose", Seq(Pose)), ("twist", Seq(Twist)))


@dataclass(slots=True)
class LinkStates(Message):
    """Every link's pose and twist in the world frame (names ``model::link``)."""

    name: list[str] = field(default_factory=list)
    pose: list[Pose] = field(default_factory=list)
    twist: list[Twist] = field(default_factory=list)
    __typename__ = "gazebo_msgs/msg/LinkStates"
    __fields__ = (("name", Seq("string")), ("pose", Seq(Pose)), ("twist", Seq(Twist)))


@dataclass(slots=True)
class GetLinkState_Request(Message):
    link_name: str = ""
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/srv/GetLinkState_Request"
    __fields__ = (("link_name", "string"), ("reference_frame", "string"))


@dataclass(slots=True)
class GetLinkState_Response(Message):
    link_state: LinkState = field(default_factory=LinkState)
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/GetLinkState_Response"
    __fields__ = (("link_state", LinkState), ("success", "bool"), ("status_message", "string"))


class GetLinkState(Service):
    __typename__ = "gazebo_msgs/srv/GetLinkState"
    Request = GetLinkState_Request
    Response = GetLinkState_Response


@dataclass(slots=True)
class SetLinkState_Request(Message):
    link_state: LinkState = field(default_factory=LinkState)
    __typename__ = "gazebo_msgs/srv/SetLinkState_Request"
    __fields__ = (("link_state", LinkState),)


@dataclass(slots=True)
class SetLinkState_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/SetLinkState_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class SetLinkState(Service):
    __typename__ = "gazebo_msgs/srv/SetLinkState"
    Request = SetLinkState_Request
    Response = SetLinkState_Response


@dataclass(slots=True)
class GetModelProperties_Request(Message):
    model_name: str = ""
    __typename__ = "gazebo_msgs/srv/GetModelProperties_Request"
    __fields__ = (("model_name", "string"),)


@dataclass(slots=True)
class GetModelProperties_Response(Message):
    parent_model_name: str = ""
    canonical_body_name: str = ""
    body_names: list[str] = field(default_factory=list)
    geom_names: list[str] = field(default_factory=list)
    joint_names: list[str] = field(default_factory=list)
    child_model_names: list[str] = field(default_factory=list)
    is_static: bool = False
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/GetModelProperties_Response"
    __fields__ = (
        ("parent_model_name", "string"),
        ("canonical_body_name", "string"),
        ("body_names", Seq("string")),
        ("geom_names", Seq("string")),
        ("joint_names", Seq("string")),
        ("child_model_names", Seq("string")),
        ("is_static", "bool"),
        ("success", "bool"),
        ("status_message", "string"),
    )


class GetModelProperties(Service):
    __typename__ = "gazebo_msgs/srv/GetModelProperties"
    Request = GetModelProperties_Request
    Response = GetModelProperties_Response
