"""ROS 2 actions as rcl_action builds them from services and topics, so that ``ros2 action``,
rclpy/rclcpp action clients and robomodel's :class:`ActionClient` reach robomodel's servers.

Under ``<action>/_action/``: the services ``send_goal``, ``cancel_goal`` (action_msgs/CancelGoal)
and ``get_result``, the topic ``feedback`` (the action's FeedbackMessage) and the topic
``status`` (action_msgs/GoalStatusArray, transient local, depth 1, as rcl_action's status QoS).
``get_result`` answers when the goal has ended (a :class:`Deferred` response); the cancel
request follows rcl_action's rules (a zero goal id with a zero stamp cancels every goal, with a
stamp those accepted at or before it).

A server is given ``accept(goal) -> ActionGoal | None`` (``accept(goal, info)``, the goal's
GoalInfo too, with ``accept_with_info=True``); the returned object reports its status, result
and feedback, and is polled at ``monitor_rate_hz`` on the node's executor. A server that has
feedback to send at once (rclpy's ``publish_feedback``) calls :meth:`ActionServer.publish_feedback`
and :meth:`ActionServer.refresh` after a goal's status changed.
"""

from __future__ import annotations

import collections
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Action
from robomodel.runtime.msg.types.action_msgs import (
    CancelGoal,
    CancelGoal_Request,
    CancelGoal_Response,
    GoalInfo,
    GoalStatus,
    GoalStatusArray,
)
from robomodel.runtime.qos import QoSProfile, latched
from robomodel.runtime.transport.base import Deferred

if TYPE_CHECKING:
    from robomodel.runtime.node import Node

__all__ = ["TERMINAL", "ActionGoal", "ActionServer"]

TERMINAL = {GoalStatus.STATUS_SUCCEEDED, GoalStatus.STATUS_CANCELED, GoalStatus.STATUS_ABORTED}
MAX_ENDED_GOALS = 100  # ended goals kept for late get_result calls (rcl_action keeps 15 min)


class ActionGoal(Protocol):
    """What a server's ``accept`` returns for a goal it takes."""

    def status(self) -> int: ...  # a GoalStatus.STATUS_* value

    def result(self) -> Message: ...

    def feedback(self) -> Message | None: ...

    def cancel(self) -> bool: ...


@dataclass(eq=False)
class _Goal:
    info: GoalInfo
    goal: ActionGoal
    status: int = GoalStatus.STATUS_ACCEPTED
    waiting: list[Deferred] = field(default_factory=list)


def _key(info: GoalInfo) -> bytes:
    return bytes(info.goal_id.uuid)


class ActionServer:
    """Serves action ``action_type`` as ``name`` on ``node`` (see the module docstring)."""

    def __init__(
        self,
        node: Node,
        action_type: type[Action],
        name: str,
        accept: Callable[..., ActionGoal | None],
        *,
        monitor_rate_hz: float = 20.0,
        accept_with_info: bool = False,
    ) -> None:
        self._node = node
        self._accept_with_info = accept_with_info
        self._type = action_type
        self._accept = accept
        self._goals: collections.OrderedDict[bytes, _Goal] = collections.OrderedDict()
        base = node.resolve_topic_name(name).rstrip("/") + "/_action"
        self.name = base.removesuffix("/_action")
        self._services = [
            node.create_service(action_type.SendGoal, f"{base}/send_goal", self._send_goal),
            node.create_service(CancelGoal, f"{base}/cancel_goal", self._cancel_goal),
            node.create_service(action_type.GetResult, f"{base}/get_result", self._get_result),
        ]
        self._feedback = node.create_publisher(
            action_type.FeedbackMessage, f"{base}/feedback", QoSProfile(depth=10)
        )
        self._status = node.create_publisher(GoalStatusArray, f"{base}/status", latched(1))
        self._timer = node.create_timer(1.0 / monitor_rate_hz, self._monitor)

    # -- services ------------------------------------------------------------------------------
    def _send_goal(self, request: Any) -> Any:
        info = GoalInfo(request.goal_id, self._node.now())
        goal = None
        if _key(info) not in self._goals:
            goal = (
                self._accept(request.goal, info)
                if self._accept_with_info
                else self._accept(request.goal)
            )
        if goal is not None:
            self._goals[_key(info)] = _Goal(info, goal)
            self._monitor()
        return self._type.SendGoal.Response(accepted=goal is not None, stamp=info.stamp)

    def _get_result(self, request: Any) -> Any:
        entry = self._goals.get(bytes(request.goal_id.uuid))
        response = self._type.GetResult.Response
        if entry is None:
            return response(status=GoalStatus.STATUS_UNKNOWN)
        if entry.status in TERMINAL:
            return response(status=entry.status, result=entry.goal.result())
        deferred = Deferred()
        entry.waiting.append(deferred)
        return deferred

    def _cancel_goal(self, request: CancelGoal_Request) -> CancelGoal_Response:
        wanted = bytes(request.goal_info.goal_id.uuid)
        stamp = request.goal_info.stamp.to_nanoseconds()
        if any(wanted) and wanted not in self._goals:
            return CancelGoal_Response(CancelGoal_Response.ERROR_UNKNOWN_GOAL_ID)
        chosen = [
            e
            for k, e in self._goals.items()
            if k == wanted
            or (not any(wanted) and stamp == 0)
            or (stamp != 0 and e.info.stamp.to_nanoseconds() <= stamp)
        ]
        live = [e for e in chosen if e.status not in TERMINAL]
        if chosen and not live:
            return CancelGoal_Response(CancelGoal_Response.ERROR_GOAL_TERMINATED)
        canceling = [e.info for e in live if e.goal.cancel()]
        self._monitor()
        if live and not canceling:
            return CancelGoal_Response(CancelGoal_Response.ERROR_REJECTED)
        return CancelGoal_Response(CancelGoal_Response.ERROR_NONE, canceling)

    # -- monitoring ----------------------------------------------------------------------------
    def publish_feedback(self, goal_id: Any, feedback: Message) -> None:
        """Publish ``feedback`` of goal ``goal_id`` (a unique_identifier_msgs/UUID) now."""
        self._feedback.publish(self._type.FeedbackMessage(goal_id, feedback))

    def refresh(self) -> None:
        """Look at the goals now (on the executor's thread), not at the next monitor tick."""
        self._monitor()

    def _monitor(self) -> None:
        """Publish feedback of running goals; on any status change the status array, and the
        results of goals that ended."""
        changed = False
        for entry in self._goals.values():
            status = entry.goal.status()
            if status == GoalStatus.STATUS_EXECUTING:
                feedback = entry.goal.feedback()
                if feedback is not None:
                    self._feedback.publish(self._type.FeedbackMessage(entry.info.goal_id, feedback))
            if status != entry.status:
                entry.status, changed = status, True
                if status in TERMINAL:
                    waiting, entry.waiting = entry.waiting, []
                    for deferred in waiting:
                        deferred.resolve(self._type.GetResult.Response(status, entry.goal.result()))
        if changed:
            self._status.publish(
                GoalStatusArray([GoalStatus(e.info, e.status) for e in self._goals.values()])
            )
            self._forget_ended()

    def _forget_ended(self) -> None:
        ended = [k for k, e in self._goals.items() if e.status in TERMINAL and not e.waiting]
        for key in ended[: max(0, len(ended) - MAX_ENDED_GOALS)]:
            del self._goals[key]

    def destroy(self) -> None:
        self._timer.cancel()
        for service in self._services:
            service.destroy()
        self._feedback.destroy()
        self._status.destroy()
