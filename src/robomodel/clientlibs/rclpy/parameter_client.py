"""``rclpy.parameter_client``: :class:`AsyncParameterClient`, a remote node's parameters
through its parameter services (``<node>/get_parameters`` and the rest, rcl_interfaces), as
rclpy's client calls them. Every call returns a :class:`~rclpy.task.Future` of the service's
response."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import interface
from robomodel.clientlibs.rclpy.parameter import Parameter, parameter_dict_from_yaml_file
from robomodel.clientlibs.rclpy.qos import (
    QoSProfile,
    qos_profile_parameter_events,
    qos_profile_services_default,
)

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.node import Node
    from robomodel.clientlibs.rclpy.subscription import Subscription
    from robomodel.clientlibs.rclpy.task import Future

__all__ = ["AsyncParameterClient"]

_SERVICES = (
    "get_parameters", "list_parameters", "set_parameters", "get_parameter_types",
    "describe_parameters", "set_parameters_atomically",
)  # fmt: skip


def _service_type(service: str) -> Any:
    return interface("rcl_interfaces.srv", "".join(p.title() for p in service.split("_")))


class AsyncParameterClient:
    """The parameters of node ``remote_node_name`` (a name relative to ``node``'s namespace,
    or a fully qualified one), over clients that ``node`` makes."""

    def __init__(
        self,
        node: Node,
        remote_node_name: str,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        self.remote_node_name = remote_node_name
        self.node = node
        self._clients = {
            service: node.create_client(
                _service_type(service),
                f"{remote_node_name}/{service}",
                qos_profile=qos_profile,
                callback_group=callback_group,
            )
            for service in _SERVICES
        }

    def services_are_ready(self) -> bool:
        """True once every parameter service of the remote node answers."""
        return all(client.service_is_ready() for client in self._clients.values())

    def wait_for_services(self, timeout_sec: float | None = None) -> bool:
        """Wait up to ``timeout_sec`` (None: for ever) for every parameter service."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        for client in self._clients.values():
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            if not client.wait_for_service(timeout_sec=left):
                return False
        return True

    def _call(self, service: str, request: Any, callback: Callable[..., Any] | None) -> Future:
        future = self._clients[service].call_async(request)
        if callback is not None:
            future.add_done_callback(callback)
        return future

    def list_parameters(
        self,
        prefixes: list[str] | None = None,
        depth: int | None = None,
        callback: Callable[..., Any] | None = None,
    ) -> Future:
        """``ListParameters.Response`` of the names under ``prefixes`` to ``depth`` levels."""
        request = _service_type("list_parameters").Request()
        if prefixes:
            request.prefixes = list(prefixes)
        if depth:
            request.depth = depth
        return self._call("list_parameters", request, callback)

    def get_parameters(
        self, names: list[str], callback: Callable[..., Any] | None = None
    ) -> Future:
        """``GetParameters.Response``: the values (``ParameterValue``) of ``names``."""
        request = _service_type("get_parameters").Request(names=list(names))
        return self._call("get_parameters", request, callback)

    def set_parameters(
        self, parameters: Sequence[Any], callback: Callable[..., Any] | None = None
    ) -> Future:
        """``SetParameters.Response``: one result per parameter (``Parameter`` or its
        ``rcl_interfaces/Parameter`` message)."""
        request = _service_type("set_parameters").Request(parameters=_messages(parameters))
        return self._call("set_parameters", request, callback)

    def set_parameters_atomically(
        self, parameters: Sequence[Any], callback: Callable[..., Any] | None = None
    ) -> Future:
        """``SetParametersAtomically.Response``: all set, or none."""
        service = "set_parameters_atomically"
        request = _service_type(service).Request(parameters=_messages(parameters))
        return self._call(service, request, callback)

    def describe_parameters(
        self, names: list[str], callback: Callable[..., Any] | None = None
    ) -> Future:
        """``DescribeParameters.Response``: the descriptors of ``names``."""
        request = _service_type("describe_parameters").Request(names=list(names))
        return self._call("describe_parameters", request, callback)

    def get_parameter_types(
        self, names: list[str], callback: Callable[..., Any] | None = None
    ) -> Future:
        """``GetParameterTypes.Response``: the type codes of ``names``."""
        request = _service_type("get_parameter_types").Request(names=list(names))
        return self._call("get_parameter_types", request, callback)

    def delete_parameters(
        self, names: list[str], callback: Callable[..., Any] | None = None
    ) -> Future:
        """Unset ``names`` (set them to NOT_SET, as rclpy's client does):
        ``SetParameters.Response``; only an undeclared-allowed node lets them go."""
        return self.set_parameters([Parameter(name) for name in names], callback=callback)

    def load_parameter_file(
        self,
        parameter_file: str,
        use_wildcard: bool = False,
        callback: Callable[..., Any] | None = None,
    ) -> Future:
        """Set every parameter of a parameter file (each section but ``/**``, with it too
        under ``use_wildcard``): ``SetParameters.Response``."""
        parameters = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters(list(parameters.values()), callback=callback)

    def load_parameter_file_atomically(
        self,
        parameter_file: str,
        use_wildcard: bool = False,
        callback: Callable[..., Any] | None = None,
    ) -> Future:
        """:meth:`load_parameter_file`, all or nothing."""
        parameters = parameter_dict_from_yaml_file(parameter_file, use_wildcard)
        return self.set_parameters_atomically(list(parameters.values()), callback=callback)

    def on_parameter_event(
        self,
        callback: Callable[[Any], Any],
        qos_profile: QoSProfile = qos_profile_parameter_events,
        callback_group: CallbackGroup | None = None,
    ) -> Subscription:
        """Call ``callback(ParameterEvent)`` for each event on ``/parameter_events``."""
        return self.node.create_subscription(
            interface("rcl_interfaces.msg", "ParameterEvent"),
            "/parameter_events",
            callback,
            qos_profile,
            callback_group=callback_group,
        )


def _messages(parameters: Sequence[Any]) -> list[Any]:
    return [p.to_parameter_msg() if isinstance(p, Parameter) else p for p in parameters]
