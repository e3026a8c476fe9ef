"""``rclpy.impl.logging_severity``: the log severities (rcutils' values)."""

from __future__ import annotations

from robomodel.clientlibs.rclpy.logging import LoggingSeverity

__all__ = ["LoggingSeverity"]
