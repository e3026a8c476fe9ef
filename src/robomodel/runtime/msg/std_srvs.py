"""std_srvs (Jazzy): Empty, Trigger and SetBool."""

from __future__ import annotations

from dataclasses import dataclass

from robomodel.runtime.msg._schema import Message, Service

__all__ = [
    "Empty",
    "Empty_Request",
    "Empty_Response",
    "SetBool",
    "SetBool_Request",
    "SetBool_Response",
    "Trigger",
    "Trigger_Request",
    "Trigger_Response",
]


@dataclass(slots=True)
class Empty_Request(Message):
    __typename__ = "std_srvs/srv/Empty_Request"
    __fields__ = ()


@dataclass(slots=True)
class Empty_Response(Message):
    __typename__ = "std_srvs/srv/Empty_Response"
    __fields__ = ()


class Empty(Service):
    __typename__ = "std_srvs/srv/Empty"
    Request = Empty_Request
    Response = Empty_Response


@dataclass(slots=True)
class Trigger_Request(Message):
    __typename__ = "std_srvs/srv/Trigger_Request"
    __fields__ = ()


@dataclass(slots=True)
class Trigger_Response(Message):
    success: bool = False
    message: str = ""
    __typename__ = "std_srvs/srv/Trigger_Response"
    __fields__ = (("success", "bool"), ("message", "string"))


class Trigger(Service):
    __typename__ = "std_srvs/srv/Trigger"
    Request = Trigger_Request
    Response = Trigger_Response


@dataclass(slots=True)
class SetBool_Request(Message):
    data: bool = False
    __typename__ = "std_srvs/srv/SetBool_Request"
    __fields__ = (("data", "bool"),)


@dataclass(slots=True)
class SetBool_Response(Message):
    success: bool = False
    message: str = ""
    __typename__ = "std_srvs/srv/SetBool_Response"
    __fields__ = (("success", "bool"), ("message", "string"))


class SetBool(Service):
    __typename__ = "std_srvs/srv/SetBool"
    Request = SetBool_Request
    Response = SetBool_Response
