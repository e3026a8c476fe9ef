"""actionlib's ``ActionClient``, ``ClientGoalHandle`` and ``CommState``: an action's client on
ROS 1 topics.

The client publishes ``<ns>/goal`` and ``<ns>/cancel`` and subscribes to ``<ns>/status``,
``<ns>/result`` and ``<ns>/feedback``. Each goal it sends gets the id
``<caller id>-<count>-<seconds>`` (seconds with three decimals, as actionlib's Python client) and
a communication state (:class:`CommState`) that the server's status list and result move, by
actionlib's transition table: a status that skips states passes through them (a goal that
succeeds before the client heard it active goes ACTIVE, WAITING_FOR_RESULT, DONE, with a
``transition_cb`` for each); a goal missing from the status list once it was pending or active is
LOST. The client keeps weak references to the goals: a handle nobody holds is forgotten.
"""

from __future__ import annotations

import itertools
import threading
import time
import weakref
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.actionlib import _wire
from robomodel.clientlibs.actionlib.action_server import (
    ABORTED,
    ACTIVE,
    LOST,
    PENDING,
    PREEMPTED,
    PREEMPTING,
    RECALLED,
    RECALLING,
    REJECTED,
    SUCCEEDED,
)
from robomodel.clientlibs.rospy import client as _params
from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.rostime import Time, get_rostime
from robomodel.clientlibs.rospy.topics import Publisher, Subscriber

__all__ = [
    "ActionClient",
    "ClientGoalHandle",
    "CommState",
    "CommStateMachine",
    "TerminalState",
    "get_name_of_constant",
    "seconds",
]


def get_name_of_constant(kind: Any, value: int) -> str:
    """The name of the integer constant ``value`` of class ``kind`` (``CommState.to_string``)."""
    for name, found in vars(kind).items():
        if isinstance(found, int) and not isinstance(found, bool) and found == value:
            return str(name)
    return f"NO_SUCH_STATE_{value}"


class CommState:
    """A goal's state as the client sees it."""

    WAITING_FOR_GOAL_ACK = 0
    PENDING = 1
    ACTIVE = 2
    WAITING_FOR_RESULT = 3
    WAITING_FOR_CANCEL_ACK = 4
    RECALLING = 5
    PREEMPTING = 6
    DONE = 7
    LOST = 8

    @classmethod
    def to_string(cls, value: int) -> str:
        return get_name_of_constant(cls, value)


class TerminalState:
    """How a goal ended (actionlib_msgs/GoalStatus's terminal values)."""

    RECALLED = RECALLED
    REJECTED = REJECTED
    PREEMPTED = PREEMPTED
    ABORTED = ABORTED
    SUCCEEDED = SUCCEEDED
    LOST = LOST

    @classmethod
    def to_string(cls, value: int) -> str:
        return get_name_of_constant(cls, value)


_C = CommState
_NONE = ()  # a status that changes nothing
_BAD = None  # a status that cannot follow the state: logged, ignored

