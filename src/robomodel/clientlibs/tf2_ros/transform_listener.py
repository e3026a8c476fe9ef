"""``tf2_ros.TransformListener``: fills a :class:`~.buffer.Buffer` from /tf and /tf_static.

ROS 2's form ``TransformListener(buffer, node)`` subscribes through the rclpy node; ROS 1's
``TransformListener(buffer)`` through the rospy process's node. The subscriptions are
tf2_ros's: /tf with depth 100, /tf_static transient-local (latched) with depth 100.
"""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.tf2_ros._node import robomodel_node
from robomodel.clientlibs.tf2_ros.buffer import Buffer
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.tf_listener import AUTHORITY, ClockJumps, from_msg

__all__ = ["TransformListener"]


class TransformListener:
    """tf2_ros's listener on both wires (see the module docstring)."""

    def __init__(
        self,
        buffer: Buffer,
        node: Any = None,
        *args: Any,
        spin_thread: bool = False,
        qos: Any = None,
        static_qos: Any = None,
        **kwargs: Any,
    ) -> None:
        if spin_thread:
            raise NotImplementedError(
                "tf2_ros.TransformListener(spin_thread=True) is not offered by robomodel: the "
                "listener's callbacks run in the node's executor; spin the node"
            )
        ros1 = node is None or isinstance(node, int)  # ROS 1's second argument: queue_size
        self.buffer = buffer
        self._node = robomodel_node(None if ros1 else node, user="tf2_ros.TransformListener")
        self._jumps = ClockJumps(self._node, buffer.clear)
        depth = 100
        self._subscriptions = [
            self._node.create_subscription(TFMessage, "/tf", self._dynamic, depth),
            self._node.create_subscription(
                TFMessage,
                "/tf_static",
                self._static,
                QoSProfile(depth, Durability.TRANSIENT_LOCAL),
            ),
        ]

    def _dynamic(self, msg: TFMessage) -> None:
        self._jumps.check()
        for transform in msg.transforms:
            self.buffer._insert(from_msg(transform), AUTHORITY, False)

    def _static(self, msg: TFMessage) -> None:
        self._jumps.check()
        for transform in msg.transforms:
            self.buffer._insert(from_msg(transform), AUTHORITY, True)

    def unregister(self) -> None:
        """Stop listening (ROS 1's ``unregister``; ROS 2 destroys the subscriptions)."""
        for subscription in self._subscriptions:
            subscription.destroy()
        self._subscriptions = []
