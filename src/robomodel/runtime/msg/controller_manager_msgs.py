"""controller_manager_msgs (ros2_control, Jazzy): the controller manager's services and their
messages."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from robomodel.runtime.msg._schema import Message, Seq, Service
from robomodel.runtime.msg.builtin_interfaces import Duration
from robomodel.runtime.msg.lifecycle_msgs import State
from robomodel.runtime.msg.std_msgs import Header

__all__ = [
    "ChainConnection",
    "CleanupController",
    "CleanupController_Request",
    "CleanupController_Response",
    "ConfigureController",
    "ConfigureController_Request",
    "ConfigureController_Response",
    "ControllerManagerActivity",
    "ControllerState",
    "HardwareComponentState",
    "HardwareInterface",
    "ListControllerTypes",
    "ListControllerTypes_Request",
    "ListControllerTypes_Response",
    "ListControllers",
    "ListControllers_Request",
    "ListControllers_Response",
    "ListHardwareComponents",
    "ListHardwareComponents_Request",
    "ListHardwareComponents_Response",
    "ListHardwareInterfaces",
    "ListHardwareInterfaces_Request",
    "ListHardwareInterfaces_Response",
    "LoadController",
    "LoadController_Request",
    "LoadController_Response",
    "NamedLifecycleState",
    "ReloadControllerLibraries",
    "ReloadControllerLibraries_Request",
    "ReloadControllerLibraries_Response",
    "SetHardwareComponentState",
    "SetHardwareComponentState_Request",
    "SetHardwareComponentState_Response",
    "SwitchController",
    "SwitchController_Request",
    "SwitchController_Response",
    "UnloadController",
    "UnloadController_Request",
    "UnloadController_Response",
]


@dataclass(slots=True)
class HardwareInterface(Message):
    name: str = ""
    data_type: str = ""
    is_available: bool = False
    is_claimed: bool = False
    __typename__ = "controller_manager_msgs/msg/HardwareInterface"
    __fields__ = (
        ("name", "string"),
        ("data_type", "string"),
        ("is_available", "bool"),
        ("is_claimed", "bool"),
    )


@dataclass(slots=True)
class ChainConnection(Message):
    name: str = ""
    reference_interfaces: list[str] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/msg/ChainConnection"
    __fields__ = (("name", "string"), ("reference_interfaces", Seq("string")))


@dataclass(slots=True)
class ControllerState(Message):
    name: str = ""
    state: str = ""
    type: str = ""
    is_async: bool = False
    update_rate: int = 0
    claimed_interfaces: list[str] = field(default_factory=list)
    required_command_interfaces: list[str] = field(default_factory=list)
    required_state_interfaces: list[str] = field(default_factory=list)
    is_chainable: bool = False
    is_chained: bool = False
    exported_state_interfaces: list[str] = field(default_factory=list)
    reference_interfaces: list[str] = field(default_factory=list)
    chain_connections: list[ChainConnection] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/msg/ControllerState"
    __fields__ = (
        ("name", "string"),
        ("state", "string"),
        ("type", "string"),
        ("is_async", "bool"),
        ("update_rate", "uint16"),
        ("claimed_interfaces", Seq("string")),
        ("required_command_interfaces", Seq("string")),
        ("required_state_interfaces", Seq("string")),
        ("is_chainable", "bool"),
        ("is_chained", "bool"),
        ("exported_state_interfaces", Seq("string")),
        ("reference_interfaces", Seq("string")),
        ("chain_connections", Seq(ChainConnection)),
    )


@dataclass(slots=True)
class NamedLifecycleState(Message):
    name: str = ""
    state: State = field(default_factory=State)
    __typename__ = "controller_manager_msgs/msg/NamedLifecycleState"
    __fields__ = (("name", "string"), ("state", State))


@dataclass(slots=True)
class HardwareComponentState(Message):
    name: str = ""
    type: str = ""
    is_async: bool = False
    rw_rate: int = 0
    class_type: str = ""
    plugin_name: str = ""
    state: State = field(default_factory=State)
    command_interfaces: list[HardwareInterface] = field(default_factory=list)
    state_interfaces: list[HardwareInterface] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/msg/HardwareComponentState"
    __fields__ = (
        ("name", "string"),
        ("type", "string"),
        ("is_async", "bool"),
        ("rw_rate", "uint16"),
        ("class_type", "string"),
        ("plugin_name", "string"),
        ("state", State),
        ("command_interfaces", Seq(HardwareInterface)),
        ("state_interfaces", Seq(HardwareInterface)),
    )


@dataclass(slots=True)
class ControllerManagerActivity(Message):
    header: Header = field(default_factory=Header)
    controllers: list[NamedLifecycleState] = field(default_factory=list)
    hardware_components: list[NamedLifecycleState] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/msg/ControllerManagerActivity"
    __fields__ = (
        ("header", Header),
        ("controllers", Seq(NamedLifecycleState)),
        ("hardware_components", Seq(NamedLifecycleState)),
    )


@dataclass(slots=True)
class ListControllers_Request(Message):
    __typename__ = "controller_manager_msgs/srv/ListControllers_Request"
    __fields__ = ()


@dataclass(slots=True)
class ListControllers_Response(Message):
    controller: list[ControllerState] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/srv/ListControllers_Response"
    __fields__ = (("controller", Seq(ControllerState)),)


class ListControllers(Service):
    __typename__ = "controller_manager_msgs/srv/ListControllers"
    Request = ListControllers_Request
    Response = ListControllers_Response


@dataclass(slots=True)
class ListControllerTypes_Request(Message):
    __typename__ = "controller_manager_msgs/srv/ListControllerTypes_Request"
    __fields__ = ()


@dataclass(slots=True)
class ListControllerTypes_Response(Message):
    types: list[str] = field(default_factory=list)
    base_classes: list[str] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/srv/ListControllerTypes_Response"
    __fields__ = (("types", Seq("string")), ("base_classes", Seq("string")))


class ListControllerTypes(Service):
    __typename__ = "controller_manager_msgs/srv/ListControllerTypes"
    Request = ListControllerTypes_Request
    Response = ListControllerTypes_Response


@dataclass(slots=True)
class ListHardwareComponents_Request(Message):
    __typename__ = "controller_manager_msgs/srv/ListHardwareComponents_Request"
    __fields__ = ()


@dataclass(slots=True)
class ListHardwareComponents_Response(Message):
    component: list[HardwareComponentState] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/srv/ListHardwareComponents_Response"
    __fields__ = (("component", Seq(HardwareComponentState)),)


class ListHardwareComponents(Service):
    __typename__ = "controller_manager_msgs/srv/ListHardwareComponents"
    Request = ListHardwareComponents_Request
    Response = ListHardwareComponents_Response


@dataclass(slots=True)
class ListHardwareInterfaces_Request(Message):
    __typename__ = "controller_manager_msgs/srv/ListHardwareInterfaces_Request"
    __fields__ = ()


@dataclass(slots=True)
class ListHardwareInterfaces_Response(Message):
    command_interfaces: list[HardwareInterface] = field(default_factory=list)
    state_interfaces: list[HardwareInterface] = field(default_factory=list)
    __typename__ = "controller_manager_msgs/srv/ListHardwareInterfaces_Response"
    __fields__ = (
        ("command_interfaces", Seq(HardwareInterface)),
        ("state_interfaces", Seq(HardwareInterface)),
    )


class ListHardwareInterfaces(Service):
    __typename__ = "controller_manager_msgs/srv/ListHardwareInterfaces"
    Request = ListHardwareInterfaces_Request
    Response = ListHardwareInterfaces_Response


@dataclass(slots=True)
class LoadController_Request(Message):
    name: str = ""
    __typename__ = "controller_manager_msgs/srv/LoadController_Request"
    __fields__ = (("name", "string"),)


@dataclass(slots=True)
class LoadController_Response(Message):
    ok: bool = False
    __typename__ = "controller_manager_msgs/srv/LoadController_Response"
    __fields__ = (("ok", "bool"),)


class LoadController(Service):
    __typename__ = "controller_manager_msgs/srv/LoadController"
    Request = LoadController_Request
    Response = LoadController_Response


@dataclass(slots=True)
class ConfigureController_Request(Message):
    name: str = ""
    __typename__ = "controller_manager_msgs/srv/ConfigureController_Request"
    __fields__ = (("name", "string"),)


@dataclass(slots=True)
class ConfigureController_Response(Message):
    ok: bool = False
    __typename__ = "controller_manager_msgs/srv/ConfigureController_Response"
    __fields__ = (("ok", "bool"),)


class ConfigureController(Service):
    __typename__ = "controller_manager_msgs/srv/ConfigureController"
    Request = ConfigureController_Request
    Response = ConfigureController_Response


@dataclass(slots=True)
class CleanupController_Request(Message):
    name: str = ""
    __typename__ = "controller_manager_msgs/srv/CleanupController_Request"
    __fields__ = (("name", "string"),)


@dataclass(slots=True)
class CleanupController_Response(Message):
    ok: bool = False
    __typename__ = "controller_manager_msgs/srv/CleanupController_Response"
    __fields__ = (("ok", "bool"),)


class CleanupController(Service):
    __typename__ = "controller_manager_msgs/srv/CleanupController"
    Request = CleanupController_Request
    Response = CleanupController_Response


@dataclass(slots=True)
class SwitchController_Request(Message):
    BEST_EFFORT: ClassVar[int] = 1
    STRICT: ClassVar[int] = 2
    AUTO: ClassVar[int] = 3
    FORCE_AUTO: ClassVar[int] = 4

    activate_controllers: list[str] = field(default_factory=list)
    deactivate_controllers: list[str] = field(default_factory=list)
    strictness: int = 0
    activate_asap: bool = False
    timeout: Duration = field(default_factory=Duration)
    __typename__ = "controller_manager_msgs/srv/SwitchController_Request"
    __fields__ = (
        ("activate_controllers", Seq("string")),
        ("deactivate_controllers", Seq("string")),
        ("strictness", "int32"),
        ("activate_asap", "bool"),
        ("timeout", Duration),
    )


@dataclass(slots=True)
class SwitchController_Response(Message):
    ok: bool = False
    message: str = ""
    __typename__ = "controller_manager_msgs/srv/SwitchController_Response"
    __fields__ = (("ok", "bool"), ("message", "string"))


class SwitchController(Service):
    __typename__ = "controller_manager_msgs/srv/SwitchController"
    Request = SwitchController_Request
    Response = SwitchController_Response


@dataclass(slots=True)
class UnloadController_Request(Message):
    name: str = ""
    __typename__ = "controller_manager_msgs/srv/UnloadController_Request"
    __fields__ = (("name", "string"),)


@dataclass(slots=True)
class UnloadController_Response(Message):
    ok: bool = False
    __typename__ = "controller_manager_msgs/srv/UnloadController_Response"
    __fields__ = (("ok", "bool"),)


class UnloadController(Service):
    __typename__ = "controller_manager_msgs/srv/UnloadController"
    Request = UnloadController_Request
    Response = UnloadController_Response


@dataclass(slots=True)
class ReloadControllerLibraries_Request(Message):
    force_kill: bool = False
    __typename__ = "controller_manager_msgs/srv/ReloadControllerLibraries_Request"
    __fields__ = (("force_kill", "bool"),)


@dataclass(slots=True)
class ReloadControllerLibraries_Response(Message):
    ok: bool = False
    __typename__ = "controller_manager_msgs/srv/ReloadControllerLibraries_Response"
    __fields__ = (("ok", "bool"),)


class ReloadControllerLibraries(Service):
    __typename__ = "controller_manager_msgs/srv/ReloadControllerLibraries"
    Request = ReloadControllerLibraries_Request
    Response = ReloadControllerLibraries_Response


@dataclass(slots=True)
class SetHardwareComponentState_Request(Message):
    name: str = ""
    target_state: State = field(default_factory=State)
    __typename__ = "controller_manager_msgs/srv/SetHardwareComponentState_Request"
    __fields__ = (("name", "string"), ("target_state", State))


@dataclass(slots=True)
class SetHardwareComponentState_Response(Message):
    ok: bool = False
    state: State = field(default_factory=State)
    __typename__ = "controller_manager_msgs/srv/SetHardwareComponentState_Response"
    __fields__ = (("ok", "bool"), ("state", State))


class SetHardwareComponentState(Service):
    __typename__ = "controller_manager_msgs/srv/SetHardwareComponentState"
    Request = SetHardwareComponentState_Request
    Response = SetHardwareComponentState_Response
