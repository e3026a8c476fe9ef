"""actionlib's ``SimpleActionServer``: one goal at a time. A new goal preempts the current one
(``is_preempt_requested()`` turns true, the preempt callback is called) and waits to be
accepted; a goal stamped before the current or next goal is cancelled at once.

With an ``execute_cb``, a thread of the server (as actionlib's) accepts each new goal and calls
``execute_cb(goal)``; a callback that returns without setting the goal's end aborts it ("No
terminal state was set."), one that raises aborts it with the exception's text. Without one,
``register_goal_callback`` and ``accept_new_goal`` drive it.
"""

from __future__ import annotations

import threading
import traceback
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.actionlib import _wire
from robomodel.clientlibs.actionlib.action_server import (
    ACTIVE,
    PREEMPTING,
    ActionServer,
    ServerGoalHandle,
)
from robomodel.clientlibs.rospy import core

__all__ = ["SimpleActionServer"]

_LOOP_S = 0.1  # how often the execute thread looks at the shutdown flag, as actionlib's
_REPLACED = "This goal was canceled because another goal was received by the simple action server"


class SimpleActionServer:
    """A one-goal-at-a-time action server on ``name`` for the action class ``ActionSpec``."""

    def __init__(
        self,
        name: str,
        ActionSpec: Any,
        execute_cb: Callable[[Any], Any] | None = None,
        auto_start: bool = True,
    ) -> None:
        self.new_goal = False
        self.preempt_request = False
        self.new_goal_preempt_request = False
        self.execute_callback = execute_cb
        self.goal_callback: Callable[[], Any] | None = None
        self.preempt_callback: Callable[[], Any] | None = None
        self.need_to_terminate = False
        # the action server's lock is always taken before this one (its callbacks hold it)
        self.lock = threading.RLock()
        self.execute_condition = threading.Condition(self.lock)
        self.current_goal = ServerGoalHandle()
        self.next_goal = ServerGoalHandle()
        self.execute_thread: threading.Thread | None = None
        if execute_cb is not None:
            self.execute_thread = threading.Thread(
                target=self._execute_loop, name=f"actionlib execute {name}", daemon=True
            )
            self.execute_thread.start()
        self.action_server = ActionServer(
            name, ActionSpec, self._goal_arrived, self._preempt_arrived, auto_start
        )

    def start(self) -> None:
        """Start the server (made with ``auto_start=False``)."""
        self.action_server.start()

    def accept_new_goal(self) -> Any:
        """Accept the goal waiting (preempting the current one) and return it (an ``XGoal``);
        None, logged, when none waits."""
        with self.action_server.lock, self.lock:
            if not self.new_goal or self.next_goal.get_goal() is None:
                core.logerr("Attempting to accept the next goal when a new goal is not available")
                return None
            if (
                self.is_active()
                and self.current_goal.get_goal() is not None
                and self.current_goal != self.next_goal
            ):
                self.current_goal.set_canceled(None, _REPLACED)
            self.current_goal = self.next_goal
            self.new_goal = False
            self.preempt_request = self.new_goal_preempt_request
            self.new_goal_preempt_request = False
            self.current_goal.set_accepted(
                "This goal has been accepted by the simple action server"
            )
            return self.current_goal.get_goal()

    def is_new_goal_available(self) -> bool:
        return self.new_goal

    def is_preempt_requested(self) -> bool:
        return self.preempt_request

    def is_active(self) -> bool:
        """Whether the current goal is ACTIVE or PREEMPTING."""
        if self.current_goal.get_goal() is None:
            return False
        return int(self.current_goal.get_goal_status().status) in (ACTIVE, PREEMPTING)

    def get_default_result(self) -> Any:
        return self.action_server.ActionResultType()

    def set_succeeded(self, result: Any = None, text: str = "") -> None:
        with self.action_server.lock, self.lock:
            self.current_goal.set_succeeded(self._result(result), text)

    def set_aborted(self, result: Any = None, text: str = "") -> None:
        with self.action_server.lock, self.lock:
            self.current_goal.set_aborted(self._result(result), text)

    def set_preempted(self, result: Any = None, text: str = "") -> None:
        with self.action_server.lock, self.lock:
            self.current_goal.set_canceled(self._result(result), text)

    def _result(self, result: Any) -> Any:
        return self.get_default_result() if result is None else result

    def publish_feedback(self, feedback: Any) -> None:
        self.current_goal.publish_feedback(feedback)

    def register_goal_callback(self, cb: Callable[[], Any]) -> None:
        """Call ``cb()`` when a new goal is available; not with an ``execute_cb`` (warned)."""
        if self.execute_callback is not None:
            core.logwarn(
                "Cannot call SimpleActionServer.register_goal_callback() because an "
                "executeCallback exists. Not going to register it."
            )
            return
        self.goal_callback = cb

    def register_preempt_callback(self, cb: Callable[[], Any]) -> None:
        """Call ``cb()`` when the current goal is asked to stop (a cancel, a newer goal)."""
        self.preempt_callback = cb

    # -- the action server's callbacks ---------------------------------------------------------
    def _goal_arrived(self, goal: ServerGoalHandle) -> None:
        with self.execute_condition:
            stamp_ns = _wire.nsec(goal.get_goal_id().stamp)
            newer = all(
                held.get_goal() is None or stamp_ns >= _wire.nsec(held.get_goal_id().stamp)
                for held in (self.current_goal, self.next_goal)
            )
            if not newer:  # a newer goal came already: this one is over before it began
                goal.set_canceled(None, _REPLACED)
                return
            if self.next_goal.get_goal() is not None and (
                self.current_goal.get_goal() is None or self.next_goal != self.current_goal
            ):
                self.next_goal.set_canceled(None, _REPLACED)
            self.next_goal = goal
            self.new_goal = True
            self.new_goal_preempt_request = False
            if self.is_active():
                self.preempt_request = True
                if self.preempt_callback is not None:
                    self.preempt_callback()
            if self.goal_callback is not None:
                self.goal_callback()
            self.execute_condition.notify()

    def _preempt_arrived(self, preempt: ServerGoalHandle) -> None:
        with self.lock:
            if preempt == self.current_goal:
                self.preempt_request = True
                if self.preempt_callback is not None:
                    self.preempt_callback()
            elif preempt == self.next_goal:
                self.new_goal_preempt_request = True

    def _execute_loop(self) -> None:
        assert self.execute_callback is not None
        while not core.is_shutdown() and not self.need_to_terminate:
            if self.is_active():
                core.logerr("Should never reach this code with an active goal")
                return
            if self.is_new_goal_available():
                goal = self.accept_new_goal()
                try:
                    self.execute_callback(goal)
                    if self.is_active():
                        core.logwarn(
                            "Your executeCallback did not set the goal to a terminal status.  "
                            "This is a bug in your ActionServer implementation. Fix your code!  "
                            "For now, the ActionServer will set this goal to aborted"
                        )
                        self.set_aborted(None, "No terminal state was set.")
                except Exception as exc:
                    core.logerr(
                        f"Exception in your execute callback: {exc}\n{traceback.format_exc()}"
                    )
                    self.set_aborted(None, f"Exception in execute callback: {exc}")
            with self.execute_condition:
                if not self.new_goal:
                    self.execute_condition.wait(_LOOP_S)
