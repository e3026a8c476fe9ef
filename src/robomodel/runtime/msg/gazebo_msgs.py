"""gazebo_msgs (gazebo_ros_pkgs, ROS 2): the simulator's spawn, delete, state, world and wrench
services, under the names ROS 1's (``/gazebo/...``) and ROS 2's gazebo_ros offer them."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Seq, Service
from robomodel.runtime.msg.builtin_interfaces import Duration, Time
from robomodel.runtime.msg.geometry_msgs import Point, Pose, Twist, Wrench
from robomodel.runtime.msg.std_msgs import Header

__all__ = [
    "ApplyBodyWrench",
    "ApplyBodyWrench_Request",
    "ApplyBodyWrench_Response",
    "DeleteEntity",
    "DeleteEntity_Request",
    "DeleteEntity_Response",
    "DeleteModel",
    "DeleteModel_Request",
    "DeleteModel_Response",
    "EntityState",
    "GetEntityState",
    "GetEntityState_Request",
    "GetEntityState_Response",
    "GetModelList",
    "GetModelList_Request",
    "GetModelList_Response",
    "GetModelState",
    "GetModelState_Request",
    "GetModelState_Response",
    "GetWorldProperties",
    "GetWorldProperties_Request",
    "GetWorldProperties_Response",
    "ModelState",
    "SetEntityState",
    "SetEntityState_Request",
    "SetEntityState_Response",
    "SetModelConfiguration",
    "SetModelConfiguration_Request",
    "SetModelConfiguration_Response",
    "SetModelState",
    "SetModelState_Request",
    "SetModelState_Response",
    "SpawnEntity",
    "SpawnEntity_Request",
    "SpawnEntity_Response",
    "SpawnModel",
    "SpawnModel_Request",
    "SpawnModel_Response",
]


@dataclass(slots=True)
class ModelState(Message):
    model_name: str = ""
    pose: Pose = field(default_factory=Pose)
    twist: Twist = field(default_factory=Twist)
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/msg/ModelState"
    __fields__ = (
        ("model_name", "string"),
        ("pose", Pose),
        ("twist", Twist),
        ("reference_frame", "string"),
    )


@dataclass(slots=True)
class EntityState(Message):
    name: str = ""
    pose: Pose = field(default_factory=Pose)
    twist: Twist = field(default_factory=Twist)
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/msg/EntityState"
    __fields__ = (
        ("name", "string"),
        ("pose", Pose),
        ("twist", Twist),
        ("reference_frame", "string"),
    )


@dataclass(slots=True)
class SpawnModel_Request(Message):
    model_name: str = ""
    model_xml: str = ""
    robot_namespace: str = ""
    initial_pose: Pose = field(default_factory=Pose)
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/srv/SpawnModel_Request"
    __fields__ = (
        ("model_name", "string"),
        ("model_xml", "string"),
        ("robot_namespace", "string"),
        ("initial_pose", Pose),
        ("reference_frame", "string"),
    )


@dataclass(slots=True)
class SpawnModel_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/SpawnModel_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class SpawnModel(Service):
    __typename__ = "gazebo_msgs/srv/SpawnModel"
    Request = SpawnModel_Request
    Response = SpawnModel_Response


@dataclass(slots=True)
class SpawnEntity_Request(Message):
    name: str = ""
    xml: str = ""
    robot_namespace: str = ""
    initial_pose: Pose = field(default_factory=Pose)
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/srv/SpawnEntity_Request"
    __fields__ = (
        ("name", "string"),
        ("xml", "string"),
        ("robot_namespace", "string"),
        ("initial_pose", Pose),
        ("reference_frame", "string"),
    )


@dataclass(slots=True)
class SpawnEntity_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/SpawnEntity_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class SpawnEntity(Service):
    __typename__ = "gazebo_msgs/srv/SpawnEntity"
    Request = SpawnEntity_Request
    Response = SpawnEntity_Response


@dataclass(slots=True)
class DeleteModel_Request(Message):
    model_name: str = ""
    __typename__ = "gazebo_msgs/srv/DeleteModel_Request"
    __fields__ = (("model_name", "string"),)


@dataclass(slots=True)
class DeleteModel_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/DeleteModel_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class DeleteModel(Service):
    __typename__ = "gazebo_msgs/srv/DeleteModel"
    Request = DeleteModel_Request
    Response = DeleteModel_Response


@dataclass(slots=True)
class DeleteEntity_Request(Message):
    name: str = ""
    __typename__ = "gazebo_msgs/srv/DeleteEntity_Request"
    __fields__ = (("name", "string"),)


@dataclass(slots=True)
class DeleteEntity_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/DeleteEntity_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class DeleteEntity(Service):
    __typename__ = "gazebo_msgs/srv/DeleteEntity"
    Request = DeleteEntity_Request
    Response = DeleteEntity_Response


@dataclass(slots=True)
class SetModelState_Request(Message):
    model_state: ModelState = field(default_factory=ModelState)
    __typename__ = "gazebo_msgs/srv/SetModelState_Request"
    __fields__ = (("model_state", ModelState),)


@dataclass(slots=True)
class SetModelState_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/SetModelState_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class SetModelState(Service):
    __typename__ = "gazebo_msgs/srv/SetModelState"
    Request = SetModelState_Request
    Response = SetModelState_Response


@dataclass(slots=True)
class GetModelState_Request(Message):
    model_name: str = ""
    relative_entity_name: str = ""
    __typename__ = "gazebo_msgs/srv/GetModelState_Request"
    __fields__ = (("model_name", "string"), ("relative_entity_name", "string"))


@dataclass(slots=True)
class GetModelState_Response(Message):
    header: Header = field(default_factory=Header)
    pose: Pose = field(default_factory=Pose)
    twist: Twist = field(default_factory=Twist)
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/GetModelState_Response"
    __fields__ = (
        ("header", Header),
        ("pose", Pose),
        ("twist", Twist),
        ("success", "bool"),
        ("status_message", "string"),
    )


class GetModelState(Service):
    __typename__ = "gazebo_msgs/srv/GetModelState"
    Request = GetModelState_Request
    Response = GetModelState_Response


@dataclass(slots=True)
class SetEntityState_Request(Message):
    state: EntityState = field(default_factory=EntityState)
    __typename__ = "gazebo_msgs/srv/SetEntityState_Request"
    __fields__ = (("state", EntityState),)


@dataclass(slots=True)
class SetEntityState_Response(Message):
    success: bool = False
    __typename__ = "gazebo_msgs/srv/SetEntityState_Response"
    __fields__ = (("success", "bool"),)


class SetEntityState(Service):
    __typename__ = "gazebo_msgs/srv/SetEntityState"
    Request = SetEntityState_Request
    Response = SetEntityState_Response


@dataclass(slots=True)
class GetEntityState_Request(Message):
    name: str = ""
    reference_frame: str = ""
    __typename__ = "gazebo_msgs/srv/GetEntityState_Request"
    __fields__ = (("name", "string"), ("reference_frame", "string"))


@dataclass(slots=True)
class GetEntityState_Response(Message):
    header: Header = field(default_factory=Header)
    state: EntityState = field(default_factory=EntityState)
    success: bool = False
    __typename__ = "gazebo_msgs/srv/GetEntityState_Response"
    __fields__ = (("header", Header), ("state", EntityState), ("success", "bool"))


class GetEntityState(Service):
    __typename__ = "gazebo_msgs/srv/GetEntityState"
    Request = GetEntityState_Request
    Response = GetEntityState_Response


@dataclass(slots=True)
class SetModelConfiguration_Request(Message):
    model_name: str = ""
    urdf_param_name: str = ""
    joint_names: list[str] = field(default_factory=list)
    joint_positions: list[float] = field(default_factory=list)
    __typename__ = "gazebo_msgs/srv/SetModelConfiguration_Request"
    __fields__ = (
        ("model_name", "string"),
        ("urdf_param_name", "string"),
        ("joint_names", Seq("string")),
        ("joint_positions", Seq("float64")),
    )


@dataclass(slots=True)
class SetModelConfiguration_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/SetModelConfiguration_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class SetModelConfiguration(Service):
    __typename__ = "gazebo_msgs/srv/SetModelConfiguration"
    Request = SetModelConfiguration_Request
    Response = SetModelConfiguration_Response


@dataclass(slots=True)
class GetWorldProperties_Request(Message):
    __typename__ = "gazebo_msgs/srv/GetWorldProperties_Request"
    __fields__ = ()


@dataclass(slots=True)
class GetWorldProperties_Response(Message):
    sim_time: float = 0.0
    model_names: list[str] = field(default_factory=list)
    rendering_enabled: bool = False
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/GetWorldProperties_Response"
    __fields__ = (
        ("sim_time", "float64"),
        ("model_names", Seq("string")),
        ("rendering_enabled", "bool"),
        ("success", "bool"),
        ("status_message", "string"),
    )


class GetWorldProperties(Service):
    __typename__ = "gazebo_msgs/srv/GetWorldProperties"
    Request = GetWorldProperties_Request
    Response = GetWorldProperties_Response


@dataclass(slots=True)
class GetModelList_Request(Message):
    __typename__ = "gazebo_msgs/srv/GetModelList_Request"
    __fields__ = ()


@dataclass(slots=True)
class GetModelList_Response(Message):
    header: Header = field(default_factory=Header)
    model_names: list[str] = field(default_factory=list)
    success: bool = False
    __typename__ = "gazebo_msgs/srv/GetModelList_Response"
    __fields__ = (("header", Header), ("model_names", Seq("string")), ("success", "bool"))


class GetModelList(Service):
    __typename__ = "gazebo_msgs/srv/GetModelList"
    Request = GetModelList_Request
    Response = GetModelList_Response


@dataclass(slots=True)
class ApplyBodyWrench_Request(Message):
    body_name: str = ""
    reference_frame: str = ""
    reference_point: Point = field(default_factory=Point)
    wrench: Wrench = field(default_factory=Wrench)
    start_time: Time = field(default_factory=Time)
    duration: Duration = field(default_factory=Duration)
    __typename__ = "gazebo_msgs/srv/ApplyBodyWrench_Request"
    __fields__ = (
        ("body_name", "string"),
        ("reference_frame", "string"),
        ("reference_point", Point),
        ("wrench", Wrench),
        ("start_time", Time),
        ("duration", Duration),
    )


@dataclass(slots=True)
class ApplyBodyWrench_Response(Message):
    success: bool = False
    status_message: str = ""
    __typename__ = "gazebo_msgs/srv/ApplyBodyWrench_Response"
    __fields__ = (("success", "bool"), ("status_message", "string"))


class ApplyBodyWrench(Service):
    __typename__ = "gazebo_msgs/srv/ApplyBodyWrench"
    Request = ApplyBodyWrench_Request
    Response = ApplyBodyWrench_Response
