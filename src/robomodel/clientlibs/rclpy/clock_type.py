"""``rclpy.clock_type.ClockType``: which time a clock tells."""

from __future__ import annotations

import enum

__all__ = ["ClockType"]


class ClockType(enum.IntEnum):
    UNINITIALIZED = 0
    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3
