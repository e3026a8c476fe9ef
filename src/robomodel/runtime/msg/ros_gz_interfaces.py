"""ros_gz_interfaces (ros_gz, Jazzy): ControlWorld, Gazebo Sim's pause / step / reset request."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg._schema import Message, Service
from robomodel.runtime.msg.builtin_interfaces import Time

__all__ = [
    "ControlWorld",
    "ControlWorld_Request",
    "ControlWorld_Response",
    "WorldControl",
    "WorldReset",
]


@dataclass(slots=True)
class WorldReset(Message):
    all: bool = False
    time_only: bool = False
    model_only: bool = False
    __typename__ = "ros_gz_interfaces/msg/WorldReset"
    __fields__ = (("all", "bool"), ("time_only", "bool"), ("model_only", "bool"))


@dataclass(slots=True)
class WorldControl(Message):
    pause: bool = False
    step: bool = False
    multi_step: int = 0
    reset: WorldReset = field(default_factory=WorldReset)
    seed: int = 0
    run_to_sim_time: Time = field(default_factory=Time)
    __typename__ = "ros_gz_interfaces/msg/WorldControl"
    __fields__ = (
        ("pause", "bool"),
        ("step", "bool"),
        ("multi_step", "uint32"),
        ("reset", WorldReset),
        ("seed", "uint32"),
        ("run_to_sim_time", Time),
    )


@dataclass(slots=True)
class ControlWorld_Request(Message):
    world_control: WorldControl = field(default_factory=WorldControl)
    __typename__ = "ros_gz_interfaces/srv/ControlWorld_Request"
    __fields__ = (("world_control", WorldControl),)


@dataclass(slots=True)
class ControlWorld_Response(Message):
    success: bool = False
    __typename__ = "ros_gz_interfaces/srv/ControlWorld_Response"
    __fields__ = (("success", "bool"),)


class ControlWorld(Service):
    __typename__ = "ros_gz_interfaces/srv/ControlWorld"
    Request = ControlWorld_Request
    Response = ControlWorld_Response
