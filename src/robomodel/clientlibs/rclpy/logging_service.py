"""``rclpy.logging_service``: a node's logger levels read and set over services
(``Node(enable_logger_service=True)``): ``<node>/get_logger_levels`` and
``<node>/set_logger_levels`` of rcl_interfaces, as rclpy serves them."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.rclpy import logging
from robomodel.clientlibs.rclpy._support import interface
from robomodel.clientlibs.rclpy.qos import qos_profile_services_default

__all__ = ["LoggingService"]


class LoggingService:
    """Serves the logger levels of this process on ``node``'s two services."""

    def __init__(self, node: Any) -> None:  # an rclpy Node (which makes this service)
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
