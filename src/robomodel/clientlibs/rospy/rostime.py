"""rospy's ``Time`` and ``Duration`` (genpy's, with ``Time.now()``) and the node's ROS time:
wall time, or ``/clock`` when the parameter ``/use_sim_time`` is true."""

from __future__ import annotations

import time
from typing import Any

from robomodel.clientlibs import genpy
from robomodel.clientlibs.rospy import core

__all__ = ["Duration", "Time", "get_rostime", "get_time", "wallsleep"]


class Duration(genpy.Duration):
    """A span of time: ``rospy.Duration(secs, nsecs)``, ``Duration.from_sec(0.5)``."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"rospy.Duration[{self.to_nsec()}]"


class Time(genpy.Time):
    """A point in ROS time: ``rospy.Time.now()``, ``rospy.Time(secs, nsecs)``."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"rospy.Time[{self.to_nsec()}]"

    @staticmethod
    def now() -> Time:
        """The node's current ROS time (``/clock`` under ``/use_sim_time``)."""
        return get_rostime()

    @classmethod
    def from_seconds(cls, float_secs: float) -> Any:
        """:meth:`from_sec` under rospy's older name."""
        return cls.from_sec(float_secs)


def get_rostime() -> Time:
    """The node's current ROS time; ROSInitException before ``init_node``."""
    ns = core.state().node.get_clock().now_ns()
    return Time(ns // 1_000_000_000, ns % 1_000_000_000)


def get_time() -> float:
    """The node's current ROS time in seconds."""
    return core.state().node.get_clock().now_s()


def wallsleep(duration_s: float) -> None:
    """Sleep ``duration_s`` seconds of wall time (rospy's name)."""
    if duration_s > 0:
        time.sleep(duration_s)
