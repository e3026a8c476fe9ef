"""A ROS 1 parameter server (rosmaster's), shared by every robomodel process of a domain.

The first ``robomodel launch`` of a domain hosts it, as ``roscore`` does, and offers it over the
bus as one service of its own, ``/_robomodel_params/call`` (``robomodel_interfaces/srv/MasterCall``: the call
-- ``getParam``, ``setParam``, ``deleteParam``, ``hasParam``, ``searchParam``, ``getParamNames``
-- and its arguments and result as JSON); later processes of the domain find it there and use
it. ``robomodel param get /name`` / ``set`` / ``list /`` / ``delete`` reach it too.

Its node and service names are hidden ones (a part starting with ``_``, which ``ros2 node list``
and ``ros2 service list`` leave out, as ``robomodel node list`` does): a Zenoh graph shows no
``/rosmaster``, since no ROS 1 master is part of it.

Values are stored as rosmaster stores them: a tree, so getting a namespace returns a dict and
setting a dict replaces the whole namespace.
"""

from __future__ import annotations

import base64
import json
import time
from collections.abc import Callable, Mapping
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.launch.ros1.params import Binary
from robomodel.runtime.msg.types.robomodel_interfaces import (
    MasterCall,
    MasterCall_Request,
    MasterCall_Response,
)
from robomodel.runtime.transport.ros1.param_tree import ParamServerError, ParamTree

__all__ = [
    "NODE",
    "SERVICE",
    "ParamServer",
    "ParamServerError",
    "RemoteParamServer",
    "connect_or_host",
    "decode_value",
    "encode_value",
]

NODE = "_robomodel_params"
SERVICE = f"/{NODE}/call"
_CALLS = ("getParam", "setParam", "deleteParam", "hasParam", "searchParam", "getParamNames")


def encode_value(value: Any) -> Any:
    """A value as it travels over the bus (JSON-like; bytes as {"__binary__": base64})."""
    if isinstance(value, Binary):
        return {"__binary__": base64.b64encode(value.data).decode("ascii")}
    if isinstance(value, Mapping):
        return {str(k): encode_value(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [encode_value(v) for v in value]
    return value


def decode_value(value: Any) -> Any:
    if isinstance(value, Mapping):
        if set(value) == {"__binary__"}:
            return Binary(base64.b64decode(value["__binary__"]))
        return {k: decode_value(v) for k, v in value.items()}
    if isinstance(value, list):
        return [decode_value(v) for v in value]
    return value


class ParamServer(ParamTree):
    """rosmaster's parameter tree, served over the bus as :data:`SERVICE`."""

    # -- over the bus -----------------------------------------------------------------------
    def handle(self, call: str, request: Mapping[str, Any]) -> dict[str, Any]:
        try:
            if call == "getParam":
                return {"value": encode_value(self.get(str(request["key"])))}
            if call == "setParam":
                self.set(str(request["key"]), decode_value(request.get("value")))
                return {"ok": True}
            if call == "deleteParam":
                self.delete(str(request["key"]))
                return {"ok": True}
            if call == "hasParam":
                return {"value": self.has(str(request["key"]))}
            if call == "searchParam":
                return {"value": self.search(str(request.get("ns", "/")), str(request["key"]))}
            if call == "getParamNames":
                return {"value": self.names()}
        except ParamServerError as exc:
            return {"error": str(exc)}
        except (KeyError, TypeError) as exc:
            return {"error": f"bad {call} request: {exc}"}
        return {"error": f"unknown call {call}"}

    def serve(self, context: Any) -> Callable[[], None]:
        """Offer this server as the :data:`SERVICE` service on ``context``'s bus."""
        node = context.create_node(NODE)
        node.create_service(MasterCall, SERVICE, self._answer)
        return node.destroy  # type: ignore[no-any-return]

    def _answer(self, request: MasterCall_Request) -> MasterCall_Response:
        try:
            arguments = json.loads(request.arguments or "{}")
        except ValueError:
            return MasterCall_Response(False, "null", "arguments are not JSON")
        except RecursionError:
            return MasterCall_Response(False, "null", "arguments are nested too deeply")
        if not isinstance(arguments, dict):
            return MasterCall_Response(False, "null", "arguments must be a JSON object")
        reply = self.handle(request.method, arguments)
        if "error" in reply:
            return MasterCall_Response(False, "null", str(reply["error"]))
        return MasterCall_Response(True, json.dumps(reply.get("value")), "")


class RemoteParamServer:
    """The parameter server of another process of the domain, through its services."""

    def __init__(self, context: Any, timeout_s: float = 3.0) -> None:
        self._context = context
        self._timeout_s = timeout_s

    def _call(self, call: str, **request: Any) -> Any:
        try:
            reply = self._context.call_service(
                SERVICE, MasterCall, MasterCall_Request(call, json.dumps(request)), self._timeout_s
            )
        except RobomodelError as exc:
            raise ParamServerError(f"the parameter server does not answer: {exc}") from None
        if not reply.ok:
            raise ParamServerError(reply.error)
        return decode_value(json.loads(reply.result))

    def get(self, name: str) -> Any:
        return self._call("getParam", key=name)

    def set(self, name: str, value: Any) -> None:
        self._call("setParam", key=name, value=encode_value(value))

    def delete(self, name: str) -> None:
        self._call("deleteParam", key=name)

    def has(self, name: str) -> bool:
        return bool(self._call("hasParam", key=name))

    def names(self) -> list[str]:
        return list(self._call("getParamNames"))

    def search(self, namespace: str, key: str) -> str | None:
        value = self._call("searchParam", ns=namespace, key=key)
        return None if value is None else str(value)


def connect_or_host(context: Any, settle_s: float = 1.5) -> tuple[Any, bool]:
    """The domain's parameter server: a remote one if a process already hosts it (its
    :data:`SERVICE` is in the graph), else a new one hosted (and served) here. Returns
    ``(server, hosted_here)``.

    The graph decides, not a timed call: a call to a service this session has not yet heard of
    returns at once. A session linked to a router receives the router's liveliness tokens some
    milliseconds after opening, longer on a loaded machine; so while the domain looks empty and
    the session is linked, the graph is asked again for up to ``settle_s``. Once other nodes
    show, the graph must stop changing for three answers before its lack of :data:`SERVICE`
    decides. A second server would split the
    launch's parameters in two."""
    if context.transport.name != "inproc" and _remote_server_found(context, settle_s):
        return RemoteParamServer(context), False
    server = ParamServer()
    server.serve(context)
    return server, True


def _remote_server_found(context: Any, settle_s: float) -> bool:
    linked = getattr(context.transport, "linked", lambda: False)
    deadline = time.monotonic() + settle_s
    previous: tuple[list[str], list[str]] | None = None
    stable = 0
    while True:
        graph = context.graph(timeout_s=0.5)
        info = graph.services.get(SERVICE)
        if info is not None and info.servers:  # a server, not another launch's client of it
            return True
        # Liveliness tokens arrive in batches: decide only once the graph has stopped growing
        # (three answers in a row the same), not on a partial one that lacks the service yet.
        snapshot = (sorted(map(str, graph.nodes)), sorted(map(str, graph.services)))
        stable = stable + 1 if graph.nodes and snapshot == previous else 0
        previous = snapshot
        if stable >= 3 or not linked() or time.monotonic() >= deadline:
            return False
        time.sleep(0.1)
