"""``rclpy.action.ActionClient``: goals sent through rcl_action's services and topics
(``<action>/_action/send_goal``, ``get_result``, ``cancel_goal``, ``feedback``, ``status``),
with the node's clients and subscriptions, so its futures and callbacks behave as the node's.

On the bus it speaks with robomodel's own classes of the action's types, as robomodel's action
server does (so the in-process bus, which hands over objects, matches them); what user code
receives, results and feedback, is of the classes the user's action type names."""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import interface
from robomodel.clientlibs.rclpy.action._types import as_class, robomodel_action, uuid_key
from robomodel.clientlibs.rclpy.qos import QoSProfile, qos_profile_action_status_default
from robomodel.clientlibs.rclpy.task import Future

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.node import Node

__all__ = ["ActionClient", "ClientGoalHandle"]


class ClientGoalHandle:
    """A goal the server has answered: accepted or not, its status and its result."""

    def __init__(self, action_client: ActionClient, goal_id: Any, goal_response: Any) -> None:
        self._client = action_client
        self._goal_id = goal_id
        self._response = goal_response
        self._status = 0  # GoalStatus.STATUS_UNKNOWN until the server says

    @property
    def goal_id(self) -> Any:
        return self._goal_id

    @property
    def stamp(self) -> Any:
        return self._response.stamp

    @property
    def accepted(self) -> bool:
        return bool(self._response.accepted)

    @property
    def status(self) -> int:
        return self._status

    def __repr__(self) -> str:
        return f"ClientGoalHandle <id={uuid_key(self._goal_id).hex()}, accepted={self.accepted}, status={self._status}>"

    def get_result_async(self) -> Future:
        """A future of the GetResult response (``.status`` and ``.result``)."""
        if not self.accepted:
            raise RuntimeError("Cannot get result of a goal that was not accepted")
        return self._client._get_result_async(self)

    def get_result(self) -> Any:
        return _wait(self.get_result_async())

    def cancel_goal_async(self) -> Future:
        """A future of the action_msgs/CancelGoal response."""
        return self._client._cancel_goal_async(self)

    def cancel_goal(self) -> Any:
        return _wait(self.cancel_goal_async())


def _wait(future: Future) -> Any:
    done = threading.Event()
    future.add_done_callback(lambda _f: done.set())
    while not future.done():
        done.wait(0.05)
    return future.result()


