"""rospy's ``Service``, ``ServiceProxy`` and ``wait_for_service`` on robomodel's ROS 1
services (TCPROS, registered with the master; ``rosservice`` sees and calls them)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.exceptions import (
    ROSException,
    ROSInterruptException,
    ServiceException,
)
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Service as ServiceType
from robomodel.runtime.transport.base import OnReceivingThread

__all__ = ["Service", "ServiceProxy", "wait_for_service"]

CALL_TIMEOUT_S = 24 * 3600.0  # rospy's calls wait as long as the provider takes
_WAIT_POLL_S = 0.1


def _check_class(service_class: Any, name: str) -> type[ServiceType]:
    if not (
        isinstance(service_class, type)
        and isinstance(getattr(service_class, "Request", None), type)
        and isinstance(getattr(service_class, "Response", None), type)
        and bool(getattr(service_class, "__typename__", ""))
    ):
        raise ValueError(
            f"service {name}: service_class must be a service class"
            f" (from rospy_tutorials.srv import AddTwoInts), got {service_class!r}"
        )
    found: type[ServiceType] = service_class
    return found


def _request_class(service_class: type[ServiceType]) -> type[Message]:
    return getattr(service_class, "_request_class", None) or service_class.Request


def _response_class(service_class: type[ServiceType]) -> type[Message]:
    return getattr(service_class, "_response_class", None) or service_class.Response


def _same_type(value: Any, cls: type[Message]) -> bool:
    return isinstance(value, Message) and type(value).__typename__ == cls.__typename__


def response_of(answer: Any, response_class: Any) -> Message:
    """The handler's answer as a response, as rospy reads it: a response as it is, a dict as
    keywords, a list or tuple as positional fields, anything else as the one field."""
    if _same_type(answer, response_class):
        return answer  # type: ignore[no-any-return]
    if answer is None:
        raise ServiceException("service handler returned None")
    try:
        if isinstance(answer, dict):
            made: Message = response_class(**answer)
        elif isinstance(answer, (list, tuple)):
            made = response_class(*answer)
        else:
            made = response_class(answer)
    except (TypeError, AttributeError) as exc:
        raise ServiceException(f"handler returned invalid value: {exc}") from None
    return made


class Service:
    """Answers ``name`` with ``handler(request)``, as rospy on the thread of the client's
    connection: calls from several clients are answered at once."""

    def __init__(
        self,
        name: str,
        service_class: Any,
        handler: Callable[[Any], Any],
        buff_size: int = 65536,
        error_handler: Callable[..., Any] | None = None,
    ) -> None:
        node_state = core.state()
        self.service_class = _check_class(service_class, name)
        self.request_class = _request_class(self.service_class)
        self.response_class = _response_class(self.service_class)
        self.resolved_name = node_state.resolve(name)
        self.handler = handler
        self._error_handler = error_handler
        self._server: Any = node_state.node.create_service(
            self.service_class, self.resolved_name, OnReceivingThread(self._answer)
        )

    def _answer(self, request: Any) -> Message:
        try:
            return response_of(self.handler(request), self.response_class)
        except Exception as exc:
            if self._error_handler is not None:
                self._error_handler(exc, type(exc), exc.__traceback__)
            core.logerr(f"Error processing request: {exc}")
            raise ServiceException(f"error processing request: {exc}") from None

    def shutdown(self, reason: str = "") -> None:
        """Stop offering the service."""
        if self._server is not None:
            self._server.destroy()
            self._server = None

    unregister = shutdown

    def spin(self) -> None:
        """Block until the node shuts down (rospy's ``Service.spin``)."""
        from robomodel.clientlibs.rospy.client import spin

        spin()


class ServiceProxy:
    """Calls service ``name``: ``proxy(a, b)``, ``proxy(request)`` or ``proxy(a=1, b=2)``.
    ServiceException when no provider answers or the provider answers an error. ``headers``
    go into the connection header, which the provider's request carries as
    ``_connection_header``; the response carries the provider's."""

    def __init__(
        self,
        name: str,
        service_class: Any,
        persistent: bool = False,
        headers: Any = None,
    ) -> None:
        self.service_class = _check_class(service_class, name)
        self.request_class = _request_class(self.service_class)
        self.response_class = _response_class(self.service_class)
        self.resolved_name = core.resolve_name(name)
        self.persistent = persistent  # every call opens its connection: the same answers
        self.headers = {str(k): str(v) for k, v in (headers or {}).items()}

    def __call__(self, *args: Any, **kwds: Any) -> Any:
        return self.call(*args, **kwds)

    def call(self, *args: Any, **kwds: Any) -> Any:
        """The response to the request made of the arguments."""
        if len(args) == 1 and not kwds and _same_type(args[0], self.request_class):
            request = args[0]
        else:
            try:
                request = self.request_class(*args, **kwds)
            except TypeError as exc:
                raise TypeError(
                    f"service {self.resolved_name}: cannot make a request of the arguments: {exc}"
                ) from None
        from robomodel.runtime.transport.base import ServiceCallError
        from robomodel.runtime.transport.ros1.ros1_types import Ros1TypeError, ros1_service_type
        from robomodel.runtime.transport.ros1.services import call_service

        node_state = core.current()
        try:
            if self.headers:  # over the wire, where the connection header travels
                kind = ros1_service_type(self.service_class)
                return call_service(
                    _master_uri(),
                    core.get_name(),
                    self.resolved_name,
                    kind,
                    request,
                    CALL_TIMEOUT_S,
                    header_fields=self.headers,
                )
            if node_state is not None:  # this process's own services are called in place
                return node_state.context.transport.call_service(
                    self.resolved_name,
                    self.service_class,
                    request,
                    CALL_TIMEOUT_S,
                    node=node_state.caller_id,
                )
            # rospy calls services without init_node (ros_tutorials' add_two_ints_client does)
            kind = ros1_service_type(self.service_class)
            return call_service(
                _master_uri(), core.get_name(), self.resolved_name, kind, request, CALL_TIMEOUT_S
            )
        except Ros1TypeError as exc:
            raise ServiceException(f"service [{self.resolved_name}]: {exc}") from None
        except ServiceCallError as exc:
            raise ServiceException(
                f"service [{self.resolved_name}] responded with an error: {exc}"
            ) from None

    def wait_for_service(self, timeout: float | None = None) -> None:
        wait_for_service(self.resolved_name, timeout)

    def close(self) -> None:
        """Nothing stays open between calls."""


def _master_uri() -> str:
    """The master of the node, or (before ``init_node``) of ``ROS_MASTER_URI``/``__master:=``."""
    node_state = core.current()
    if node_state is not None:
        return str(node_state.context.transport.master_uri)  # type: ignore[attr-defined]
    import sys

    from robomodel.clientlibs.rospy.names import parse_command_line
    from robomodel.runtime.transport.ros1.names import master_uri

    return master_uri(parse_command_line(sys.argv).special.get("__master"))


def _provider_answers(name: str) -> bool:
    from robomodel.runtime.transport.base import ServiceCallError
    from robomodel.runtime.transport.ros1.services import probe_service_type

    try:
        probe_service_type(_master_uri(), core.get_name(), name, timeout_s=2.0)
    except ServiceCallError:
        return False
    return True


def wait_for_service(service: str, timeout: float | None = None) -> None:
    """Wait until a provider of ``service`` answers. ROSException after ``timeout`` seconds,
    ROSInterruptException when the node shuts down first."""
    name = core.resolve_name(service)
    end = None if timeout is None else time.monotonic() + float(timeout)
    stop = core.shutdown_event()
    while not _provider_answers(name):
        if stop.is_set():
            raise ROSInterruptException("rospy shutdown")
        if end is not None and time.monotonic() >= end:
            raise ROSException(f"timeout exceeded while waiting for service {name}")
        stop.wait(_WAIT_POLL_S)
