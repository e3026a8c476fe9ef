"""Another node's parameters through its parameter services (rclpy's AsyncParameterClient, but
blocking): what ``robomodel param`` and the viewer's Parameters panel use, for robomodel nodes
and real ROS 2 nodes alike."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg.types import rcl_interfaces as rcl
from robomodel.runtime.param_values import from_parameter_value, to_parameter_value
from robomodel.runtime.params import ParameterError, SetResult

if TYPE_CHECKING:
    from robomodel.runtime.context import Context

__all__ = ["ParameterClient"]


class ParameterClient:
    """The parameters of node ``node`` (a fully qualified name, ``/ns/name``)."""

    def __init__(self, context: Context, node: str, *, timeout_s: float = 2.0) -> None:
        self.context = context
        self.node = node if node.startswith("/") else f"/{node}"
        self.timeout_s = timeout_s

    def _call(self, service: str, srv_type: Any, request: Any) -> Any:
        return self.context.call_service(
            f"{self.node.rstrip('/')}/{service}", srv_type, request, self.timeout_s
        )

    def list_names(self, prefixes: Sequence[str] = (), depth: int = 0) -> list[str]:
        """Parameter names (``ros2 param list``), sorted."""
        reply = self._call(
            "list_parameters", rcl.ListParameters, rcl.ListParameters_Request(list(prefixes), depth)
        )
        return sorted(reply.result.names)

    def get(self, names: Sequence[str]) -> dict[str, Any]:
        """Values by name; ParameterError when one of them is not set."""
        reply = self._call(
            "get_parameters", rcl.GetParameters, rcl.GetParameters_Request(list(names))
        )
        if len(reply.values) != len(names):
            raise ParameterError(f"parameter(s) not set on {self.node}: {', '.join(names)}")
        try:
            return {n: from_parameter_value(v) for n, v in zip(names, reply.values, strict=True)}
        except ParameterError:
            raise ParameterError(
                f"parameter(s) not set on {self.node}: {', '.join(names)}"
            ) from None

    def describe(self, names: Sequence[str]) -> list[rcl.ParameterDescriptor]:
        reply = self._call(
            "describe_parameters",
            rcl.DescribeParameters,
            rcl.DescribeParameters_Request(list(names)),
        )
        return list(reply.descriptors)

    def set(self, values: Mapping[str, Any]) -> list[SetResult]:
        """Set each parameter on its own (``ros2 param set``); one result per parameter."""
        parameters = [rcl.Parameter(n, to_parameter_value(v)) for n, v in values.items()]
        reply = self._call(
            "set_parameters", rcl.SetParameters, rcl.SetParameters_Request(parameters)
        )
        return [SetResult(r.successful, r.reason) for r in reply.results]

    def set_atomically(self, values: Mapping[str, Any]) -> SetResult:
        """Set all parameters or none (``ros2 param load``)."""
        parameters = [rcl.Parameter(n, to_parameter_value(v)) for n, v in values.items()]
        reply = self._call(
            "set_parameters_atomically",
            rcl.SetParametersAtomically,
            rcl.SetParametersAtomically_Request(parameters),
        )
        return SetResult(reply.result.successful, reply.result.reason)
