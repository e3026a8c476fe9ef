"""``tf2_ros.TransformBroadcaster``: ``sendTransform`` publishes on /tf (ROS 2:
``TransformBroadcaster(node, qos=100)``; ROS 1: ``TransformBroadcaster(queue_size=100)``)."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.tf2_ros._convert import from_message
from robomodel.clientlibs.tf2_ros._node import robomodel_node
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.tf_listener import to_msg

__all__ = ["TransformBroadcaster"]


def _transforms(transform: Any) -> list[Any]:
    """One ``geometry_msgs/TransformStamped`` or a list of them, as robomodel's messages."""
    items = transform if isinstance(transform, list | tuple) else [transform]
    return [to_msg(from_message(item)) for item in items]


class TransformBroadcaster:
    """tf2_ros's broadcaster on both wires."""

    def __init__(self, node: Any = None, qos: Any = 100, *, queue_size: int = 100) -> None:
        ros1 = node is None or isinstance(node, int)  # ROS 1's first argument: queue_size
        own = robomodel_node(None if ros1 else node, user="tf2_ros.TransformBroadcaster")
        depth = qos if isinstance(qos, int) else getattr(qos, "depth", 100)
        self._publisher = own.create_publisher(TFMessage, "/tf", depth)

    def sendTransform(self, transform: Any) -> None:
        """Publish one ``geometry_msgs/TransformStamped`` or a list of them on /tf."""
        self._publisher.publish(TFMessage(_transforms(transform)))
