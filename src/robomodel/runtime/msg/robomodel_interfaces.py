"""robomodel_interfaces: robomodel's own service types, for what ROS has no type for.

``MasterCall`` carries a call of the ROS 1 parameter server that ``robomodel launch`` hosts for
ROS 1 launch files on the Zenoh bus (rosmaster's ``getParam``, ``setParam``, ...), with its
arguments and result as JSON, on one service of its own (``/rosmaster``).
"""

from __future__ import annotations

from dataclasses import dataclass

from robomodel.runtime.msg._schema import Message, Service

__all__ = ["MasterCall", "MasterCall_Request", "MasterCall_Response"]


@dataclass(slots=True)
class MasterCall_Request(Message):
    method: str = ""
    arguments: str = "{}"
    __typename__ = "robomodel_interfaces/srv/MasterCall_Request"
    __fields__ = (("method", "string"), ("arguments", "string"))


@dataclass(slots=True)
class MasterCall_Response(Message):
    ok: bool = False
    result: str = "null"
    error: str = ""
    __typename__ = "robomodel_interfaces/srv/MasterCall_Response"
    __fields__ = (("ok", "bool"), ("result", "string"), ("error", "string"))


class MasterCall(Service):
    __typename__ = "robomodel_interfaces/srv/MasterCall"
    Request = MasterCall_Request
    Response = MasterCall_Response
