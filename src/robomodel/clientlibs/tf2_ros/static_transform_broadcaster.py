"""``tf2_ros.StaticTransformBroadcaster``: /tf_static, latched (transient local, depth 1),
each ``sendTransform`` publishing every static transform sent so far, newest per child frame,
as tf2_ros keeps its ``net_message`` (ROS 2: ``StaticTransformBroadcaster(node)``; ROS 1:
``StaticTransformBroadcaster()``)."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.tf2_ros._node import robomodel_node
from robomodel.clientlibs.tf2_ros.transform_broadcaster import _transforms
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.qos import Durability, QoSProfile

__all__ = ["StaticTransformBroadcaster"]


class StaticTransformBroadcaster:
    """tf2_ros's static broadcaster on both wires."""

    def __init__(self, node: Any = None, qos: Any = None) -> None:
        own = robomodel_node(node, user="tf2_ros.StaticTransformBroadcaster")
        self._publisher = own.create_publisher(
            TFMessage, "/tf_static", QoSProfile(1, Durability.TRANSIENT_LOCAL)
        )
        self._net: dict[str, Any] = {}  # child frame -> its newest transform

    def sendTransform(self, transform: Any) -> None:
        """Add (or replace, per child frame) static transforms and publish them all."""
        for item in _transforms(transform):
            self._net[item.child_frame_id] = item
        self._publisher.publish(TFMessage(list(self._net.values())))
