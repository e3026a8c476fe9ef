"""tf's ``TransformBroadcaster``: transforms on ``/tf`` from the rospy node of this process."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

__all__ = ["TransformBroadcaster"]


def stamp_ns(stamp: Any) -> int:
    """Nanoseconds of a ROS 1 time (``secs``/``nsecs``) or a ROS 2 one (``sec``/``nanosec``)."""
    if hasattr(stamp, "to_nsec"):
        return int(stamp.to_nsec())
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


class TransformBroadcaster:
    """Publishes transforms on ``/tf`` (``tf2_msgs/TFMessage``, ROS 1's ``tf/tfMessage``)."""

    def __init__(self, queue_size: int = 100) -> None:
        from robomodel.clientlibs.rospy.core import robomodel_node
        from robomodel.runtime.msg import TFMessage

        self._publisher = robomodel_node().create_publisher(TFMessage, "/tf", queue_size)

    def sendTransform(
        self,
        translation: Sequence[float],
        rotation: Sequence[float],
        time: Any,
        child: str,
        parent: str,
    ) -> None:
        """Publish the pose of frame ``child`` in frame ``parent`` at ``time``: ``translation``
        [m] and ``rotation`` as a quaternion ``[x, y, z, w]``."""
        from robomodel.runtime.msg import (
            Header,
            Quaternion,
            Time,
            Transform,
            TransformStamped,
            Vector3,
        )

        ns = stamp_ns(time)
        x, y, z = (float(v) for v in translation)
        qx, qy, qz, qw = (float(v) for v in rotation)
        msg = TransformStamped(
            Header(Time(ns // 1_000_000_000, ns % 1_000_000_000), parent),
            child,
            Transform(Vector3(x, y, z), Quaternion(qx, qy, qz, qw)),
        )
        self.sendTransformMessage(msg)

    def sendTransformMessage(self, transform: Any) -> None:
        """Publish a ``geometry_msgs/TransformStamped`` (or a list of them)."""
        from robomodel.runtime.msg import TFMessage

        transforms = transform if isinstance(transform, (list, tuple)) else [transform]
        self._publisher.publish(TFMessage([_own(t) for t in transforms]))


def _own(transform: Any) -> Any:
    """A TransformStamped of robomodel's own classes, whichever face the caller's is."""
    from robomodel.runtime.msg import (
        Header,
        Quaternion,
        Time,
        Transform,
        TransformStamped,
        Vector3,
    )

    if type(transform) is TransformStamped:
        return transform
    ns = stamp_ns(transform.header.stamp)
    t, r = transform.transform.translation, transform.transform.rotation
    return TransformStamped(
        Header(Time(ns // 1_000_000_000, ns % 1_000_000_000), transform.header.frame_id),
        transform.child_frame_id,
        Transform(Vector3(t.x, t.y, t.z), Quaternion(r.x, r.y, r.z, r.w)),
    )
