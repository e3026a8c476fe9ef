"""actionlib's ``SimpleActionClient``: one goal at a time, its state as PENDING, ACTIVE, DONE
(:class:`SimpleGoalState`) and the callbacks ``done_cb(state, result)``, ``active_cb()`` and
``feedback_cb(feedback)``."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.actionlib.action_client import (
    ActionClient,
    ClientGoalHandle,
    CommState,
    get_name_of_constant,
    seconds,
)
from robomodel.clientlibs.actionlib.action_server import (
    ACTIVE,
    LOST,
    PENDING,
    PREEMPTING,
    RECALLING,
)
from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.rostime import get_rostime

__all__ = ["SimpleActionClient", "SimpleGoalState"]

_LOOP_S = 0.1  # how often wait_for_result looks at the shutdown flag, as actionlib's


class SimpleGoalState:
    """The simple client's view of its goal."""

    PENDING = 0
    ACTIVE = 1
    DONE = 2

    @classmethod
    def to_string(cls, value: int) -> str:
        return get_name_of_constant(cls, value)


class SimpleActionClient:
    """The client of the action server on ``ns`` for the action class ``ActionSpec``,
    tracking the last goal it sent."""

    def __init__(self, ns: str, ActionSpec: Any) -> None:
        self.action_client = ActionClient(ns, ActionSpec)
        self.simple_state = SimpleGoalState.DONE
        self.gh: ClientGoalHandle | None = None
        self.done_condition = threading.Condition()
        self.done_cb: Callable[[int, Any], Any] | None = None
        self.active_cb: Callable[[], Any] | None = None
        self.feedback_cb: Callable[[Any], Any] | None = None

    def wait_for_server(self, timeout: Any = None) -> bool:
        """Wait until the server is connected; False after ``timeout`` (a Duration, zero or
        None for no limit)."""
        return self.action_client.wait_for_server(timeout)

    def send_goal(
        self,
        goal: Any,
        done_cb: Callable[[int, Any], Any] | None = None,
        active_cb: Callable[[], Any] | None = None,
        feedback_cb: Callable[[Any], Any] | None = None,
    ) -> None:
        """Send ``goal`` and track it instead of the one before (which is not cancelled)."""
        self.stop_tracking_goal()
        self.done_cb, self.active_cb, self.feedback_cb = done_cb, active_cb, feedback_cb
        self.simple_state = SimpleGoalState.PENDING
        self.gh = self.action_client.send_goal(goal, self._handle_transition, self._feedback)

    def send_goal_and_wait(
        self, goal: Any, execute_timeout: Any = None, preempt_timeout: Any = None
    ) -> int:
        """Send ``goal`` and wait for its end; cancel it after ``execute_timeout`` and wait
        ``preempt_timeout`` more. The goal's state (:meth:`get_state`)."""
        self.send_goal(goal)
        if not self.wait_for_result(execute_timeout):
            self.cancel_goal()
            self.wait_for_result(preempt_timeout)
        return self.get_state()

    def wait_for_result(self, timeout: Any = None) -> bool:
        """Wait until the goal is done; False after ``timeout`` (zero or None: no limit), at
        shutdown, or with no goal sent."""
        if self.gh is None:
            core.logerr("Called wait_for_result when no goal exists")
            return False
        timeout_s = seconds(timeout)
        end_s = get_rostime().to_sec() + timeout_s
        with self.done_condition:
            while not core.is_shutdown() and self.simple_state != SimpleGoalState.DONE:
                left_s = end_s - get_rostime().to_sec()
                if timeout_s > 0 and left_s <= 0:
                    break
                self.done_condition.wait(_LOOP_S if timeout_s == 0 else min(_LOOP_S, left_s))
        return self.simple_state == SimpleGoalState.DONE

    def get_result(self) -> Any:
        """The goal's result (an ``XResult``), None before it came or with no goal."""
        if self.gh is None:
            core.logerr("Called get_result when no goal is running")
            return None
        return self.gh.get_result()

    def get_state(self) -> int:
        """The goal's GoalStatus value (RECALLING reads PENDING, PREEMPTING reads ACTIVE, as
        actionlib); LOST with no goal."""
        if self.gh is None:
            return LOST
        status = self.gh.get_goal_status()
        return {RECALLING: PENDING, PREEMPTING: ACTIVE}.get(status, status)

    def get_goal_status_text(self) -> str:
        """The text the server gave with the goal's status."""
        if self.gh is None:
            core.logerr("Called get_goal_status_text when no goal is running")
            return "ERROR: Called get_goal_status_text when no goal is running"
        return self.gh.get_goal_status_text()

    def cancel_all_goals(self) -> None:
        self.action_client.cancel_all_goals()

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        self.action_client.cancel_goals_at_and_before_time(time)

    def cancel_goal(self) -> None:
        """Cancel the goal being tracked."""
        if self.gh is not None:
            self.gh.cancel()

    def stop_tracking_goal(self) -> None:
        """Forget the goal (no cancel): its callbacks are called no more."""
        self.gh = None

    def _handle_transition(self, gh: ClientGoalHandle) -> None:
        if gh != self.gh:
            return  # a goal no more tracked
        comm = gh.get_comm_state()
        if comm in (CommState.ACTIVE, CommState.PREEMPTING):
            if self.simple_state == SimpleGoalState.PENDING:
                self.simple_state = SimpleGoalState.ACTIVE
                if self.active_cb is not None:
                    self.active_cb()
            elif self.simple_state == SimpleGoalState.DONE:
                self._unexpected(comm)
        elif comm == CommState.RECALLING:
            if self.simple_state != SimpleGoalState.PENDING:
                self._unexpected(comm)
        elif comm == CommState.DONE:
            if self.simple_state == SimpleGoalState.DONE:
                core.logerr("SimpleActionClient received DONE twice")
                return
            if self.done_cb is not None:
                self.done_cb(gh.get_goal_status(), gh.get_result())
            with self.done_condition:
                self.simple_state = SimpleGoalState.DONE
                self.done_condition.notify_all()

    def _unexpected(self, comm: int) -> None:
        core.logerr(
            f"Received comm state {CommState.to_string(comm)} when in simple state "
            f"{SimpleGoalState.to_string(self.simple_state)} with SimpleActionClient in NS "
            f"{core.resolve_name(self.action_client.ns)}"
        )

    def _feedback(self, gh: ClientGoalHandle, feedback: Any) -> None:
        if self.gh is None or gh != self.gh:
            return
        if self.feedback_cb is not None:
            self.feedback_cb(feedback)
