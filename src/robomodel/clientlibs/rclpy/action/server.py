"""``rclpy.action.ActionServer`` on robomodel's :class:`~robomodel.runtime.action_server.ActionServer`
(rcl_action's services and topics, so ``ros2 action`` and rclpy/rclcpp clients reach it).

The goal callback decides at once (``GoalResponse``); an accepted goal goes to
``handle_accepted_callback`` (default: execute it now), and ``execute_callback(goal_handle)``
runs on the executor as a task, publishing feedback as it goes and ending with
``succeed()``, ``abort()`` or ``canceled()`` and the result it returns.
"""

from __future__ import annotations

import enum
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered
from robomodel.clientlibs.rclpy.action._types import as_class, robomodel_action
from robomodel.clientlibs.rclpy.task import Future, Task
from robomodel.runtime.msg.types.action_msgs import GoalStatus

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.node import Node

__all__ = [
    "ActionServer",
    "CancelResponse",
    "GoalResponse",
    "ServerGoalHandle",
    "default_cancel_callback",
    "default_goal_callback",
    "default_handle_accepted_callback",
]


class GoalResponse(enum.Enum):
    REJECT = 1
    ACCEPT = 2


class CancelResponse(enum.Enum):
    REJECT = 1
    ACCEPT = 2


def default_goal_callback(goal_request: Any) -> GoalResponse:
    return GoalResponse.ACCEPT


def default_cancel_callback(cancel_request: Any) -> CancelResponse:
    return CancelResponse.REJECT


def default_handle_accepted_callback(goal_handle: ServerGoalHandle) -> None:
    goal_handle.execute()


_ACTIVE = {GoalStatus.STATUS_ACCEPTED, GoalStatus.STATUS_EXECUTING, GoalStatus.STATUS_CANCELING}


class ServerGoalHandle:
    """One goal on the server: its request, status, feedback and end."""

    def __init__(self, server: ActionServer, goal_info: Any, goal_request: Any) -> None:
        self._server = server
        self._goal_info = goal_info
        self.request = goal_request
        self._status = GoalStatus.STATUS_ACCEPTED
        self._result: Any = None
        self._lock = threading.Lock()
        self._before_end = GoalStatus.STATUS_EXECUTING  # what the server sees until the result
        self._ended = False  # the execute callback returned: the result is known

    @property
    def goal_id(self) -> Any:
        return self._goal_info.goal_id

    @property
    def is_active(self) -> bool:
        return self._status in _ACTIVE

    @property
    def is_cancel_requested(self) -> bool:
        return self._status == GoalStatus.STATUS_CANCELING

    @property
    def status(self) -> int:
        return self._status

    def _move(self, status: int, allowed: set[int], what: str) -> None:
        with self._lock:
            if self._status not in allowed:
                raise RuntimeError(f"goal cannot {what} from status {self._status}")
            if status not in _ACTIVE:
                self._before_end = self._status
            self._status = status
        self._server._changed()

    def execute(self, execute_callback: Callable[[ServerGoalHandle], Any] | None = None) -> None:
        """Run the server's execute callback for this goal (as a task on the executor)."""
        if self._status == GoalStatus.STATUS_ACCEPTED:
            self._move(GoalStatus.STATUS_EXECUTING, {GoalStatus.STATUS_ACCEPTED}, "execute")
        self._server._execute(self, execute_callback)

    def publish_feedback(self, feedback: Any) -> None:
        """Publish ``feedback`` (the action's Feedback, or its FeedbackMessage) now."""
        if not self.is_active:
            raise RuntimeError("feedback of a goal that has ended")
        self._server._publish_feedback(self, feedback)

    def succeed(self) -> None:
        self._move(GoalStatus.STATUS_SUCCEEDED, {GoalStatus.STATUS_EXECUTING}, "succeed")

    def abort(self) -> None:
        self._move(GoalStatus.STATUS_ABORTED,
                   {GoalStatus.STATUS_EXECUTING, GoalStatus.STATUS_CANCELING}, "abort")  # fmt: skip

    def canceled(self) -> None:
        self._move(GoalStatus.STATUS_CANCELED, {GoalStatus.STATUS_CANCELING}, "be canceled")

    def destroy(self) -> None:
        """Nothing to free: the server forgets ended goals itself."""


