"""tf2_ros's TransformListener: fills a TF buffer from /tf and /tf_static."""

from __future__ import annotations

from collections.abc import Callable

from robomodel.runtime.clock import BackwardJumps
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.msg import TransformStamped as TransformStampedMsg
from robomodel.runtime.node import Node
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.tf import BufferCore, TransformStamped

__all__ = ["ClockJumps", "TransformListener", "from_msg", "to_msg"]

AUTHORITY = "default_authority"  # what rclpy's listener records


def from_msg(msg: TransformStampedMsg) -> TransformStamped:
    """A ``geometry_msgs/TransformStamped`` message as the TF layer's frozen value."""
    t, r = msg.transform.translation, msg.transform.rotation
    return TransformStamped(
        msg.header.frame_id,
        msg.child_frame_id,
        (t.x, t.y, t.z),
        (r.x, r.y, r.z, r.w),
        msg.header.stamp.to_nanoseconds(),
    )


def to_msg(transform: TransformStamped) -> TransformStampedMsg:
    from robomodel.runtime.msg import Header, Quaternion, Time, Transform, Vector3

    x, y, z = transform.translation_m
    qx, qy, qz, qw = transform.rotation_xyzw
    return TransformStampedMsg(
        Header(Time(transform.sec, transform.nanosec), transform.frame_id),
        transform.child_frame_id,
        Transform(Vector3(x, y, z), Quaternion(qx, qy, qz, qw)),
    )


class TransformListener:
    """Subscribes /tf (depth 100) and /tf_static (transient local, depth 100), as tf2_ros does."""

    def __init__(self, node: Node, buffer: BufferCore | None = None) -> None:
        self.buffer = buffer if buffer is not None else BufferCore()
        self._jumps = ClockJumps(node, self.buffer.clear)
        node.create_subscription(TFMessage, "/tf", self._dynamic, 100)
        node.create_subscription(
            TFMessage, "/tf_static", self._static, QoSProfile(100, Durability.TRANSIENT_LOCAL)
        )

    def _dynamic(self, msg: TFMessage) -> None:
        self._jumps.check()
        for transform in msg.transforms:
            self.buffer.set_transform(from_msg(transform), AUTHORITY, False)

    def _static(self, msg: TFMessage) -> None:
        self._jumps.check()
        for transform in msg.transforms:
            self.buffer.set_transform(from_msg(transform), AUTHORITY, True)


class ClockJumps:
    """tf2_ros's listeners' check, made at each message: when the node's clock went back since
    the last one (a simulation reset, a bag played again, ``use_sim_time`` switched on), the
    buffer's dynamic transforms are forgotten (``clear``), their stamps being of a time that is
    no more; with tf2_ros's warning."""

    def __init__(self, node: Node, clear: Callable[[], None]) -> None:
        self._node = node
        self._clear = clear
        self._jumps = BackwardJumps(lambda: node.get_clock().now_ns())

    def check(self) -> None:
        if back_ns := self._jumps.back_ns():
            self._node.logger.warning("Detected jump back in time of %gs. Clearing TF buffer.", back_ns / 1e9)  # fmt: skip
            self._clear()
