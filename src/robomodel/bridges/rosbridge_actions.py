"""ROS 2 rosbridge's action operations, on robomodel's action runtime.

As a client of an action (roslibjs's ``Action.sendGoal``, roslibpy's ``ActionClient``):
``send_action_goal`` (``action``, ``action_type``, ``args``, ``feedback``) sends the goal to the
action's server on the bus (any ROS 2 action server: robomodel's, rclpy's, rclcpp's); the client
hears ``action_feedback`` while it runs (when it asked for feedback) and one ``action_result``
(``values``, ``status``, ``result``) when it ended, with ``result: false`` and the reason when
the goal could not be sent or was rejected. ``cancel_action_goal`` (``id``) cancels it.

As a server (roslibjs's ``Action.advertise``): ``advertise_action`` (``action``, ``type``) offers
the action on the bus (:class:`~robomodel.runtime.action_server.ActionServer`); each goal that
comes is accepted and sent to the client as ``send_action_goal`` (with an id), a cancel request
as ``cancel_action_goal``; the client answers with ``action_feedback`` and ``action_result``
(``status`` 4 succeeded, 5 canceled, anything else aborted; ``result: false`` aborts).
``unadvertise_action`` (or the client leaving) aborts the goals still running.

Transcribed from github:RobotWebTools/rosbridge_suite (ros2 branch, commit c1bfc2f),
``rosbridge_library/capabilities/send_action_goal.py``, ``advertise_action.py``,
``action_feedback.py``, ``action_result.py``, ``unadvertise_action.py`` and
``internal/actions.py``. ROS 1's rosbridge has no such operations (ROS 1's actionlib goes over
topics, which clients reach with ``subscribe`` and ``publish``); on ROS 1 they are refused.
"""

from __future__ import annotations

import contextlib
import threading
from dataclasses import dataclass, field
from typing import Any, Protocol

from robomodel.bridges.exceptions import ClientError
from robomodel.bridges.json_mapping import message_from_json, message_to_json
from robomodel.errors import RobomodelError

__all__ = ["ActionOps", "Client"]


class Client(Protocol):
    """What the action operations use of a rosbridge client's session."""

    server: Any  # the RosbridgeServer: context, node, dialect, on_bus
    closed: threading.Event

    def send(self, message: dict[str, Any]) -> None: ...
    def status(self, level: str, text: str, op_id: Any = None) -> None: ...
    def name_of(self, message: dict[str, Any], key: str) -> str: ...
    def count_endpoints(self) -> None: ...


MAX_GOALS_IN_FLIGHT = 16  # per client: goals it sent that have not ended
_SEND_GOAL_TIMEOUT_S = 5.0
_RESULT_POLL_S = 10.0  # one get_result call's wait; repeated while the goal runs
# action_msgs/GoalStatus
_UNKNOWN, _EXECUTING, _CANCELING, _SUCCEEDED, _CANCELED, _ABORTED = 0, 2, 3, 4, 5, 6


def action_type(name: Any, where: str) -> Any:
    """The action class of ``pkg/action/Name`` (or ``pkg/Name``); ClientError naming ``where``."""
    from robomodel.runtime.msg._resolver import resolve_action

    if not isinstance(name, str) or not name:
        raise ClientError(f"{where}: the action's type must be given, as pkg/action/Name")
    parts = name.strip("/").split("/")
    key = f"{parts[0]}/action/{parts[1]}" if len(parts) == 2 else "/".join(parts)
    try:
        return resolve_action(key, name)
    except RobomodelError as exc:
        raise ClientError(f"{where}: {exc}") from None


@dataclass
class _SentGoal:
    """A goal this client sent: its id on the bus once sent, and a cancel asked meanwhile."""

    action: str
    type: Any
    goal_id: Any = None
    cancel_wanted: bool = False


class _ClientGoal:
    """A goal of an action the client serves, as the ActionServer polls it."""

    def __init__(self, ops: ActionOps, action: str, request_id: str, result: Any) -> None:
        self._ops = ops
        self._action = action
        self.request_id = request_id
        self.state = _EXECUTING
        self.outcome = result  # the Result message, replaced by the client's

    def status(self) -> int:
        return self.state

    def result(self) -> Any:
        return self.outcome

    def feedback(self) -> Any:
        return None  # the client's feedback is published when it comes

    def cancel(self) -> bool:
        """rosbridge accepts every cancel request and tells the client."""
        if self.state in (_SUCCEEDED, _CANCELED, _ABORTED):
            return False
        self.state = _CANCELING
        self._ops.session.send(
            {"op": "cancel_action_goal", "id": self.request_id, "action": self._action}
        )
        return True


