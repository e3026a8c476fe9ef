"""``rclpy.action``: action servers and clients (rcl_action's protocol over services and topics)."""

from robomodel.clientlibs.rclpy.action.client import ActionClient, ClientGoalHandle
from robomodel.clientlibs.rclpy.action.server import (
    ActionServer,
    CancelResponse,
    GoalResponse,
    ServerGoalHandle,
)

__all__ = [
    "ActionClient",
    "ActionServer",
    "CancelResponse",
    "ClientGoalHandle",
    "GoalResponse",
    "ServerGoalHandle",
]