# actionlib's transition table: the states a status moves a goal through, from each state.
_TRANSITIONS: dict[int, dict[int, tuple[int, ...] | None]] = {
    _C.WAITING_FOR_GOAL_ACK: {
        PENDING: (_C.PENDING,),
        ACTIVE: (_C.ACTIVE,),
        REJECTED: (_C.PENDING, _C.WAITING_FOR_RESULT),
        RECALLING: (_C.PENDING, _C.RECALLING),
        RECALLED: (_C.PENDING, _C.WAITING_FOR_RESULT),
        PREEMPTED: (_C.ACTIVE, _C.PREEMPTING, _C.WAITING_FOR_RESULT),
        SUCCEEDED: (_C.ACTIVE, _C.WAITING_FOR_RESULT),
        ABORTED: (_C.ACTIVE, _C.WAITING_FOR_RESULT),
        PREEMPTING: (_C.ACTIVE, _C.PREEMPTING),
    },
    _C.PENDING: {
        PENDING: _NONE,
        ACTIVE: (_C.ACTIVE,),
        REJECTED: (_C.WAITING_FOR_RESULT,),
        RECALLING: (_C.RECALLING,),
        RECALLED: (_C.RECALLING, _C.WAITING_FOR_RESULT),
        PREEMPTED: (_C.ACTIVE, _C.PREEMPTING, _C.WAITING_FOR_RESULT),
        SUCCEEDED: (_C.ACTIVE, _C.WAITING_FOR_RESULT),
        ABORTED: (_C.ACTIVE, _C.WAITING_FOR_RESULT),
        PREEMPTING: (_C.ACTIVE, _C.PREEMPTING),
    },
    _C.ACTIVE: {
        PENDING: _BAD,
        ACTIVE: _NONE,
        REJECTED: _BAD,
        RECALLING: _BAD,
        RECALLED: _BAD,
        PREEMPTED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        SUCCEEDED: (_C.WAITING_FOR_RESULT,),
        ABORTED: (_C.WAITING_FOR_RESULT,),
        PREEMPTING: (_C.PREEMPTING,),
    },
    _C.WAITING_FOR_RESULT: {
        PENDING: _BAD,
        ACTIVE: _NONE,
        REJECTED: _NONE,
        RECALLING: _BAD,
        RECALLED: _NONE,
        PREEMPTED: _NONE,
        SUCCEEDED: _NONE,
        ABORTED: _NONE,
        PREEMPTING: _BAD,
    },
    _C.WAITING_FOR_CANCEL_ACK: {
        PENDING: _NONE,
        ACTIVE: _NONE,
        REJECTED: (_C.WAITING_FOR_RESULT,),
        RECALLING: (_C.RECALLING,),
        RECALLED: (_C.RECALLING, _C.WAITING_FOR_RESULT),
        PREEMPTED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        SUCCEEDED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        ABORTED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        PREEMPTING: (_C.PREEMPTING,),
    },
    _C.RECALLING: {
        PENDING: _BAD,
        ACTIVE: _BAD,
        REJECTED: (_C.WAITING_FOR_RESULT,),
        RECALLING: _NONE,
        RECALLED: (_C.WAITING_FOR_RESULT,),
        PREEMPTED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        SUCCEEDED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        ABORTED: (_C.PREEMPTING, _C.WAITING_FOR_RESULT),
        PREEMPTING: (_C.PREEMPTING,),
    },
    _C.PREEMPTING: {
        PENDING: _BAD,
        ACTIVE: _BAD,
        REJECTED: _BAD,
        RECALLING: _BAD,
        RECALLED: _BAD,
        PREEMPTED: (_C.WAITING_FOR_RESULT,),
        SUCCEEDED: (_C.WAITING_FOR_RESULT,),
        ABORTED: (_C.WAITING_FOR_RESULT,),
        PREEMPTING: _NONE,
    },
    _C.DONE: {
        PENDING: _BAD,
        ACTIVE: _BAD,
        REJECTED: _NONE,
        RECALLING: _BAD,
        RECALLED: _NONE,
        PREEMPTED: _NONE,
        SUCCEEDED: _NONE,
        ABORTED: _NONE,
        PREEMPTING: _BAD,
    },
}
_TERMINAL = (PREEMPTED, SUCCEEDED, ABORTED, REJECTED, RECALLED, LOST)


class CommStateMachine:
    """One goal's communication state, moved by the server's status, result and feedback."""

    def __init__(
        self,
        action_goal: Any,
        transition_cb: Callable[[ClientGoalHandle], Any] | None,
        feedback_cb: Callable[[ClientGoalHandle, Any], Any] | None,
        send_goal_fn: Callable[[Any], None],
        send_cancel_fn: Callable[[Any], None],
    ) -> None:
        self.action_goal = action_goal
        self.transition_cb = transition_cb
        self.feedback_cb = feedback_cb
        self.send_goal_fn = send_goal_fn
        self.send_cancel_fn = send_cancel_fn
        self.state = CommState.WAITING_FOR_GOAL_ACK
        self.mutex = threading.RLock()
        self.latest_goal_status = _wire.goal_status_class()(status=PENDING)
        self.latest_result: Any = None

    @property
    def goal_id(self) -> str:
        return str(self.action_goal.goal_id.id)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, CommStateMachine) and self.goal_id == other.goal_id

    def __hash__(self) -> int:
        return hash(self.goal_id)

    def update_status(self, status_array: Any) -> None:
        with self.mutex:
            if self.state == CommState.DONE:
                return
            status = next((s for s in status_array.status_list if s.goal_id.id == self.goal_id),
                          None)  # fmt: skip
            if status is None:
                if self.state not in (CommState.WAITING_FOR_GOAL_ACK,
                                      CommState.WAITING_FOR_RESULT, CommState.DONE):  # fmt: skip
                    self.latest_goal_status.status = LOST
                    self.transition_to(CommState.DONE)
                return
            self.latest_goal_status = status
            table = _TRANSITIONS[self.state]
            if status.status not in table:
                core.logerr(f"Got an unknown status from the ActionServer: {status.status}")
                return
            states = table[status.status]
            if states is None:
                core.logerr(
                    f"Invalid goal status transition from {CommState.to_string(self.state)} to "
                    f"{get_name_of_constant(_wire.goal_status_class(), status.status)}"
                )
                return
            for state in states:
                self.transition_to(state)

    def transition_to(self, state: int) -> None:
        self.state = state
        if self.transition_cb is not None:
            self.transition_cb(ClientGoalHandle(self))

    def update_result(self, action_result: Any) -> None:
        if action_result.status.goal_id.id != self.goal_id:
            return
        with self.mutex:
            self.latest_goal_status = action_result.status
            self.latest_result = action_result
            if self.state == CommState.DONE:
                core.logerr("Got a result when we were already in the DONE state")
                return
            array = _wire.goal_status_array_class()(status_list=[action_result.status])
            self.update_status(array)
            self.transition_to(CommState.DONE)

    def update_feedback(self, action_feedback: Any) -> None:
        if action_feedback.status.goal_id.id != self.goal_id:
            return
        if self.feedback_cb is not None and self.state != CommState.DONE:
            self.feedback_cb(ClientGoalHandle(self), action_feedback.feedback)


