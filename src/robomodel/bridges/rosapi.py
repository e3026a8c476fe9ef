"""The rosapi services roslibjs and roslibpy call, answered by the bridge itself.

rosbridge's launch file starts a ``rosapi`` node beside the server; its services (``/rosapi/
topics``, ``/rosapi/get_param``, ...) read the graph and the parameters. Here the bridge answers
them in-process (a ``call_service`` to a ``/rosapi/...`` name never goes on the bus), with the
fields rosapi's ``.srv`` files give: topic and service lists with their types as the bus names
them (``std_msgs/String`` on ROS 1, ``std_msgs/msg/String`` on ROS 2), nodes, a node's details,
and parameters. Parameter values travel as JSON text, as rosapi's ``GetParam``/``SetParam`` do.

Parameters are the ROS 1 master's parameter server on ROS 1, and the nodes' own on ROS 2, named
``/node:param`` as ROS 2's rosapi names them.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any, Protocol

from robomodel.bridges.exceptions import ClientError
from robomodel.bridges.json_mapping import Dialect

__all__ = ["PREFIX", "Ros1Params", "Ros2Params", "Rosapi", "RosapiParams"]

PREFIX = "/rosapi/"


class RosapiParams(Protocol):
    """The parameters rosapi reads and writes."""

    def names(self) -> list[str]: ...
    def get(self, name: str) -> Any: ...  # KeyError when not set
    def set(self, name: str, value: Any) -> None: ...
    def delete(self, name: str) -> None: ...


class Ros1Params:
    """The master's parameter server (a launch's ParamServer or RemoteParamServer, or
    MasterParams): anything with ``get``/``set``/``has``/``delete``/``names``."""

    def __init__(self, server: Any) -> None:
        self._server = server

    def names(self) -> list[str]:
        return sorted(self._server.names())

    def get(self, name: str) -> Any:
        if not self._server.has(name):
            raise KeyError(name)
        return self._server.get(name)

    def set(self, name: str, value: Any) -> None:
        self._server.set(name, value)

    def delete(self, name: str) -> None:
        if not self._server.has(name):
            raise KeyError(name)
        self._server.delete(name)


class Ros2Params:
    """The nodes' parameters through their parameter services, named ``/node:param``."""

    def __init__(self, context: Any, nodes: Callable[[], list[str]], timeout_s: float) -> None:
        self._context = context
        self._nodes = nodes
        self._timeout_s = timeout_s

    def _client(self, node: str) -> Any:
        from robomodel.runtime.param_client import ParameterClient

        return ParameterClient(self._context, node, timeout_s=self._timeout_s)

    @staticmethod
    def _split(name: str) -> tuple[str, str]:
        node, sep, param = name.partition(":")
        if not sep or not node or not param:
            raise ClientError(f"parameter '{name}': ROS 2 names a parameter /node:param")
        return node if node.startswith("/") else f"/{node}", param

    def names(self) -> list[str]:
        from robomodel.errors import RobomodelError

        found: list[str] = []
        for node in self._nodes():
            try:
                found += [f"{node}:{p}" for p in self._client(node).list_names()]
            except RobomodelError:
                continue  # a node without parameter services (rosapi skips it as well)
        return found

    def get(self, name: str) -> Any:
        from robomodel.runtime.params import ParameterError

        node, param = self._split(name)
        try:
            return self._client(node).get([param])[param]
        except ParameterError:
            raise KeyError(name) from None

    def set(self, name: str, value: Any) -> None:
        node, param = self._split(name)
        result = self._client(node).set({param: value})[0]
        if not result.successful:
            raise ClientError(f"{name}: {result.reason or 'the node refused the value'}")

    def delete(self, name: str) -> None:
        raise ClientError(f"{name}: ROS 2 parameters are undeclared by their node, not deleted")


