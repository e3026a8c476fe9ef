"""``rclpy.service.Service``: a robomodel service whose handler calls rclpy's
``callback(request, response)``."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.clock import Clock
    from robomodel.clientlibs.rclpy.qos import QoSProfile
    from robomodel.clientlibs.rclpy.service_introspection import (
        Introspection,
        ServiceIntrospectionState,
    )
    from robomodel.runtime.node import ServiceServer

__all__ = ["Service"]


class Service:
    """Answers ``srv_name`` (made by ``Node.create_service``)."""

    def __init__(
        self,
        server: ServiceServer,
        callback: Callable[[Any, Any], Any],
        callback_group: CallbackGroup,
        qos_profile: QoSProfile,
        introspection: Introspection,
    ) -> None:
        self.robomodel_service = server
        self._introspection = introspection
        self.srv_type = server.srv_type
        self.callback = callback
        self.callback_group = callback_group
        self.qos_profile = qos_profile

    @property
    def srv_name(self) -> str:
        return self.robomodel_service.name

    @property
    def service_name(self) -> str:
        return self.robomodel_service.name

    @property
    def handle(self) -> Any:
        not_offered("Service.handle (rcl's handle)")

    def send_response(self, response: Any, header: Any) -> None:
        not_offered("Service.send_response()", "return the response from the callback")

    def configure_introspection(
        self,
        clock: Clock,
        service_event_qos_profile: QoSProfile,
        introspection_state: ServiceIntrospectionState,
    ) -> None:
        """Publish this service's events on ``<service>/_service_event`` as the state says
        (stamped by ``clock``)."""
        self._introspection.configure(clock, service_event_qos_profile, introspection_state)

    def destroy(self) -> None:
        self._introspection.destroy()
        self.robomodel_service.destroy()

    def __enter__(self) -> Service:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy()
