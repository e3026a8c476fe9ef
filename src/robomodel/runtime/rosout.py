"""A node's ``/rosout``: its log lines, as roscpp and rclcpp publish them.

Every node publishes on ``/rosout`` from its start (so ``rostopic list`` / ``ros2 topic list``
show it, as for any ROS node): ``rosgraph_msgs/Log`` on a ROS 1 graph (roscpp's queue, not
latched; levels DEBUG 1, INFO 2, WARN 4, ERROR 8, FATAL 16, and the node's advertised topics),
``rcl_interfaces/msg/Log`` elsewhere (rcl's ``/rosout`` QoS: reliable, transient local, depth
1000; levels 10 to 50).

What is published: the records of the node's Python logger (``node.logger``) that logging lets
through (WARNING and up unless the application lowers the level), and the lines a launch prints
for the node (``[/node] text``, INFO), through :func:`publish_line`.
"""

from __future__ import annotations

import logging
import threading
from typing import TYPE_CHECKING, Any

from robomodel.runtime.qos import Durability, QoSProfile, Reliability

if TYPE_CHECKING:
    from robomodel.runtime.context import Context
    from robomodel.runtime.node import Node

__all__ = ["ROSOUT_QOS", "Rosout", "publish_line"]

ROSOUT_QOS = QoSProfile(1000, Durability.TRANSIENT_LOCAL, Reliability.RELIABLE)
_ROS1_QUEUE = 100
_ROS1_LEVELS = {logging.DEBUG: 1, logging.INFO: 2, logging.WARNING: 4, logging.ERROR: 8,
                logging.CRITICAL: 16}  # fmt: skip
_busy = threading.local()  # a record logged while publishing one is not published again


def _ros1_level(level: int) -> int:
    """rosgraph_msgs/Log's level of a Python level (the nearest one at or below it)."""
    best = 1
    for python_level, ros_level in sorted(_ROS1_LEVELS.items()):
        if level >= python_level:
            best = ros_level
    return best


class Rosout:
    """``node``'s /rosout publisher, and a logging handler on ``node.logger`` feeding it."""

    def __init__(self, node: Node) -> None:
        self.node = node
        self.ros1 = getattr(node.context, "bus", "") == "ros1"
        if self.ros1:
            from robomodel.runtime.msg.types.rosgraph_msgs import Log as RosgraphLog

            self._publisher: Any = node.create_publisher(RosgraphLog, "/rosout", _ROS1_QUEUE)
        else:
            from robomodel.runtime.msg.types.rcl_interfaces import Log

            self._publisher = node.create_publisher(Log, "/rosout", ROSOUT_QOS)
        self._handler = _Handler(self)
        node.logger.addHandler(self._handler)

    def publish(
        self, level: int, text: str, *, file: str = "", function: str = "", line: int = 0
    ) -> None:
        """Publish one log line at Python logging level ``level``."""
        if getattr(_busy, "on", False):
            return
        _busy.on = True
        try:
            node = self.node
            if self.ros1:
                from robomodel.runtime.msg.types.rosgraph_msgs import Log as RosgraphLog
                from robomodel.runtime.msg.types.std_msgs import Header

                topics = sorted({p.topic for p in node._publishers})
                msg: Any = RosgraphLog(
                    Header(stamp=node.now()), _ros1_level(level), node.fully_qualified_name,
                    text, file, function, line, topics,
                )  # fmt: skip
            else:
                from robomodel.runtime.msg.types.rcl_interfaces import Log

                msg = Log(node.now(), level, node.fully_qualified_name, text, file, function, line)
            self._publisher.publish(msg)
        finally:
            _busy.on = False

    def close(self) -> None:
        self.node.logger.removeHandler(self._handler)


class _Handler(logging.Handler):
    def __init__(self, rosout: Rosout) -> None:
        super().__init__()
        self.rosout = rosout

    def emit(self, record: logging.LogRecord) -> None:
        try:
            text = record.getMessage()
            self.rosout.publish(
                record.levelno, text, file=record.pathname, function=record.funcName,
                line=record.lineno or 0,
            )  # fmt: skip
        except Exception:  # logging must never raise into the code that logs
            self.handleError(record)


def publish_line(context: Context | None, node_name: str, text: str) -> None:
    """Publish a launch's line for node ``node_name`` (INFO) on that node's /rosout, when a node
    of that name lives in ``context`` (a node the launch runs in-process)."""
    if context is None:
        return
    for node in reversed(getattr(context, "nodes", ())):
        rosout = getattr(node, "rosout", None)
        if rosout is not None and node.fully_qualified_name == node_name:
            try:
                rosout.publish(logging.INFO, text)
            except Exception as exc:  # a line that cannot go out is still printed
                logging.getLogger("robomodel.runtime").debug("/rosout: %s", exc)
            return
