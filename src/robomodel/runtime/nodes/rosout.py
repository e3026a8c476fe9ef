"""roscore's ``rosout`` node: subscribes ``/rosout`` and republishes every line on
``/rosout_agg``, as ``rosout.cpp`` does (a node named ``/rosout``, itself without a /rosout
publisher: ``ros::init_options::NoRosout``). robomodel runs it where it hosts a ROS 1 master
(``robomodel master``, and a launch that starts one), so the graph is roscore's. It does not
write roscore's ``rosout.log``.

Like every roscpp node it offers ``/rosout/get_loggers`` and ``/rosout/set_logger_level``
(roscpp/GetLoggers, roscpp/SetLoggerLevel): ``rosservice list`` on robomodel's master is then
roscore's. The node logs nothing of its own, so its loggers are the levels set on it: ``ros``
at ``info``, and each name ``set_logger_level`` gives (roscpp creates a logger it does not know,
as log4cxx does); a level other than debug, info, warn, error or fatal is refused, as roscpp's
``setLoggerLevel`` refuses it (the service call fails).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg.types.rosgraph_msgs import Log as RosgraphLog

if TYPE_CHECKING:
    from robomodel.runtime.context import Context

__all__ = ["LoggerLevelError", "RosoutAggregator"]

_QUEUE = 100  # rosout.cpp: subscribe("/rosout", 100, ...), advertise("/rosout_agg", 0)


_LEVELS = ("debug", "info", "warn", "error", "fatal")  # roscpp's setLoggerLevel, lower case


class LoggerLevelError(RobomodelError):
    """A set_logger_level request with a level roscpp does not know."""


class RosoutAggregator:
    """The ``/rosout`` node on ``context`` (a ROS 1 bus)."""

    def __init__(self, context: Context) -> None:
        from robomodel.runtime.msg.types.roscpp import GetLoggers, SetLoggerLevel

        self.loggers = {"ros": "info"}
        self.node = context.create_node("rosout", enable_rosout=False)
        self._agg = self.node.create_publisher(RosgraphLog, "/rosout_agg", _QUEUE)
        self.node.create_subscription(RosgraphLog, "/rosout", self._on_line, _QUEUE)
        self.node.create_service(GetLoggers, "/rosout/get_loggers", self._get_loggers)
        self.node.create_service(SetLoggerLevel, "/rosout/set_logger_level", self._set_level)

    def _on_line(self, msg: Any) -> None:
        self._agg.publish(msg)

    def _get_loggers(self, request: Any) -> Any:
        from robomodel.runtime.msg.types.roscpp import GetLoggers_Response, Logger

        return GetLoggers_Response([Logger(n, lv) for n, lv in sorted(self.loggers.items())])

    def _set_level(self, request: Any) -> Any:
        from robomodel.runtime.msg.types.roscpp import SetLoggerLevel_Response

        level = str(request.level).lower()
        if level not in _LEVELS:
            raise LoggerLevelError(
                f"unknown logger level '{request.level}': levels are {', '.join(_LEVELS)}"
            )
        self.loggers[str(request.logger)] = level
        return SetLoggerLevel_Response()

    def close(self) -> None:
        self.node.destroy()
