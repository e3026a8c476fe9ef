"""roscore's ``rosout`` node: subscribes ``/rosout`` and republishes every line on
``/rosout_agg``, as ``rosout.cpp`` does (a node named ``/rosout``, itself without a /rosout
publisher: ``ros::init_options::NoRosout``). robomodel runs it where it hosts a ROS 1 master
(``robomodel master``, and a launch that starts one), so the graph is roscore's. It does not
write roscore's ``rosout.log``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg.nav_msgs import RosgraphLog

if TYPE_CHECKING:
    from robomodel.runtime.context import Context

__all__ = ["RosoutAggregator"]

_QUEUE = 100  # rosout.cpp: subscribe("/rosout", 100, ...), advertise("/rosout_agg", 0)


class RosoutAggregator:
    """The ``/rosout`` node on ``context`` (a ROS 1 bus)."""

    def __init__(self, context: Context) -> None:
        self.node = context.create_node("rosout", enable_rosout=False)
        self._agg = self.node.create_publisher(RosgraphLog, "/rosout_agg", _QUEUE)
        self.node.create_subscription(RosgraphLog, "/rosout", self._on_line, _QUEUE)

    def _on_line(self, msg: Any) -> None:
        self._agg.publish(msg)

    def close(self) -> None:
        self.node.destroy()