@dataclass
class _Advertised:
    """An action the client serves: its server on the bus and the goals sent to the client."""

    type: Any
    server: Any = None
    goals: dict[str, tuple[_ClientGoal, Any]] = field(default_factory=dict)  # id -> (goal, uuid)


class ActionOps:
    """One client's action operations (module docstring)."""

    def __init__(self, session: Client) -> None:
        self.session = session
        self.sent: dict[str, _SentGoal] = {}  # request id -> goal
        self.advertised: dict[str, _Advertised] = {}
        self._slots = threading.BoundedSemaphore(MAX_GOALS_IN_FLIGHT)
        self._lock = threading.Lock()
        self._next = 0

    def _check_ros2(self, op: str) -> None:
        if self.session.server.dialect != "ros2":
            raise ClientError(f"{op}: actions are ROS 2 rosbridge's; this bridge is on ROS 1")

    def _next_id(self) -> int:
        with self._lock:
            self._next += 1
            return self._next

    # -- the client's goals -------------------------------------------------------------------
    def send_action_goal(self, message: dict[str, Any]) -> None:
        self._check_ros2("send_action_goal")
        action = self.session.name_of(message, "action")
        found = action_type(message.get("action_type"), f"send_action_goal {action}")
        args = message.get("args")
        if isinstance(args, list):  # the goal's fields in order, as rosbridge takes them
            args = dict(zip([n for n, _ in found.Goal.__fields__], args, strict=False))
        goal = message_from_json(found.Goal, args, self.session.server.dialect)
        request_id = message.get("id")
        if request_id is None:
            request_id = f"send_action_goal:{action}:{self._next_id()}"
        request_id = str(request_id)
        if request_id in self.sent:
            raise ClientError(f"send_action_goal: a goal with id {request_id!r} runs already")
        if not self._slots.acquire(blocking=False):
            raise ClientError(
                f"send_action_goal {action}: {MAX_GOALS_IN_FLIGHT} goals of this client run already"
            )
        self.sent[request_id] = _SentGoal(action, found)
        threading.Thread(
            target=self._run_goal,
            args=(request_id, action, found, goal, message.get("feedback") is True),
            name=f"rosbridge goal {action}", daemon=True,
        ).start()  # fmt: skip

    def _run_goal(
        self, request_id: str, action: str, found: Any, goal: Any, feedback: bool
    ) -> None:
        from robomodel.runtime.msg.types.unique_identifier_msgs import UUID

        session, server = self.session, self.session.server
        base = action.rstrip("/") + "/_action"
        goal_id = UUID.random()
        subscription = None
        try:
            if feedback:
                subscription = server.on_bus(
                    lambda: server.node.create_subscription(
                        found.FeedbackMessage, f"{base}/feedback",
                        lambda msg: self._feedback(request_id, action, goal_id, msg), 10,
                    )
                )  # fmt: skip
            request = found.SendGoal.Request(goal_id=goal_id, goal=goal)
            reply = server.context.call_service(
                f"{base}/send_goal", found.SendGoal, request, _SEND_GOAL_TIMEOUT_S
            )
            if not reply.accepted:
                raise ClientError(f"the goal of {action} was rejected")
            entry = self.sent.get(request_id)
            if entry is not None:
                entry.goal_id = goal_id
                if entry.cancel_wanted:
                    self._cancel(action, found, goal_id)
            status, result = self._wait_result(action, found, goal_id)
            session.send({"op": "action_result", "id": request_id, "action": action,
                          "values": message_to_json(result, server.dialect), "status": status,
                          "result": True})  # fmt: skip
        except RobomodelError as exc:
            session.status("error", f"send_action_goal {action}: {exc}", request_id)
            session.send({"op": "action_result", "id": request_id, "action": action,
                          "values": str(exc), "status": _UNKNOWN, "result": False})  # fmt: skip
        finally:
            self.sent.pop(request_id, None)
            self._slots.release()
            if subscription is not None:
                handle = subscription
                # a bus that is gone took its endpoints with it
                with contextlib.suppress(ClientError):
                    server.on_bus(handle.destroy)

    def _wait_result(self, action: str, found: Any, goal_id: Any) -> tuple[int, Any]:
        """The goal's (status, result), asking again while it runs and the client is here."""
        from robomodel.runtime.action_client import ActionClient
        from robomodel.runtime.transport.base import ServiceCallError

        client = ActionClient(self.session.server.context, found, action)
        while True:
            try:
                return client.get_result(goal_id, timeout_s=_RESULT_POLL_S)
            except ServiceCallError:
                if self.session.closed.wait(0.5):
                    raise ClientError("the client left") from None

    def _feedback(self, request_id: str, action: str, goal_id: Any, msg: Any) -> None:
        if bytes(msg.goal_id.uuid) != bytes(goal_id.uuid):
            return
        values = message_to_json(msg.feedback, self.session.server.dialect)
        self.session.send(
            {"op": "action_feedback", "id": request_id, "action": action, "values": values}
        )

    def cancel_action_goal(self, message: dict[str, Any]) -> None:
        self._check_ros2("cancel_action_goal")
        request_id = str(message.get("id"))
        entry = self.sent.get(request_id)
        if entry is None:
            raise ClientError(f"cancel_action_goal: no goal with id {request_id!r} runs")
        if entry.goal_id is None:
            entry.cancel_wanted = True  # cancelled once the server accepted it
            return
        threading.Thread(
            target=self._cancel, args=(entry.action, entry.type, entry.goal_id),
            name=f"rosbridge cancel {entry.action}", daemon=True,
        ).start()  # fmt: skip

    def _cancel(self, action: str, found: Any, goal_id: Any) -> None:
        from robomodel.runtime.action_client import ActionClient

        try:
            ActionClient(self.session.server.context, found, action).cancel(goal_id)
        except RobomodelError as exc:
            self.session.status("error", f"cancel_action_goal {action}: {exc}")

    # -- actions the client serves ---------------------------------------------------------------
    def advertise_action(self, message: dict[str, Any]) -> None:
        from robomodel.runtime.action_server import ActionServer

        self._check_ros2("advertise_action")
        action = self.session.name_of(message, "action")
        found = action_type(message.get("type"), f"advertise_action {action}")
        if action in self.advertised:
            raise ClientError(f"advertise_action: {action} is advertised by this client already")
        self.session.count_endpoints()
        entry = _Advertised(found)

        def accept(goal: Any, info: Any) -> _ClientGoal:
            request_id = f"action_goal:{action}:{self._next_id()}"
            taken = _ClientGoal(self, action, request_id, found.Result())
            entry.goals[request_id] = (taken, info.goal_id)
            self.session.send({"op": "send_action_goal", "id": request_id, "action": action,
                               "action_type": found.__typename__,
                               "args": message_to_json(goal, self.session.server.dialect),
                               "feedback": True})  # fmt: skip
            return taken

        node = self.session.server.node
        entry.server = self.session.server.on_bus(
            lambda: ActionServer(node, found, action, accept, accept_with_info=True)
        )
        self.advertised[action] = entry

    def _served(self, message: dict[str, Any], op: str) -> tuple[_Advertised, _ClientGoal, Any]:
        action = self.session.name_of(message, "action")
        entry = self.advertised.get(action)
        if entry is None:
            raise ClientError(f"{op}: action {action} has not been advertised via rosbridge")
        goal = entry.goals.get(str(message.get("id")))
        if goal is None:
            raise ClientError(f"{op} {action}: no goal with id {message.get('id')!r} runs")
        return entry, *goal

    def action_feedback(self, message: dict[str, Any]) -> None:
        self._check_ros2("action_feedback")
        entry, _, goal_uuid = self._served(message, "action_feedback")
        feedback = message_from_json(
            entry.type.Feedback, message.get("values"), self.session.server.dialect
        )
        server = entry.server
        self.session.server.context.executor.post(
            lambda: server.publish_feedback(goal_uuid, feedback)
        )

    def action_result(self, message: dict[str, Any]) -> None:
        self._check_ros2("action_result")
        entry, goal, _ = self._served(message, "action_result")
        if message.get("result") is True:
            goal.outcome = message_from_json(
                entry.type.Result, message.get("values"), self.session.server.dialect
            )
            status = message.get("status")
            goal.state = status if status in (_SUCCEEDED, _CANCELED) else _ABORTED
        else:
            goal.state = _ABORTED
        del entry.goals[goal.request_id]
        self.session.server.context.executor.post(entry.server.refresh)

    def unadvertise_action(self, message: dict[str, Any]) -> None:
        self._check_ros2("unadvertise_action")
        action = self.session.name_of(message, "action")
        entry = self.advertised.pop(action, None)
        if entry is None:
            raise ClientError(f"unadvertise_action: {action} is not advertised by this client")
        self.session.server.on_bus(lambda: _withdraw(entry))

    def endpoints(self) -> int:
        return len(self.advertised)

    def close(self) -> list[Any]:
        """Abort the goals of the actions the client served; the work the bus must do."""
        entries = list(self.advertised.values())
        self.advertised.clear()
        return [lambda entry=entry: _withdraw(entry) for entry in entries]


def _withdraw(entry: _Advertised) -> None:
    """On the bus's thread: the goals still running abort, then the server goes."""
    for goal, _ in entry.goals.values():
        goal.state = _ABORTED
    entry.goals.clear()
    entry.server.refresh()
    entry.server.destroy()
