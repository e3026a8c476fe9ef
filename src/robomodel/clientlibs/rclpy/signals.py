"""``rclpy.signals``: which signal handlers ``rclpy.init`` installs. robomodel's rclpy installs
none (Ctrl-C is Python's KeyboardInterrupt in the spinning thread), which is
``SignalHandlerOptions.NO``; asking for handlers raises NotImplementedError."""

from __future__ import annotations

import enum

__all__ = ["SignalHandlerOptions"]


class SignalHandlerOptions(enum.IntEnum):
    NO = 0
    SIGINT = 1
    SIGTERM = 2
    ALL = 3
