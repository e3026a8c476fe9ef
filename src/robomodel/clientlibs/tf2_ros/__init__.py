"""tf2_ros on robomodel: ``Buffer``, ``TransformListener``, ``TransformBroadcaster``,
``StaticTransformBroadcaster``, ``TransformRegistration`` and tf2's exceptions, in ROS 2's form (a node passed: an rclpy
``Node``) and ROS 1's (no node: the rospy process's)."""

from robomodel.clientlibs.tf2_ros._exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
    TypeException,
)
from robomodel.clientlibs.tf2_ros._transform_types import TransformRegistration
from robomodel.clientlibs.tf2_ros.buffer import Buffer
from robomodel.clientlibs.tf2_ros.static_transform_broadcaster import StaticTransformBroadcaster
from robomodel.clientlibs.tf2_ros.transform_broadcaster import TransformBroadcaster
from robomodel.clientlibs.tf2_ros.transform_listener import TransformListener

BufferInterface = Buffer  # tf2_ros's base of Buffer (user code type-hints with it)

__all__ = [
    "Buffer",
    "BufferInterface",
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "StaticTransformBroadcaster",
    "TimeoutException",
    "TransformBroadcaster",
    "TransformException",
    "TransformListener",
    "TransformRegistration",
    "TypeException",
]
