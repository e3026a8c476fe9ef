"""A node's parameter services and ``/parameter_events``, as rclcpp's ParameterService offers
them, so that ``ros2 param`` and ``robomodel param`` work on every robomodel node.

Semantics follow rclcpp (parameter_service.cpp, node_parameters.cpp): ``get_parameters`` and
``describe_parameters`` answer nothing when one of the names is not declared;
``set_parameters`` sets each parameter on its own and answers one result per parameter;
``set_parameters_atomically`` sets all or none; ``list_parameters`` filters by prefixes and
depth with ``.`` as the separator. A declaration and every successful set is published on
``/parameter_events``.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg.types import rcl_interfaces as rcl
from robomodel.runtime.param_values import from_parameter_value, to_parameter_value, type_code
from robomodel.runtime.params import ParameterError, ParameterStore
from robomodel.runtime.qos import QoSProfile

if TYPE_CHECKING:
    from robomodel.runtime.node import Node

__all__ = ["PARAMETER_EVENTS_QOS", "ParameterServices", "list_names"]

log = logging.getLogger("robomodel.runtime")

# rclcpp's ParameterEventsQoS: reliable, volatile, keep last 1000.
PARAMETER_EVENTS_QOS = QoSProfile(depth=1000)
_SEPARATOR = "."


def list_names(names: list[str], prefixes: list[str], depth: int) -> rcl.ListParametersResult:
    """rclcpp ``NodeParameters::list_parameters`` over ``names``."""
    result = rcl.ListParametersResult()
    recursive = depth == rcl.ListParameters_Request.DEPTH_RECURSIVE
    for name in names:
        get_all = not prefixes and (recursive or name.count(_SEPARATOR) < depth)

        def matches(prefix: str, name: str = name) -> bool:
            if name == prefix:
                return True
            if name.startswith(prefix + _SEPARATOR):
                return recursive or name[len(prefix) :].count(_SEPARATOR) < depth
            return False

        if get_all or any(matches(p) for p in prefixes):
            result.names.append(name)
            if _SEPARATOR in name:
                prefix = name.rsplit(_SEPARATOR, 1)[0]
                if prefix not in result.prefixes:
                    result.prefixes.append(prefix)
    return result


class ParameterServices:
    """The six services of one node and its parameter event publisher."""

    def __init__(self, node: Node) -> None:
        self._node = node
        self._store: ParameterStore = node.parameters
        self._events = node.create_publisher(
            rcl.ParameterEvent, "/parameter_events", PARAMETER_EVENTS_QOS
        )
        base = node.fully_qualified_name.rstrip("/")
        handlers: list[tuple[str, Any, Callable[[Any], Any]]] = [
            ("describe_parameters", rcl.DescribeParameters, self._describe),
            ("get_parameter_types", rcl.GetParameterTypes, self._types),
            ("get_parameters", rcl.GetParameters, self._get),
            ("list_parameters", rcl.ListParameters, self._list),
            ("set_parameters", rcl.SetParameters, self._set),
            ("set_parameters_atomically", rcl.SetParametersAtomically, self._set_atomically),
        ]
        self.services = []
        try:
            for name, srv_type, handler in handlers:
                self.services.append(node.create_service(srv_type, f"{base}/{name}", handler))
        except RobomodelError:  # a second node of the same name in this process (as rcl warns)
            log.warning(
                "a node named %s already offers parameter services in this process; the "
                "parameters of this one are not reachable over the bus",
                node.fully_qualified_name,
            )

    def publish_event(
        self, *, new: Mapping[str, Any] | None = None, changed: Mapping[str, Any] | None = None
    ) -> None:
        """Publish a ParameterEvent; a ``changed`` value of None is a deleted parameter."""
        changed = changed or {}
        deleted = [rcl.Parameter(n, rcl.ParameterValue()) for n, v in changed.items() if v is None]

        def params(values: Mapping[str, Any] | None) -> list[rcl.Parameter]:
            return [
                rcl.Parameter(n, to_parameter_value(v))
                for n, v in (values or {}).items()
                if v is not None
            ]

        self._events.publish(
            rcl.ParameterEvent(
                stamp=self._node.now(),
                node=self._node.fully_qualified_name,
                new_parameters=params(new),
                changed_parameters=params(changed),
                deleted_parameters=deleted,
            )
        )

    # -- handlers ------------------------------------------------------------------------------
    def _get(self, request: rcl.GetParameters_Request) -> rcl.GetParameters_Response:
        store = self._store
        if not all(store.has(n) for n in request.names):
            return rcl.GetParameters_Response()
        return rcl.GetParameters_Response([to_parameter_value(store.get(n)) for n in request.names])

    def _types(self, request: rcl.GetParameterTypes_Request) -> rcl.GetParameterTypes_Response:
        store = self._store
        return rcl.GetParameterTypes_Response(
            bytes(type_code(store.get(n)) if store.has(n) else 0 for n in request.names)
        )

    def _describe(self, request: rcl.DescribeParameters_Request) -> rcl.DescribeParameters_Response:
        store = self._store
        if not all(store.has(n) for n in request.names):
            return rcl.DescribeParameters_Response()
        return rcl.DescribeParameters_Response(
            [
                rcl.ParameterDescriptor(
                    name=n,
                    type=type_code(store.get(n)),
                    description=store.describe(n),
                    read_only=store.is_read_only(n),
                )
                for n in request.names
            ]
        )

    def _list(self, request: rcl.ListParameters_Request) -> rcl.ListParameters_Response:
        names = self._store.names()
        return rcl.ListParameters_Response(
            list_names(names, list(request.prefixes), int(request.depth))
        )

    def _set_values(
        self, parameters: list[rcl.Parameter]
    ) -> dict[str, Any] | rcl.SetParametersResult:
        values: dict[str, Any] = {}
        for parameter in parameters:
            if parameter.value.type == 0:  # PARAMETER_NOT_SET: unset it (ParameterStore.set)
                values[parameter.name] = None
                continue
            try:
                values[parameter.name] = from_parameter_value(parameter.value)
            except ParameterError:
                return rcl.SetParametersResult(
                    False, f"parameter '{parameter.name}' has an unknown type"
                )
        return values

    def _set(self, request: rcl.SetParameters_Request) -> rcl.SetParameters_Response:
        results = []
        for parameter in request.parameters:
            results.append(self._apply([parameter]))
        return rcl.SetParameters_Response(results)

    def _set_atomically(
        self, request: rcl.SetParametersAtomically_Request
    ) -> rcl.SetParametersAtomically_Response:
        return rcl.SetParametersAtomically_Response(self._apply(list(request.parameters)))

    def _apply(self, parameters: list[rcl.Parameter]) -> rcl.SetParametersResult:
        values = self._set_values(parameters)
        if isinstance(values, rcl.SetParametersResult):
            return values
        result = self._node.set_parameters(values)
        return rcl.SetParametersResult(result.successful, result.reason)
