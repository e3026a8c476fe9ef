"""``rclpy.logging_service``: a node's logger levels read and set over services
(``Node(enable_logger_service=True)``): ``<node>/get_logger_levels`` and
``<node>/set_logger_levels`` of rcl_interfaces, as rclpy serves them."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from robomodel.clientlibs.rclpy import logging
from robomodel.clientlibs.rclpy._support import interface
from robomodel.clientlibs.rclpy.qos import QoSProfile, qos_profile_services_default

__all__ = ["LoggingService", "ServiceMaker"]


class ServiceMaker(Protocol):
    """What the logger service needs of its rclpy Node: its name and ``create_service``."""

    def get_name(self) -> str: ...

    def create_service(
        self, srv_type: Any, srv_name: str, callback: Callable[[Any, Any], Any], *,
        qos_profile: QoSProfile = ...,
    ) -> object: ...  # fmt: skip


class LoggingService:
    """Serves the logger levels of this process on ``node``'s two services."""

    def __init__(self, node: ServiceMaker) -> None:
        name = node.get_name()
        node.create_service(
            interface("rcl_interfaces.srv", "GetLoggerLevels"),
            f"{name}/get_logger_levels",
            self._get_logger_levels,
            qos_profile=qos_profile_services_default,
        )
        node.create_service(
            interface("rcl_interfaces.srv", "SetLoggerLevels"),
            f"{name}/set_logger_levels",
            self._set_logger_levels,
            qos_profile=qos_profile_services_default,
        )

    @staticmethod
    def _get_logger_levels(request: Any, response: Any) -> Any:
        """Each named logger's own level (0, UNSET, for one that has none)."""
        level_class = interface("rcl_interfaces.msg", "LoggerLevel")
        for name in request.names:
            level = int(logging.get_logger_level(name))
            response.levels.append(level_class(name=name, level=level))
        return response

    @staticmethod
    def _set_logger_levels(request: Any, response: Any) -> Any:
        """Set each level; an invalid one is refused in its result, as rclpy refuses it."""
        result_class = interface("rcl_interfaces.msg", "SetLoggerLevelsResult")
        for level in request.levels:
            try:
                logging.set_logger_level(level.name, level.level, detailed_error=True)
            except ValueError:
                response.results.append(
                    result_class(successful=False, reason="Failed reason: Invalid logger level.")
                )
                continue
            response.results.append(result_class(successful=True))
        return response
