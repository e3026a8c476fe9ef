"""actionlib's ``ActionServer`` and ``ServerGoalHandle``: an action's server on ROS 1 topics.

The wire is actionlib's: the server subscribes to ``<ns>/goal`` (``XActionGoal``) and
``<ns>/cancel`` (``actionlib_msgs/GoalID``) and publishes ``<ns>/status`` (a latched
``GoalStatusArray``, at ``actionlib_status_frequency`` Hz, 5 by default, and at each change),
``<ns>/feedback`` and ``<ns>/result``. Each goal's status follows actionlib's state machine:
PENDING, then ACTIVE (accepted) or REJECTED; a cancel request makes a PENDING goal RECALLING and
an ACTIVE one PREEMPTING; the terminal states are RECALLED, REJECTED, PREEMPTED, ABORTED and
SUCCEEDED. A goal in a terminal state stays in the status list for ``<ns>/status_list_timeout``
seconds (5 by default), so that clients hear how it ended.

A cancel message cancels the goal of its id; one with a stamp and no id every goal stamped at or
before it (and goals that come later stamped so); one with neither every goal. A cancel of an id
the server has not seen yet is kept (RECALLING), and the goal is RECALLED when it comes.
"""

from __future__ import annotations

import itertools
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from robomodel.clientlibs.actionlib import _wire
from robomodel.clientlibs.rospy import client as _params
from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.rostime import Time, get_rostime
from robomodel.clientlibs.rospy.timer import Timer
from robomodel.clientlibs.rospy.topics import Publisher, Subscriber

__all__ = ["ActionServer", "ServerGoalHandle", "nop_cb"]

# actionlib_msgs/GoalStatus's constants
PENDING, ACTIVE, PREEMPTED, SUCCEEDED, ABORTED = 0, 1, 2, 3, 4
REJECTED, PREEMPTING, RECALLING, RECALLED, LOST = 5, 6, 7, 8, 9

DEFAULT_STATUS_FREQUENCY_HZ = 5.0
DEFAULT_STATUS_LIST_TIMEOUT_S = 5.0
DEFAULT_PUB_QUEUE_SIZE = 50


def nop_cb(goal_handle: Any) -> None:
    """A callback that does nothing (actionlib's default cancel callback)."""


def _now_ns() -> int:
    return _wire.nsec(get_rostime())


