"""actionlib on robomodel: ROS 1 actions (``SimpleActionServer``, ``SimpleActionClient``, the
lower-level ``ActionServer`` and ``ActionClient``) on robomodel's rospy, with actionlib's wire
protocol, so that real ROS 1 actionlib peers are their clients and servers.

``import actionlib`` gives this package when no real actionlib is on the path; ``actionlib.msg``
is the actionlib interface package's messages (``TestAction``, ``TwoIntsAction``).
"""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.actionlib.action_client import (
    ActionClient,
    ClientGoalHandle,
    CommState,
    CommStateMachine,
    TerminalState,
    get_name_of_constant,
)
from robomodel.clientlibs.actionlib.action_server import ActionServer, ServerGoalHandle, nop_cb
from robomodel.clientlibs.actionlib.exceptions import ActionException
from robomodel.clientlibs.actionlib.goal_id_generator import GoalIDGenerator
from robomodel.clientlibs.actionlib.simple_action_client import (
    SimpleActionClient,
    SimpleGoalState,
)
from robomodel.clientlibs.actionlib.simple_action_server import SimpleActionServer

__all__ = [
    "ActionClient",
    "ActionException",
    "ActionServer",
    "ClientGoalHandle",
    "CommState",
    "CommStateMachine",
    "GoalIDGenerator",
    "GoalStatus",
    "ServerGoalHandle",
    "SimpleActionClient",
    "SimpleActionServer",
    "SimpleGoalState",
    "TerminalState",
    "get_name_of_constant",
    "nop_cb",
]


def __getattr__(name: str) -> Any:
    if name == "GoalStatus":  # actionlib's modules re-export actionlib_msgs' GoalStatus
        from robomodel.clientlibs.actionlib._wire import goal_status_class

        found = goal_status_class()
        globals()["GoalStatus"] = found
        return found
    raise AttributeError(f"module 'actionlib' has no attribute '{name}'")