class ClientGoalHandle:
    """The client's handle of one goal it sent; two handles of one goal are equal."""

    def __init__(self, comm_state_machine: CommStateMachine | None) -> None:
        self.comm_state_machine = comm_state_machine

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ClientGoalHandle):
            return False
        return self.comm_state_machine == other.comm_state_machine

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self.comm_state_machine)

    def cancel(self) -> None:
        """Ask the server to cancel this goal (its id, no stamp): WAITING_FOR_CANCEL_ACK."""
        machine = self._machine("cancel")
        if machine is None:
            return
        with machine.mutex:
            machine.send_cancel_fn(_wire.goal_id_class()(stamp=Time(0), id=machine.goal_id))
            machine.transition_to(CommState.WAITING_FOR_CANCEL_ACK)

    def _machine(self, what: str) -> CommStateMachine | None:
        if self.comm_state_machine is None:
            core.logerr(f"Trying to {what} on an inactive ClientGoalHandle.")
        return self.comm_state_machine

    def get_comm_state(self) -> int:
        machine = self._machine("get_comm_state")
        return CommState.LOST if machine is None else machine.state

    def get_goal_status(self) -> int:
        machine = self._machine("get_goal_status")
        return PENDING if machine is None else int(machine.latest_goal_status.status)

    def get_goal_status_text(self) -> str:
        machine = self._machine("get_goal_status_text")
        if machine is None:
            return "ERROR: Trying to get_goal_status_text on an inactive ClientGoalHandle."
        return str(machine.latest_goal_status.text)

    def get_result(self) -> Any:
        """The goal's result (an ``XResult``), or None before one came."""
        machine = self._machine("get_result")
        if machine is None or machine.latest_result is None:
            return None
        return machine.latest_result.result

    def get_terminal_state(self) -> int:
        """How the goal ended (a terminal GoalStatus value); LOST if it has not."""
        machine = self._machine("get_terminal_state")
        if machine is None:
            return LOST
        with machine.mutex:
            if machine.state != CommState.DONE:
                core.logwarn(
                    f"Asking for the terminal state when we're in "
                    f"[{CommState.to_string(machine.state)}]"
                )
            status = int(machine.latest_goal_status.status)
            if status in _TERMINAL:
                return status
            core.logerr(f"Asking for a terminal state, but the goal status is {status}")
            return LOST


def seconds(timeout: Any) -> float:
    """A timeout given as a Duration (actionlib's), a number of seconds, or None (zero)."""
    if timeout is None:
        return 0.0
    return float(timeout.to_sec()) if hasattr(timeout, "to_sec") else float(timeout)


_goal_count = itertools.count(1)
_goal_count_lock = threading.Lock()