class Rosapi:
    """Answers ``/rosapi/<name>`` calls: ``answer(service, args)`` is the response's fields."""

    def __init__(
        self,
        graph: Callable[[], Any],
        params: RosapiParams,
        dialect: Dialect,
        now_ns: Callable[[], int],
    ) -> None:
        self._graph = graph
        self._params = params
        self._dialect = dialect
        self._now_ns = now_ns
        self._handlers: dict[str, Callable[[dict[str, Any]], dict[str, Any]]] = {
            "topics": self._topics,
            "topic_type": self._topic_type,
            "topics_for_type": self._topics_for_type,
            "services": self._services,
            "service_type": self._service_type,
            "services_for_type": self._services_for_type,
            "nodes": self._nodes,
            "node_details": self._node_details,
            "get_param_names": self._param_names,
            "get_param": self._get_param,
            "set_param": self._set_param,
            "has_param": self._has_param,
            "delete_param": self._delete_param,
            "get_time": self._get_time,
        }

    @property
    def services(self) -> list[str]:
        return [PREFIX + name for name in sorted(self._handlers)]

    def answer(self, service: str, args: dict[str, Any]) -> dict[str, Any]:
        handler = self._handlers.get(service[len(PREFIX) :])
        if handler is None:
            raise ClientError(f"no rosapi service {service}; there are: {', '.join(self.services)}")
        return handler(args)

    @staticmethod
    def _text(args: dict[str, Any], key: str) -> str:
        value = args.get(key, "")
        if not isinstance(value, str):
            raise ClientError(f"rosapi: '{key}' must be a string, got {value!r:.60}")
        return value

    def _one_type(self, types: set[str]) -> str:
        """The type as the bus's ROS names it: ``pkg/Name`` on ROS 1, ``pkg/msg/Name`` on 2."""
        if not types:
            return ""
        name = sorted(types)[0]
        parts = name.split("/")
        if self._dialect == "ros1" and len(parts) == 3:
            return f"{parts[0]}/{parts[2]}"
        return name

    def _topics(self, _: dict[str, Any]) -> dict[str, Any]:
        topics = self._graph().topics
        names = sorted(topics)
        return {"topics": names, "types": [self._one_type(topics[n].types) for n in names]}

    def _topic_type(self, args: dict[str, Any]) -> dict[str, Any]:
        info = self._graph().topics.get(self._text(args, "topic"))
        return {"type": self._one_type(info.types) if info else ""}

    def _topics_for_type(self, args: dict[str, Any]) -> dict[str, Any]:
        wanted = _type_key(self._text(args, "type"))
        topics = self._graph().topics
        found = sorted(n for n, i in topics.items() if wanted in {_type_key(t) for t in i.types})
        return {"topics": found}

    def _services(self, _: dict[str, Any]) -> dict[str, Any]:
        return {"services": sorted(set(self._graph().services) | set(self.services))}

    def _service_type(self, args: dict[str, Any]) -> dict[str, Any]:
        info = self._graph().services.get(self._text(args, "service"))
        return {"type": self._one_type(info.types) if info else ""}

    def _services_for_type(self, args: dict[str, Any]) -> dict[str, Any]:
        wanted = _type_key(self._text(args, "type"))
        services = self._graph().services
        found = sorted(n for n, i in services.items() if wanted in {_type_key(t) for t in i.types})
        return {"services": found}

    def _nodes(self, _: dict[str, Any]) -> dict[str, Any]:
        return {"nodes": sorted(self._graph().nodes)}

    def _node_details(self, args: dict[str, Any]) -> dict[str, Any]:
        node = self._text(args, "node")
        graph = self._graph()
        topics = graph.topics.values()
        return {
            "subscribing": sorted(t.name for t in topics if any(e.node == node for e in t.subscribers)),
            "publishing": sorted(t.name for t in topics if any(e.node == node for e in t.publishers)),
            "services": sorted(s.name for s in graph.services.values() if any(e.node == node for e in s.servers)),
        }  # fmt: skip

    def _param_names(self, _: dict[str, Any]) -> dict[str, Any]:
        return {"names": self._params.names()}

    def _get_param(self, args: dict[str, Any]) -> dict[str, Any]:
        name = self._text(args, "name")
        default = self._text(args, "default")
        try:
            value = self._params.get(name)
        except KeyError:
            value = _loads(default, "default") if default else None
        return {"value": json.dumps(value)}

    def _set_param(self, args: dict[str, Any]) -> dict[str, Any]:
        name = self._text(args, "name")
        self._params.set(name, _loads(self._text(args, "value"), "value"))
        return {}

    def _has_param(self, args: dict[str, Any]) -> dict[str, Any]:
        try:
            self._params.get(self._text(args, "name"))
        except KeyError:
            return {"exists": False}
        return {"exists": True}

    def _delete_param(self, args: dict[str, Any]) -> dict[str, Any]:
        name = self._text(args, "name")
        try:
            self._params.delete(name)
        except KeyError:
            raise ClientError(f"parameter {name} is not set") from None
        return {}

    def _get_time(self, _: dict[str, Any]) -> dict[str, Any]:
        ns = self._now_ns()
        sec, nanosec = divmod(ns, 1_000_000_000)
        if self._dialect == "ros1":
            return {"time": {"secs": sec, "nsecs": nanosec}}
        return {"time": {"sec": sec, "nanosec": nanosec}}


def _type_key(name: str) -> str:
    """``std_msgs/String``, ``std_msgs/msg/String`` and ``std_srvs/srv/Empty`` as ``pkg/Name``
    (they compare equal however the client and the bus spell them)."""
    parts = name.strip("/").split("/")
    return f"{parts[0]}/{parts[-1]}" if len(parts) >= 2 else name


def _loads(text: str, what: str) -> Any:
    try:
        return json.loads(text)
    except ValueError:
        raise ClientError(f"rosapi: '{what}' must be JSON text, got {text!r:.60}") from None
