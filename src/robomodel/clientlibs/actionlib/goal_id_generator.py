"""actionlib's ``GoalIDGenerator``: goal ids ``<name>-<count>-<secs>.<nsecs>``."""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.actionlib.action_server import generate_goal_id
from robomodel.clientlibs.rospy import core

__all__ = ["GoalIDGenerator"]


class GoalIDGenerator:
    """Makes unique goal ids prefixed by ``name`` (the node's name by default)."""

    def __init__(self, name: str | None = None) -> None:
        self.name = core.get_name() if name is None else name

    def set_name(self, name: str) -> None:
        self.name = name

    def generate_ID(self) -> Any:
        """A new ``actionlib_msgs/GoalID``, stamped now."""
        return generate_goal_id(self.name)