class ActionClient:
    """Sends goals of ``action_type`` to ``action_name`` (rclpy's arguments)."""

    def __init__(
        self,
        node: Node,
        action_type: Any,
        action_name: str,
        *,
        callback_group: CallbackGroup | None = None,
        goal_service_qos_profile: Any = None,
        result_service_qos_profile: Any = None,
        cancel_service_qos_profile: Any = None,
        feedback_sub_qos_profile: Any = None,
        status_sub_qos_profile: QoSProfile = qos_profile_action_status_default,
    ) -> None:
        self._node = node
        self._action_type = action_type
        self._base = robomodel_action(action_type)
        self.callback_group = callback_group or node.default_callback_group
        base = node.resolve_topic_name(action_name) + "/_action"
        from robomodel.runtime.msg.types.action_msgs import CancelGoal, GoalStatusArray

        self._cancel_type = CancelGoal
        group = self.callback_group
        self._send_goal = node.create_client(self._base.SendGoal, f"{base}/send_goal",
                                             callback_group=group)  # fmt: skip
        self._get_result = node.create_client(self._base.GetResult, f"{base}/get_result",
                                              callback_group=group)  # fmt: skip
        self._cancel = node.create_client(CancelGoal, f"{base}/cancel_goal",
                                          callback_group=group)  # fmt: skip
        self._feedback_callbacks: dict[bytes, Callable[[Any], None]] = {}
        self._handles: dict[bytes, ClientGoalHandle] = {}
        self._feedback_sub = node.create_subscription(
            self._base.FeedbackMessage, f"{base}/feedback", self._on_feedback,
            feedback_sub_qos_profile or 10, callback_group=group,
        )  # fmt: skip
        self._status_sub = node.create_subscription(
            GoalStatusArray, f"{base}/status", self._on_status,
            status_sub_qos_profile, callback_group=group,
        )  # fmt: skip

    # -- server --------------------------------------------------------------------------------
    def server_is_ready(self) -> bool:
        return all(c.service_is_ready() for c in (self._send_goal, self._get_result, self._cancel))

    def wait_for_server(self, timeout_sec: float | None = None) -> bool:
        """Wait until the server's services are in the graph; False after ``timeout_sec``."""
        import time

        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        for client in (self._send_goal, self._get_result, self._cancel):
            remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
            if not client.wait_for_service(remaining):
                return False
        return True

    # -- goals ---------------------------------------------------------------------------------
    def _goal_id(self, goal_uuid: Any) -> Any:
        """A goal id of robomodel's UUID class: ``goal_uuid`` (of any flavour) or a new one."""
        from robomodel.runtime.msg.types.unique_identifier_msgs import UUID

        if goal_uuid is None:
            return UUID(uuid=os.urandom(16))
        return UUID(uuid=bytes(bytearray(goal_uuid.uuid)))

    def send_goal_async(
        self,
        goal: Any,
        feedback_callback: Callable[[Any], None] | None = None,
        goal_uuid: Any = None,
    ) -> Future:
        """Send ``goal``; a future of its :class:`ClientGoalHandle`. ``feedback_callback``
        receives each FeedbackMessage (``.goal_id``, ``.feedback``)."""
        goal_id = self._goal_id(goal_uuid)
        key = uuid_key(goal_id)
        if feedback_callback is not None:
            self._feedback_callbacks[key] = feedback_callback
        request = self._base.SendGoal.Request(goal_id=goal_id, goal=as_class(goal, self._base.Goal))
        answered = self._send_goal.call_async(request)
        future = Future(executor=self._node.context)

        def on_answer(done: Future) -> None:
            failure = done.exception()
            if failure is not None:
                self._feedback_callbacks.pop(key, None)
                future.set_exception(failure)
                return
            handle = ClientGoalHandle(self, goal_id, done.result())
            if handle.accepted:
                self._handles[key] = handle
            else:
                self._feedback_callbacks.pop(key, None)
            future.set_result(handle)

        answered.add_done_callback(on_answer)
        return future

    def send_goal(
        self,
        goal: Any,
        feedback_callback: Callable[[Any], None] | None = None,
        goal_uuid: Any = None,
    ) -> Any:
        """Send ``goal`` and wait for its end: the GetResult response, or None if rejected."""
        handle = _wait(self.send_goal_async(goal, feedback_callback, goal_uuid))
        if not handle.accepted:
            return None
        return handle.get_result()

    def _get_result_async(self, handle: ClientGoalHandle) -> Future:
        request = self._base.GetResult.Request(goal_id=handle.goal_id)
        return self._converted(
            self._get_result.call_async(request),
            self._action_type.GetResult.Response,
            lambda response: self._ended(handle, response),
        )

    def _ended(self, handle: ClientGoalHandle, response: Any) -> None:
        handle._status = int(response.status)
        key = uuid_key(handle.goal_id)

        def forget() -> None:
            self._feedback_callbacks.pop(key, None)
            self._handles.pop(key, None)

        # after the feedback that waits in the group's queue (it came before the result)
        self._node._dispatcher(self.callback_group, forget)()

    def _cancel_goal_async(self, handle: ClientGoalHandle) -> Future:
        from robomodel.runtime.msg.types.action_msgs import GoalInfo

        request = self._cancel_type.Request(goal_info=GoalInfo(goal_id=handle.goal_id))
        flavoured = interface("action_msgs.srv", "CancelGoal").Response
        return self._converted(self._cancel.call_async(request), flavoured)

    def _converted(
        self, answered: Future, cls: Any, seen: Callable[[Any], None] | None = None
    ) -> Future:
        """A future of ``answered``'s response as an instance of ``cls`` (the user's flavour)."""
        future = Future(executor=self._node.context)

        def convert(done: Future) -> None:
            failure = done.exception()
            if failure is not None:
                future.set_exception(failure)
                return
            if seen is not None:
                seen(done.result())
            future.set_result(as_class(done.result(), cls))

        answered.add_done_callback(convert)
        return future

    def _on_feedback(self, message: Any) -> None:
        callback = self._feedback_callbacks.get(uuid_key(message.goal_id))
        if callback is not None:
            callback(as_class(message, self._action_type.FeedbackMessage))

    def _on_status(self, message: Any) -> None:
        for status in message.status_list:
            handle = self._handles.get(uuid_key(status.goal_info.goal_id))
            if handle is not None:
                handle._status = int(status.status)

    def destroy(self) -> None:
        for client in (self._send_goal, self._get_result, self._cancel):
            self._node.destroy_client(client)
        for subscription in (self._feedback_sub, self._status_sub):
            self._node.destroy_subscription(subscription)
