"""Between the client libraries' values and robomodel's TF layer: ``geometry_msgs/
TransformStamped`` messages of any flavour (rosidl's, genpy's, robomodel's own), times and
durations of rclpy and rospy (and plain seconds)."""

from __future__ import annotations

import importlib
from typing import Any

from robomodel.tf import TransformStamped

__all__ = ["duration_s", "from_message", "stamp_ns", "time_ns", "to_message"]


def stamp_ns(stamp: Any) -> int:
    """A message's time field (``sec``/``nanosec`` of ROS 2, ``secs``/``nsecs`` of ROS 1)."""
    if hasattr(stamp, "nanosec"):
        return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
    if hasattr(stamp, "nsecs"):
        return int(stamp.secs) * 1_000_000_000 + int(stamp.nsecs)
    return time_ns(stamp)


def _set_stamp(stamp: Any, ns: int) -> None:
    sec, nanosec = divmod(int(ns), 1_000_000_000)
    if hasattr(stamp, "nanosec"):
        stamp.sec, stamp.nanosec = sec, nanosec
    else:
        stamp.secs, stamp.nsecs = sec, nanosec


def time_ns(value: Any) -> int:
    """A lookup time [ns]: ``rclpy.time.Time`` (``nanoseconds``), ``rospy.Time`` (``to_nsec``),
    a stamp message, or seconds. 0 means the latest common time, as in tf2."""
    if value is None:
        return 0
    nanoseconds = getattr(value, "nanoseconds", None)
    if isinstance(nanoseconds, int):
        return nanoseconds
    to_nsec = getattr(value, "to_nsec", None)
    if callable(to_nsec):
        return int(to_nsec())
    if hasattr(value, "nanosec") or hasattr(value, "nsecs"):
        return stamp_ns(value)
    if isinstance(value, int | float):
        return round(float(value) * 1e9)
    raise TypeError(
        f"a tf2 time must be an rclpy.time.Time, a rospy.Time, a stamp message or seconds, "
        f"not {type(value).__name__}"
    )


def duration_s(value: Any) -> float:
    """A timeout [s]: ``rclpy.duration.Duration``, ``rospy.Duration`` or seconds."""
    if value is None:
        return 0.0
    nanoseconds = getattr(value, "nanoseconds", None)
    if isinstance(nanoseconds, int):
        return nanoseconds / 1e9
    to_sec = getattr(value, "to_sec", None)
    if callable(to_sec):
        return float(to_sec())
    if hasattr(value, "nanosec") or hasattr(value, "nsecs"):
        return stamp_ns(value) / 1e9
    if isinstance(value, int | float):
        return float(value)
    raise TypeError(
        "a tf2 timeout must be an rclpy.duration.Duration, a rospy.Duration or seconds, "
        f"not {type(value).__name__}"
    )


def from_message(msg: Any) -> TransformStamped:
    """A ``geometry_msgs/TransformStamped`` of any flavour as the TF layer's frozen value."""
    t, r = msg.transform.translation, msg.transform.rotation
    return TransformStamped(
        str(msg.header.frame_id),
        str(msg.child_frame_id),
        (float(t.x), float(t.y), float(t.z)),
        (float(r.x), float(r.y), float(r.z), float(r.w)),
        stamp_ns(msg.header.stamp),
    )


def to_message(transform: TransformStamped) -> Any:
    """The process's ``geometry_msgs.msg.TransformStamped`` (its client library's flavour)."""
    cls = importlib.import_module("geometry_msgs.msg").TransformStamped
    msg = cls()
    msg.header.frame_id = transform.frame_id
    _set_stamp(msg.header.stamp, transform.stamp_ns)
    msg.child_frame_id = transform.child_frame_id
    translation, rotation = msg.transform.translation, msg.transform.rotation
    translation.x, translation.y, translation.z = transform.translation_m
    rotation.x, rotation.y, rotation.z, rotation.w = transform.rotation_xyzw
    return msg