def _time(ns: int) -> Time:
    return Time(ns // 1_000_000_000, ns % 1_000_000_000)


_ids = itertools.count(1)
_ids_lock = threading.Lock()


def generate_goal_id(name: str | None = None) -> Any:
    """A new ``actionlib_msgs/GoalID``: ``<node name>-<count>-<secs>.<nsecs>`` stamped now, as
    actionlib's GoalIDGenerator makes the id of a goal that came without one."""
    now = get_rostime()
    with _ids_lock:
        count = next(_ids)
    return _wire.goal_id_class()(
        stamp=now, id=f"{name or core.get_name()}-{count}-{now.secs}.{now.nsecs}"
    )


@dataclass(eq=False)
class _Tracked:
    """One goal in the server's status list (actionlib's StatusTracker): its goal message
    (None for a cancel that came before its goal), its status, and when it reached a terminal
    state (None while it has not)."""

    goal: Any
    status: Any
    ended_ns: int | None = None


class ServerGoalHandle:
    """One goal on the server: the user moves it through actionlib's states. A method that
    is not allowed in the goal's state logs an error and changes nothing, as actionlib's."""

    def __init__(self, tracked: _Tracked | None = None, server: ActionServer | None = None):
        self._tracked = tracked
        self._server = server
        self.goal = tracked.goal if tracked is not None else None

    def _live(self, what: str) -> bool:
        if self.goal is None or self._tracked is None or self._server is None:
            core.logerr(f"Attempt to {what} on an uninitialized ServerGoalHandle")
            return False
        return True

    def get_goal(self) -> Any:
        """The goal (the ``XGoal`` message), or None for an empty handle."""
        return None if self.goal is None else self.goal.goal

    def get_goal_id(self) -> Any:
        """The goal's ``actionlib_msgs/GoalID``."""
        if self._tracked is None or self.goal is None:
            return _wire.goal_id_class()()
        return self._tracked.status.goal_id

    def get_goal_status(self) -> Any:
        """The goal's ``actionlib_msgs/GoalStatus`` (its status and text)."""
        if self._tracked is None or self.goal is None:
            return _wire.goal_status_class()()
        return self._tracked.status

    def get_default_result(self) -> Any:
        assert self._server is not None
        return self._server.ActionResultType()

    def _move(
        self, allowed: dict[int, int], result: Any, text: str, what: str, terminal: bool
    ) -> bool:
        if not self._live(f"set status ({what})"):
            return False
        assert self._server is not None and self._tracked is not None
        with self._server.lock:
            status = self._tracked.status
            target = allowed.get(status.status)
            if target is None:
                core.logerr(
                    f"To transition to {what}, the goal must be in one of the states "
                    f"{sorted(allowed)}, it is currently in state: {status.status}"
                )
                return False
            status.status = target
            status.text = text
            if terminal:
                self._tracked.ended_ns = _now_ns()
                self._server.publish_result(
                    status, self.get_default_result() if result is None else result
                )
            else:
                self._server.publish_status()
            return True

    def set_accepted(self, text: str = "") -> None:
        """PENDING becomes ACTIVE; RECALLING (a cancel came first) becomes PREEMPTING."""
        self._move({PENDING: ACTIVE, RECALLING: PREEMPTING}, None, text, "an active state", False)

    def set_rejected(self, result: Any = None, text: str = "") -> None:
        """A PENDING or RECALLING goal is REJECTED."""
        self._move({PENDING: REJECTED, RECALLING: REJECTED}, result, text, "rejected", True)

    def set_canceled(self, result: Any = None, text: str = "") -> None:
        """A goal not started (PENDING, RECALLING) is RECALLED, a started one (ACTIVE,
        PREEMPTING) PREEMPTED."""
        allowed = {PENDING: RECALLED, RECALLING: RECALLED, ACTIVE: PREEMPTED, PREEMPTING: PREEMPTED}
        self._move(allowed, result, text, "a cancelled state", True)

    def set_aborted(self, result: Any = None, text: str = "") -> None:
        """An ACTIVE or PREEMPTING goal is ABORTED."""
        self._move({ACTIVE: ABORTED, PREEMPTING: ABORTED}, result, text, "aborted", True)

    def set_succeeded(self, result: Any = None, text: str = "") -> None:
        """An ACTIVE or PREEMPTING goal is SUCCEEDED."""
        self._move({ACTIVE: SUCCEEDED, PREEMPTING: SUCCEEDED}, result, text, "succeeded", True)

    def set_cancel_requested(self) -> bool:
        """PENDING becomes RECALLING, ACTIVE becomes PREEMPTING; whether the user's cancel
        callback is to be called (actionlib's private step of a cancel request)."""
        if self._tracked is None or self._server is None or self.goal is None:
            return False
        with self._server.lock:
            status = self._tracked.status
            if status.status not in (PENDING, ACTIVE):
                return False
            status.status = RECALLING if status.status == PENDING else PREEMPTING
            self._server.publish_status()
            return True

    def publish_feedback(self, feedback: Any) -> None:
        """Send ``feedback`` (an ``XFeedback``) to the clients, with the goal's status."""
        if self._live("publish feedback"):
            assert self._server is not None and self._tracked is not None
            self._server.publish_feedback(self._tracked.status, feedback)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ServerGoalHandle) or self.goal is None or other.goal is None:
            return False
        return bool(self.get_goal_id().id == other.get_goal_id().id)

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self.get_goal_id().id)


