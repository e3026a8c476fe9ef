"""The robomodel node behind a client library's node: rclpy's ``Node.robomodel_node``, or
rospy's :func:`robomodel.clientlibs.rospy.robomodel_node` once ``init_node`` ran."""

from __future__ import annotations

import importlib
from typing import Any

__all__ = ["robomodel_node"]


def robomodel_node(node: Any, *, user: str) -> Any:
    """The :class:`robomodel.runtime.Node` of ``node`` (ROS 2 form), or of the rospy process
    (ROS 1 form: ``node`` is None). ``user`` names the caller in errors."""
    if node is not None:
        found = getattr(node, "robomodel_node", None)
        if found is None:
            raise TypeError(
                f"{user}: node must be an rclpy Node (one with .robomodel_node), "
                f"not {type(node).__name__}"
            )
        return found
    try:
        rospy = importlib.import_module("robomodel.clientlibs.rospy")
    except ModuleNotFoundError:
        raise RuntimeError(
            f"{user} without a node is ROS 1's form: it needs rospy.init_node() first "
            "(ROS 2: pass the rclpy node)"
        ) from None
    return rospy.robomodel_node()
