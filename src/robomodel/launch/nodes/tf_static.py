"""``tf``/``tf2_ros`` ``static_transform_publisher``: both argument orders.

``x y z yaw pitch roll frame_id child_frame_id [period_ms]`` (Euler, ZYX) or
``x y z qx qy qz qw frame_id child_frame_id [period_ms]``; tf's version takes the period in
milliseconds (and publishes on /tf at that rate), tf2_ros's publishes once on /tf_static
(latched). Bad arguments end the node with exit code 1 and the usage, as the real one.
"""

from __future__ import annotations

import math

from robomodel.launch.nodes.base import NodeContext, RunningNode, register
from robomodel.launch.nodes.state import InProcessNode

__all__ = ["parse_static_transform_args", "start_transform_publisher"]

_USAGE = (
    "static_transform_publisher x y z yaw pitch roll frame_id child_frame_id [period_in_ms]\n"
    "OR\n"
    "static_transform_publisher x y z qx qy qz qw frame_id child_frame_id [period_in_ms]"
)


def _quat_from_ypr(yaw: float, pitch: float, roll: float) -> tuple[float, float, float, float]:
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def parse_static_transform_args(
    args: tuple[str, ...] | list[str], with_period: bool
) -> tuple[tuple[float, float, float], tuple[float, float, float, float], str, str, float | None]:
    """``(xyz, xyzw, frame_id, child_frame_id, period_s)``; ValueError with the usage."""
    words = [a for a in args if ":=" not in a]
    extra = 1 if with_period else 0
    try:
        if len(words) == 8 + extra:
            x, y, z, yaw, pitch, roll = (float(w) for w in words[:6])
            quat = _quat_from_ypr(yaw, pitch, roll)
            frames = words[6:8]
        elif len(words) == 9 + extra:
            x, y, z, qx, qy, qz, qw = (float(w) for w in words[:7])
            norm = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
            if norm == 0.0:
                raise ValueError("the quaternion is zero")
            quat = (qx / norm, qy / norm, qz / norm, qw / norm)
            frames = words[7:9]
        else:
            raise ValueError(f"{len(words)} arguments")
        period = float(words[-1]) / 1000.0 if with_period else None
    except ValueError as exc:
        raise ValueError(f"{exc}\nUsage: {_USAGE}") from None
    if frames[0].strip("/") == frames[1].strip("/"):
        raise ValueError(
            f"target_frame and source_frame are the same ({frames[0]}), this cannot work"
        )
    return (x, y, z), quat, frames[0], frames[1], period


class _Holder:
    def __init__(self, node: object) -> None:
        self.node = node


def start_transform_publisher(
    ctx: NodeContext,
    xyz: tuple[float, float, float],
    quat_xyzw: tuple[float, float, float, float],
    parent: str,
    child: str,
    period_s: float | None = None,
) -> RunningNode:
    """A static_transform_publisher node: ``parent`` -> ``child`` latched on /tf_static, or,
    with ``period_s`` (tf's ROS 1 node), republished on /tf every period."""
    from robomodel.runtime.msg import (
        Header,
        Quaternion,
        TFMessage,
        Transform,
        TransformStamped,
        Vector3,
    )
    from robomodel.runtime.qos import latched

    node = ctx.runtime.create_node(
        ctx.spec.name or "static_transform_publisher",
        ctx.namespace,
        remappings=ctx.remappings,
    )
    stamped = TransformStamped(
        Header(node.now(), parent), child, Transform(Vector3(*xyz), Quaternion(*quat_xyzw))
    )
    if period_s is not None:
        pub = node.create_publisher(TFMessage, "/tf", 10)
        node.create_timer(period_s, lambda: pub.publish(TFMessage([stamped])))
    else:
        pub = node.create_publisher(TFMessage, "/tf_static", latched())
        pub.publish(TFMessage([stamped]))
    return InProcessNode(_Holder(node))


def _start(ctx: NodeContext, with_period: bool) -> RunningNode:
    xyz, quat, parent, child, period = parse_static_transform_args(ctx.spec.args, with_period)
    period_s = (period or 0.1) if with_period else None
    return start_transform_publisher(ctx, xyz, quat, parent, child, period_s)


@register(
    "ros1",
    "tf2_ros",
    "static_transform_publisher",
    purpose="a static transform on /tf_static (latched)",
)
def tf2_static(ctx: NodeContext) -> RunningNode:
    return _start(ctx, with_period=False)


@register(
    "ros1",
    "tf",
    "static_transform_publisher",
    purpose="a transform republished on /tf every period_in_ms (tf's version)",
)
def tf_static(ctx: NodeContext) -> RunningNode:
    return _start(ctx, with_period=True)