class ActionServer:
    """An action server on ``ns``: ``goal_cb(handle)`` for each new goal (accept or reject it
    there or later), ``cancel_cb(handle)`` for each cancel request of a goal not done.
    ``auto_start=False`` and :meth:`start` once the callbacks are ready, as actionlib
    recommends; callbacks run on the goal and cancel topics' callback threads."""

    def __init__(
        self,
        ns: str,
        ActionSpec: Any,
        goal_cb: Callable[[ServerGoalHandle], Any],
        cancel_cb: Callable[[ServerGoalHandle], Any] = nop_cb,
        auto_start: bool = True,
    ) -> None:
        types = _wire.action_types(ActionSpec)
        if not callable(goal_cb):
            raise TypeError(f"ActionServer needs a goal callback, got {goal_cb!r}")
        self.ns = ns
        self.ActionSpec = ActionSpec
        self.ActionGoal = types.action_goal
        self.ActionResult = types.action_result
        self.ActionResultType = types.result
        self.ActionFeedback = types.feedback
        self._feedback_wrapper = types.action_feedback
        self.goal_callback = goal_cb
        self.cancel_callback = cancel_cb
        self.lock = threading.RLock()
        self.status_list: list[_Tracked] = []
        self.last_cancel_ns = 0
        self.status_list_timeout_s = DEFAULT_STATUS_LIST_TIMEOUT_S
        self.status_frequency = DEFAULT_STATUS_FREQUENCY_HZ
        self.started = False
        self.auto_start = auto_start
        self.goal_sub: Subscriber | None = None
        self.cancel_sub: Subscriber | None = None
        self.status_pub: Publisher | None = None
        self.result_pub: Publisher | None = None
        self.feedback_pub: Publisher | None = None
        self.status_timer: Timer | None = None
        if auto_start:
            core.logwarn(
                "You've passed in true for auto_start to the python action server, you should "
                "always pass in false to avoid race conditions."
            )
            self.start()

    def register_goal_callback(self, cb: Callable[[ServerGoalHandle], Any]) -> None:
        self.goal_callback = cb

    def register_cancel_callback(self, cancel_cb: Callable[[ServerGoalHandle], Any]) -> None:
        self.cancel_callback = cancel_cb

    def start(self) -> None:
        """Advertise and subscribe the action's topics, and publish the status."""
        with self.lock:
            self._initialize()
            self.started = True
            self.publish_status()

    def stop(self) -> None:
        """Leave the action's topics (the goals in progress are dropped)."""
        with self.lock:
            self.started = False
            if self.status_timer is not None:
                self.status_timer.shutdown()
            for endpoint in (self.goal_sub, self.cancel_sub, self.status_pub, self.feedback_pub,
                             self.result_pub):  # fmt: skip
                if endpoint is not None:
                    endpoint.unregister()

    def _initialize(self) -> None:
        goal_class = _wire.goal_id_class()
        queue = _params.get_param("actionlib_server_pub_queue_size", DEFAULT_PUB_QUEUE_SIZE)
        pub_queue = DEFAULT_PUB_QUEUE_SIZE if int(queue) < 0 else int(queue)
        sub_queue_param = int(_params.get_param("actionlib_server_sub_queue_size", -1))
        sub_queue = None if sub_queue_param < 0 else sub_queue_param
        names = {n: _wire.topic(self.ns, n) for n in ("goal", "cancel", "status", "result",
                                                      "feedback")}  # fmt: skip
        self.status_pub = Publisher(
            names["status"], _wire.goal_status_array_class(), latch=True, queue_size=pub_queue
        )
        self.result_pub = Publisher(names["result"], self.ActionResult, queue_size=pub_queue)
        self.feedback_pub = Publisher(
            names["feedback"], self._feedback_wrapper, queue_size=pub_queue
        )
        self.goal_sub = Subscriber(
            names["goal"], self.ActionGoal, self._goal_message, queue_size=sub_queue
        )
        self.cancel_sub = Subscriber(
            names["cancel"], goal_class, self._cancel_message, queue_size=sub_queue
        )
        self.status_frequency = self._status_frequency()
        ns = core.resolve_name(self.ns).rstrip("/")
        self.status_list_timeout_s = float(
            _params.get_param(f"{ns}/status_list_timeout", DEFAULT_STATUS_LIST_TIMEOUT_S)
        )
        if self.status_frequency > 0.0:
            from robomodel.clientlibs.rospy.rostime import Duration

            period = Duration.from_sec(1.0 / self.status_frequency)
            self.status_timer = Timer(period, self._publish_status_tick)

    def _status_frequency(self) -> float:
        """``<ns>/status_frequency`` (deprecated, as actionlib warns), else the
        ``actionlib_status_frequency`` parameter found by ``search_param``, else 5 Hz."""
        ns = core.resolve_name(self.ns).rstrip("/")
        local = f"{ns}/status_frequency"
        if _params.has_param(local):
            core.logwarn(
                "You're using the deprecated status_frequency parameter, please switch to "
                "actionlib_status_frequency."
            )
            return float(_params.get_param(local, DEFAULT_STATUS_FREQUENCY_HZ))
        found = _params.search_param("actionlib_status_frequency")
        if found is None:
            return DEFAULT_STATUS_FREQUENCY_HZ
        return float(_params.get_param(found, DEFAULT_STATUS_FREQUENCY_HZ))

    # -- publishing ---------------------------------------------------------------------------
    def publish_result(self, status: Any, result: Any) -> None:
        """Publish ``result`` with the goal's ``status``, then the status list."""
        with self.lock:
            message = self.ActionResult()
            message.header.stamp = get_rostime()
            message.status = status
            message.result = result
            if not core.is_shutdown() and self.result_pub is not None:
                self.result_pub.publish(message)
            self.publish_status()

    def publish_feedback(self, status: Any, feedback: Any) -> None:
        """Publish ``feedback`` with the goal's ``status``."""
        with self.lock:
            message = self._feedback_wrapper()
            message.header.stamp = get_rostime()
            message.status = status
            message.feedback = feedback
            if not core.is_shutdown() and self.feedback_pub is not None:
                self.feedback_pub.publish(message)

    def _publish_status_tick(self, event: Any) -> None:
        with self.lock:
            if self.started:
                self.publish_status()

    def publish_status(self) -> None:
        """Publish the status list, without the goals whose end is older than
        ``status_list_timeout``."""
        with self.lock:
            now_ns = _now_ns()
            timeout_ns = int(self.status_list_timeout_s * 1e9)
            self.status_list = [
                t
                for t in self.status_list
                if t.ended_ns is None or t.ended_ns + timeout_ns >= now_ns
            ]
            array = _wire.goal_status_array_class()()
            array.status_list = [t.status for t in self.status_list]
            array.header.stamp = _time(now_ns)
            if not core.is_shutdown() and self.status_pub is not None:
                self.status_pub.publish(array)

    # -- what comes from clients -----------------------------------------------------------------
    def _cancel_message(self, goal_id: Any) -> None:
        with self.lock:
            if not self.started:
                return
            stamp_ns = _wire.nsec(goal_id.stamp)
            everything = goal_id.id == "" and stamp_ns == 0
            found = False
            for tracked in list(self.status_list):
                known = tracked.status.goal_id
                this_one = goal_id.id != "" and goal_id.id == known.id
                before = stamp_ns != 0 and _wire.nsec(known.stamp) <= stamp_ns
                if not (everything or this_one or before):
                    continue
                found = found or this_one
                if tracked.goal is None:  # a cancel kept for its goal: kept longer
                    tracked.ended_ns = _now_ns()
                handle = ServerGoalHandle(tracked, self)
                if handle.set_cancel_requested():
                    self.cancel_callback(handle)
            if goal_id.id != "" and not found:  # its goal may come later: it is recalled then
                status = _wire.goal_status_class()(goal_id=goal_id, status=RECALLING)
                self.status_list.append(_Tracked(None, status, _now_ns()))
            self.last_cancel_ns = max(self.last_cancel_ns, stamp_ns)

    def _goal_message(self, goal: Any) -> None:
        with self.lock:
            if not self.started:
                return
            for tracked in self.status_list:
                if tracked.status.goal_id.id == goal.goal_id.id:
                    if tracked.status.status == RECALLING:  # its cancel came first
                        tracked.status.status = RECALLED
                        self.publish_result(tracked.status, self.ActionResultType())
                    if tracked.goal is None:
                        tracked.ended_ns = _now_ns()
                    return  # a goal already known: no callback, no second entry
            goal_id = goal.goal_id
            if goal_id.id == "":
                goal_id = generate_goal_id()
            elif _wire.nsec(goal_id.stamp) == 0:
                goal_id = _wire.goal_id_class()(id=goal_id.id, stamp=get_rostime())
            status = _wire.goal_status_class()(goal_id=goal_id, status=PENDING)
            tracked = _Tracked(goal, status)
            self.status_list.append(tracked)
            handle = ServerGoalHandle(tracked, self)
            stamp_ns = _wire.nsec(goal.goal_id.stamp)
            if stamp_ns != 0 and stamp_ns <= self.last_cancel_ns:
                handle.set_canceled(
                    None,
                    "This goal handle was canceled by the action server because its timestamp "
                    "is before the timestamp of the last cancel request",
                )
            else:
                self.goal_callback(handle)