class ActionClient:
    """The client of the action server on ``ns``, for the action class ``ActionSpec``."""

    def __init__(self, ns: str, ActionSpec: Any) -> None:
        types = _wire.action_types(ActionSpec)
        self.ns = ns
        self.ActionSpec = ActionSpec
        self.ActionGoal = types.action_goal
        self.ActionResult = types.action_result
        self.ActionFeedback = types.action_feedback
        self.last_status_msg: Any = None
        self._machines: list[weakref.ref[CommStateMachine]] = []
        self._lock = threading.RLock()
        pub_queue = int(_params.get_param("actionlib_client_pub_queue_size", 10))
        pub_queue = 10 if pub_queue < 0 else pub_queue
        sub_queue_param = int(_params.get_param("actionlib_client_sub_queue_size", -1))
        sub_queue = None if sub_queue_param < 0 else sub_queue_param
        self._names = {n: _wire.topic(ns, n) for n in ("goal", "cancel", "status", "result",
                                                       "feedback")}  # fmt: skip
        self.pub_goal = Publisher(self._names["goal"], self.ActionGoal, queue_size=pub_queue)
        self.pub_cancel = Publisher(
            self._names["cancel"], _wire.goal_id_class(), queue_size=pub_queue
        )
        self.status_sub = Subscriber(
            self._names["status"], _wire.goal_status_array_class(), self._status_cb,
            queue_size=sub_queue,
        )  # fmt: skip
        self.result_sub = Subscriber(
            self._names["result"], self.ActionResult, self._result_cb, queue_size=sub_queue
        )
        self.feedback_sub = Subscriber(
            self._names["feedback"], self.ActionFeedback, self._feedback_cb, queue_size=sub_queue
        )

    def stop(self) -> None:
        """Leave the action's topics."""
        for endpoint in (self.pub_goal, self.pub_cancel, self.status_sub, self.result_sub,
                         self.feedback_sub):  # fmt: skip
            endpoint.unregister()

    def _generate_id(self) -> Any:
        with _goal_count_lock:
            count = next(_goal_count)
        now = get_rostime()
        return _wire.goal_id_class()(
            id=f"{core.get_caller_id()}-{count}-{now.to_sec():.3f}", stamp=now
        )

    def send_goal(
        self,
        goal: Any,
        transition_cb: Callable[[ClientGoalHandle], Any] | None = None,
        feedback_cb: Callable[[ClientGoalHandle, Any], Any] | None = None,
    ) -> ClientGoalHandle:
        """Send ``goal`` (an ``XGoal``) and track it: ``transition_cb(handle)`` at each
        CommState it enters, ``feedback_cb(handle, feedback)`` for each feedback."""
        action_goal = self.ActionGoal(
            header=_wire.header_class()(), goal_id=self._generate_id(), goal=goal
        )
        action_goal.header.stamp = get_rostime()
        machine = CommStateMachine(
            action_goal, transition_cb, feedback_cb, self.pub_goal.publish, self.pub_cancel.publish
        )
        with self._lock:
            self._machines.append(weakref.ref(machine))
        self.pub_goal.publish(action_goal)
        return ClientGoalHandle(machine)

    def cancel_all_goals(self) -> None:
        """Cancel every goal on the server (of any client): a GoalID with no id and no stamp."""
        self.pub_cancel.publish(_wire.goal_id_class()(stamp=Time(0), id=""))

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        """Cancel every goal on the server stamped at or before ``time``."""
        self.pub_cancel.publish(_wire.goal_id_class()(stamp=time, id=""))

    def wait_for_action_server_to_start(self, timeout: Any = None) -> bool:
        """:meth:`wait_for_server` under its deprecated name."""
        return self.wait_for_server(timeout)

    def server_connected(self) -> bool:
        """Whether the server whose status came last is connected to all five topics: this
        client's goal and cancel publishers reach it, and its result and feedback publishers
        reach this client (actionlib's check, the status having come from it)."""
        status = self.last_status_msg
        if status is None:
            return False
        server = getattr(status, "_connection_header", {}).get("callerid")
        if server is None:
            return False
        return all(
            (
                server in _wire.subscriber_ids(self.pub_goal.resolved_name),
                server in _wire.subscriber_ids(self.pub_cancel.resolved_name),
                server in _wire.publisher_ids(self.result_sub.resolved_name),
                server in _wire.publisher_ids(self.feedback_sub.resolved_name),
            )
        )

    def wait_for_server(self, timeout: Any = None) -> bool:
        """Wait until an action server is connected (:meth:`server_connected`); False after
        ``timeout`` (a Duration; zero or None waits as long as it takes) or at shutdown."""
        timeout_s = seconds(timeout)
        end_s = get_rostime().to_sec() + timeout_s
        while not core.is_shutdown():
            if self.server_connected():
                return True
            if timeout_s != 0.0 and get_rostime().to_sec() >= end_s:
                return False
            time.sleep(0.01)
        return False

    def _live(self) -> list[CommStateMachine]:
        with self._lock:
            machines = [ref() for ref in self._machines]
            self._machines = [ref for ref, m in zip(self._machines, machines, strict=True) if m]
            return [m for m in machines if m is not None]

    def _status_cb(self, msg: Any) -> None:
        self.last_status_msg = msg
        for machine in self._live():
            machine.update_status(msg)

    def _result_cb(self, msg: Any) -> None:
        for machine in self._live():
            machine.update_result(msg)

    def _feedback_cb(self, msg: Any) -> None:
        for machine in self._live():
            machine.update_feedback(msg)
