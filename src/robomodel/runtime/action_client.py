"""A blocking client of a ROS 2 action (rcl_action's services), for robomodel's servers and
real ROS 2 ones: ``send_goal``, ``get_result`` and ``cancel``. Call it from a thread that does
not spin the server's executor (``get_result`` waits for the goal to end)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Action
from robomodel.runtime.msg.types.action_msgs import CancelGoal, CancelGoal_Request, GoalInfo
from robomodel.runtime.msg.types.unique_identifier_msgs import UUID

if TYPE_CHECKING:
    from robomodel.runtime.context import Context

__all__ = ["ActionClient"]


class ActionClient:
    """Goals of action ``name`` (``/ns/controller/follow_joint_trajectory``)."""

    def __init__(self, context: Context, action_type: type[Action], name: str) -> None:
        self.context = context
        self.type = action_type
        self.base = "/" + name.strip("/") + "/_action"

    def send_goal(self, goal: Message, timeout_s: float = 5.0) -> tuple[UUID, bool]:
        """Send ``goal``; its id and whether the server accepted it."""
        goal_id = UUID.random()
        request = self.type.SendGoal.Request(goal_id=goal_id, goal=goal)
        reply = self.context.call_service(
            f"{self.base}/send_goal", self.type.SendGoal, request, timeout_s
        )
        return goal_id, bool(reply.accepted)

    def get_result(self, goal_id: UUID, timeout_s: float = 60.0) -> tuple[int, Any]:
        """(status, result) once the goal has ended (GoalStatus.STATUS_*)."""
        request = self.type.GetResult.Request(goal_id=goal_id)
        reply = self.context.call_service(
            f"{self.base}/get_result", self.type.GetResult, request, timeout_s
        )
        return int(reply.status), reply.result

    def cancel(self, goal_id: UUID | None = None, timeout_s: float = 5.0) -> Any:
        """Cancel one goal, or every goal with None (a CancelGoal response)."""
        request = CancelGoal_Request(GoalInfo(goal_id or UUID()))
        return self.context.call_service(f"{self.base}/cancel_goal", CancelGoal, request, timeout_s)