class _Goal:
    """The handle as robomodel's server polls it (its ActionGoal protocol)."""

    def __init__(self, handle: ServerGoalHandle) -> None:
        self.handle = handle

    def status(self) -> int:
        """The goal's status; an end only once the execute callback returned its result."""
        handle = self.handle
        status = handle._status
        return status if status in _ACTIVE or handle._ended else handle._before_end

    def result(self) -> Any:
        server = self.handle._server
        result = self.handle._result
        return server._base.Result() if result is None else as_class(result, server._base.Result)

    def feedback(self) -> Any:
        return None  # published as it comes (publish_feedback), not polled

    def cancel(self) -> bool:
        handle = self.handle
        if handle._status not in (GoalStatus.STATUS_ACCEPTED, GoalStatus.STATUS_EXECUTING):
            return False
        if handle._server._cancel_callback(handle) != CancelResponse.ACCEPT:
            return False
        handle._status = GoalStatus.STATUS_CANCELING
        return True


class ActionServer:
    """Serves ``action_name`` of ``action_type`` on ``node`` (rclpy's arguments)."""

    def __init__(
        self,
        node: Node,
        action_type: Any,
        action_name: str,
        execute_callback: Callable[[ServerGoalHandle], Any],
        *,
        callback_group: CallbackGroup | None = None,
        goal_callback: Callable[[Any], GoalResponse] = default_goal_callback,
        handle_accepted_callback: Callable[[ServerGoalHandle], None] = (
            default_handle_accepted_callback
        ),
        cancel_callback: Callable[[Any], CancelResponse] = default_cancel_callback,
        goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None,
        feedback_pub_qos_profile: Any = None,
        status_pub_qos_profile: Any = None,
        result_timeout: int = 900,
    ) -> None:
        from robomodel.runtime.action_server import ActionServer as RobomodelActionServer

        self._node = node
        self._action_type = action_type
        self._base = robomodel_action(action_type)
        self._execute_callback = execute_callback
        self._goal_callback = goal_callback
        self._handle_accepted_callback = handle_accepted_callback
        self._cancel_callback = cancel_callback
        self.callback_group = callback_group or node.default_callback_group
        self._server = RobomodelActionServer(
            node.robomodel_node, self._base, action_name, self._accept, accept_with_info=True
        )
        self.callback_group.add_entity(self)

    def register_handle_accepted_callback(
        self, callback: Callable[[ServerGoalHandle], None]
    ) -> None:
        self._handle_accepted_callback = callback

    def register_goal_callback(self, callback: Callable[[Any], GoalResponse]) -> None:
        self._goal_callback = callback

    def register_cancel_callback(self, callback: Callable[[Any], CancelResponse]) -> None:
        self._cancel_callback = callback

    def register_execute_callback(self, callback: Callable[[ServerGoalHandle], Any]) -> None:
        self._execute_callback = callback

    def _accept(self, goal: Any, info: Any) -> _Goal | None:
        """robomodel's server asks, on the executor's thread, for each new goal."""
        request = as_class(goal, self._action_type.Goal)
        response = self._goal_callback(request)
        if isinstance(response, Task) or not isinstance(response, GoalResponse):
            not_offered("a goal callback that does not return a GoalResponse at once")
        if response != GoalResponse.ACCEPT:
            return None
        handle = ServerGoalHandle(self, info, request)
        self._node.context._post(lambda: self._handle_accepted_callback(handle))
        return _Goal(handle)

    def _execute(
        self, handle: ServerGoalHandle, callback: Callable[[ServerGoalHandle], Any] | None
    ) -> None:
        execute = callback or self._execute_callback
        context = self._node.context

        def run() -> None:
            task = Task(execute, (handle,), executor=context)
            task.add_done_callback(lambda done: self._finish(handle, done))
            task()

        dispatcher = context.dispatcher
        if dispatcher is None:
            context._post(run)
        else:
            dispatcher.dispatch(self.callback_group, run, self._node)

    def _finish(self, handle: ServerGoalHandle, task: Future) -> None:
        failure = task.exception()
        handle._result = None if failure is not None else task.result()
        handle._ended = True
        if handle.is_active:  # rclpy: a goal whose state was not set is aborted
            self._node.get_logger().warning(
                "Goal state not set, assuming aborted. Goal ID: "
                + bytes(bytearray(handle.goal_id.uuid)).hex()
            )
            with handle._lock:
                handle._status = GoalStatus.STATUS_ABORTED
        self._changed()
        if failure is not None:
            raise failure

    def _publish_feedback(self, handle: ServerGoalHandle, feedback: Any) -> None:
        feedback = getattr(feedback, "feedback", feedback)  # a FeedbackMessage: its feedback
        self._server.publish_feedback(handle._goal_info.goal_id,
                                      as_class(feedback, self._base.Feedback))  # fmt: skip

    def _changed(self) -> None:
        """A goal's status changed: the server publishes it (and answers results) promptly."""
        if self._node.context.ok():
            self._node.context._post(self._server.refresh)

    def destroy(self) -> None:
        self._server.destroy()
