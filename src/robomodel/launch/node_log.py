"""The warnings and errors of the runtime nodes a launch runs, in the launch's output.

roscpp and rclcpp print a node's ``ROS_ERROR``/``RCLCPP_WARN`` lines on its terminal, which
roslaunch and ros2 launch show (``output="screen"``): a controller manager's "Could not load
controller ..." is where a student learns why a spawner failed. robomodel's nodes log through
:mod:`logging` (``robomodel.node.<name>``); this handler shows those lines while a launch runs.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

__all__ = ["NODE_LOGGER", "NodeLogToLaunch"]

NODE_LOGGER = "robomodel.node"
"""The parent of every runtime node's logger (see :class:`robomodel.runtime.node.Node`)."""


class NodeLogToLaunch(logging.Handler):
    """``[/node] [LEVEL] message`` lines, WARNING and above, through ``log``."""

    def __init__(self, log: Callable[[str], None]) -> None:
        super().__init__(logging.WARNING)
        self._log = log

    def emit(self, record: logging.LogRecord) -> None:
        name = record.name.removeprefix(NODE_LOGGER).replace(".", "/") or "/"
        try:
            self._log(f"[{name}] [{record.levelname}] {record.getMessage()}")
        except Exception:  # a log line never takes a node down
            self.handleError(record)

    def attach(self) -> None:
        logging.getLogger(NODE_LOGGER).addHandler(self)

    def detach(self) -> None:
        logging.getLogger(NODE_LOGGER).removeHandler(self)
