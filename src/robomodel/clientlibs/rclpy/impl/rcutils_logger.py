"""``rclpy.impl.rcutils_logger``: the named logger class and its severities."""

from __future__ import annotations

from robomodel.clientlibs.rclpy.logging import LoggingSeverity, RcutilsLogger

__all__ = ["LoggingSeverity", "RcutilsLogger"]
