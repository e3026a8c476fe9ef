"""actionlib on robomodel's rospy, server and client in one node of this process, on a master of
the module's own (TCPROS on loopback): the Fibonacci server and client as actionlib_tutorials
write them, preemption by a new goal and by a cancel, abort, ``wait_for_server`` with no server,
and the lower-level ActionServer's rejection, cancel by stamp and by everything, and its status
list keeping a finished goal for ``status_list_timeout``."""

from __future__ import annotations

import re
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import robomodel.clientlibs.actionlib as actionlib
import robomodel.clientlibs.rospy as rospy
from tests.clientlibs.rospy.inprocess_node import rospy_node
from tests.timing import scaled, wait_until

PACKAGES = Path(__file__).parent / "packages"
NODE = "/actiontest"
# actionlib's Python client: <caller id>-<count>-<seconds with 3 decimals>
GOAL_ID = re.compile(rf"^{NODE}-\d+-\d+\.\d{{3}}$")


@pytest.fixture(scope="module")
def node() -> Iterator[str]:
    """A rospy node of this process on a master of its own, actionlib_tutorials' package on
    the resolver's path; yields the master's URI."""
    with rospy_node(NODE, (PACKAGES,)) as uri:
        yield uri


def _classes() -> Any:
    from robomodel.clientlibs.messages import message_class

    return tuple(
        message_class(f"actionlib_tutorials/msg/Fibonacci{part}", "genpy")
        for part in ("Action", "Goal", "Result", "Feedback")
    )


class Fibonacci:
    """actionlib_tutorials' fibonacci_server, with a gate instead of its 1 Hz rate: each step
    waits for ``gate`` (set: run through) and looks for a preempt first, as the tutorial's."""

    def __init__(self, name: str) -> None:
        action, _, self.Result, self.Feedback = _classes()
        self.gate = threading.Event()
        self.gate.set()
        self.started = threading.Event()
        # paced: after each feedback, wait for the client to hear it (the tutorial's 1 Hz rate
        # does that, in effect: the result topic's thread must not overtake the feedback's)
        self.paced = False
        self.heard = threading.Event()
        self.preempts_seen: list[int] = []
        self.goal_ids: list[str] = []
        self.server = actionlib.SimpleActionServer(
            name, action, execute_cb=self.execute_cb, auto_start=False
        )
        self.server.start()

    def execute_cb(self, goal: Any) -> None:
        self.goal_ids.append(self.server.current_goal.get_goal_id().id)
        if goal.order == -2:
            raise ValueError("no sequence of order -2")
        if goal.order == -3:
            return  # no terminal state set: the server aborts the goal
        if goal.order < 0:
            self.server.set_aborted(text=f"order {goal.order} is below 0")
            return
        feedback = self.Feedback(sequence=[0, 1])
        self.started.set()
        for i in range(1, goal.order):
            while not self.gate.wait(0.01):
                if self.server.is_preempt_requested():
                    break
            if self.server.is_preempt_requested():
                self.preempts_seen.append(goal.order)
                self.server.set_preempted()
                return
            feedback.sequence.append(feedback.sequence[i] + feedback.sequence[i - 1])
            self.server.publish_feedback(feedback)
            if self.paced:
                self.heard.wait(scaled(10))
                self.heard.clear()
        self.server.set_succeeded(self.Result(sequence=feedback.sequence))

    def close(self) -> None:
        self.server.need_to_terminate = True
        self.gate.set()
        self.server.action_server.stop()


@pytest.fixture(scope="module")
def fibonacci(node: str) -> Iterator[Fibonacci]:
    server = Fibonacci("fibonacci")
    try:
        yield server
    finally:
        server.close()


@pytest.fixture
def client(fibonacci: Fibonacci) -> Iterator[actionlib.SimpleActionClient]:
    fibonacci.gate.set()
    fibonacci.started.clear()
    made = actionlib.SimpleActionClient("fibonacci", _classes()[0])
    assert made.wait_for_server(rospy.Duration(scaled(20)))
    try:
        yield made
    finally:
        made.action_client.stop()


def test_fibonacci_feedback_result_and_succeeded(
    fibonacci: Fibonacci, client: actionlib.SimpleActionClient
) -> None:
    from actionlib_msgs.msg import GoalStatus  # type: ignore[import-not-found]

    goal_class = _classes()[1]
    fibonacci.paced = True
    feedback: list[list[int]] = []
    done: list[tuple[int, Any]] = []
    active: list[int] = []
    client.send_goal(
        goal_class(order=6),
        done_cb=lambda state, result: done.append((state, result)),
        active_cb=lambda: active.append(client.simple_state),
        feedback_cb=lambda fb: (feedback.append(list(fb.sequence)), fibonacci.heard.set()),
    )
    try:
        assert client.wait_for_result(rospy.Duration(scaled(30)))
    finally:
        fibonacci.paced = False
    assert client.get_state() == GoalStatus.SUCCEEDED == 3
    assert list(client.get_result().sequence) == [0, 1, 1, 2, 3, 5, 8]
    assert feedback == [[0, 1, 1], [0, 1, 1, 2], [0, 1, 1, 2, 3], [0, 1, 1, 2, 3, 5],
                        [0, 1, 1, 2, 3, 5, 8]]  # fmt: skip
    assert [(s, list(r.sequence)) for s, r in done] == [(3, [0, 1, 1, 2, 3, 5, 8])]
    assert active == [actionlib.SimpleGoalState.ACTIVE]
    assert client.simple_state == actionlib.SimpleGoalState.DONE
    assert GOAL_ID.match(fibonacci.goal_ids[-1]), fibonacci.goal_ids
    assert client.gh is not None and client.gh.get_comm_state() == actionlib.CommState.DONE


def test_a_new_goal_preempts_the_running_one(
    fibonacci: Fibonacci, client: actionlib.SimpleActionClient
) -> None:
    _, goal_class, _, _ = _classes()
    fibonacci.gate.clear()
    first = actionlib.ActionClient("fibonacci", _classes()[0])
    try:
        assert first.wait_for_server(rospy.Duration(scaled(20)))
        transitions: list[int] = []
        handle = first.send_goal(
            goal_class(order=20), transition_cb=lambda gh: transitions.append(gh.get_comm_state())
        )
        wait_until(fibonacci.started.is_set, 20, what="the first goal running")
        wait_until(
            lambda: handle.get_comm_state() == actionlib.CommState.ACTIVE,
            20,
            what="the first goal active at its client",
        )
        fibonacci.started.clear()
        client.send_goal(goal_class(order=3))
        wait_until(
            lambda: handle.get_comm_state() == actionlib.CommState.DONE,
            20,
            what="the first goal's end",
        )
        assert handle.get_goal_status() == actionlib.GoalStatus.PREEMPTED
        assert handle.get_terminal_state() == actionlib.TerminalState.PREEMPTED
        # PENDING is heard only if a status came before the goal was accepted
        C = actionlib.CommState
        assert [t for t in transitions if t != C.PENDING] == [
            C.ACTIVE, C.PREEMPTING, C.WAITING_FOR_RESULT, C.DONE
        ]  # fmt: skip
        assert fibonacci.preempts_seen == [20]
        fibonacci.gate.set()
        assert client.wait_for_result(rospy.Duration(scaled(30)))
        assert client.get_state() == actionlib.GoalStatus.SUCCEEDED
        assert list(client.get_result().sequence) == [0, 1, 1, 2]
    finally:
        fibonacci.preempts_seen.clear()
        first.stop()


def test_cancel_goal_preempts(fibonacci: Fibonacci, client: actionlib.SimpleActionClient) -> None:
    fibonacci.gate.clear()
    client.send_goal(_classes()[1](order=10))
    wait_until(fibonacci.started.is_set, 20, what="the goal running")
    wait_until(
        lambda: client.get_state() == actionlib.GoalStatus.ACTIVE,
        20,
        what="the goal active at the client",
    )
    client.cancel_goal()
    assert client.wait_for_result(rospy.Duration(scaled(30)))
    assert client.get_state() == actionlib.GoalStatus.PREEMPTED
    assert fibonacci.preempts_seen == [10]
    fibonacci.preempts_seen.clear()


def test_abort_with_its_text(client: actionlib.SimpleActionClient) -> None:
    state = client.send_goal_and_wait(_classes()[1](order=-1), rospy.Duration(scaled(30)))
    assert state == actionlib.GoalStatus.ABORTED == 4
    assert client.get_goal_status_text() == "order -1 is below 0"
    assert list(client.get_result().sequence) == []


def test_an_execute_callback_that_raises_or_sets_no_end_aborts(
    client: actionlib.SimpleActionClient,
) -> None:
    goal_class = _classes()[1]
    state = client.send_goal_and_wait(goal_class(order=-2), rospy.Duration(scaled(30)))
    assert state == actionlib.GoalStatus.ABORTED
    text = "Exception in execute callback: no sequence of order -2"
    assert client.get_goal_status_text() == text
    state = client.send_goal_and_wait(goal_class(order=-3), rospy.Duration(scaled(30)))
    assert state == actionlib.GoalStatus.ABORTED
    assert client.get_goal_status_text() == "No terminal state was set."


def test_wait_for_server_without_a_server_times_out(node: str) -> None:
    nobody = actionlib.SimpleActionClient("nobody_serves_this", _classes()[0])
    try:
        start = time.monotonic()
        assert nobody.wait_for_server(rospy.Duration(0.5)) is False
        assert time.monotonic() - start >= 0.5
        assert nobody.get_state() == actionlib.GoalStatus.LOST  # no goal tracked
        assert nobody.wait_for_result(rospy.Duration(0.1)) is False
    finally:
        nobody.action_client.stop()


class Recorder:
    """A lower-level ActionServer that keeps its goal handles: the test moves them."""

    def __init__(self, name: str) -> None:
        self.handles: list[actionlib.ServerGoalHandle] = []
        self.cancels: list[str] = []
        self.server = actionlib.ActionServer(
            name, _classes()[0], self.handles.append, self._cancel, auto_start=False
        )
        self.server.start()

    def _cancel(self, handle: actionlib.ServerGoalHandle) -> None:
        self.cancels.append(handle.get_goal_id().id)


def _status_lists(ns: str) -> tuple[list[Any], Any]:
    heard: list[Any] = []
    from actionlib_msgs.msg import GoalStatusArray  # type: ignore[import-not-found]

    sub = rospy.Subscriber(f"{ns}/status", GoalStatusArray, heard.append)
    return heard, sub


def _states(message: Any) -> dict[str, int]:
    return {s.goal_id.id: s.status for s in message.status_list}


def test_action_server_reject_cancel_by_stamp_and_all_and_the_status_list(node: str) -> None:
    rospy.set_param("/lowlevel/status_list_timeout", 1.0)
    recorder = Recorder("lowlevel")
    heard, status_sub = _status_lists("/lowlevel")
    client = actionlib.ActionClient("lowlevel", _classes()[0])
    goal_class = _classes()[1]
    transitions: list[int] = []
    try:
        assert client.wait_for_server(rospy.Duration(scaled(20)))
        rejected = client.send_goal(
            goal_class(order=1), transition_cb=lambda gh: transitions.append(gh.get_comm_state())
        )
        wait_until(lambda: len(recorder.handles) == 1, 20, what="the first goal")
        recorder.handles[0].set_rejected(text="not today")
        wait_until(
            lambda: rejected.get_comm_state() == actionlib.CommState.DONE,
            20,
            what="the rejection at the client",
        )
        assert rejected.get_goal_status() == actionlib.GoalStatus.REJECTED
        assert rejected.get_goal_status_text() == "not today"
        C = actionlib.CommState
        assert transitions == [C.PENDING, C.WAITING_FOR_RESULT, C.DONE]
        # a finished goal stays in the status list for status_list_timeout, then goes
        rejected_id = recorder.handles[0].get_goal_id().id
        wait_until(
            lambda: bool(heard) and _states(heard[-1]).get(rejected_id) == 5,
            20,
            what="the rejected goal in the status list",
        )
        wait_until(
            lambda: rejected_id not in _states(heard[-1]),
            20,
            what="the rejected goal gone from the status list",
        )
        # three accepted goals: a cancel of the last by its id, then of those stamped at or
        # before the first, then of all
        handles = [client.send_goal(goal_class(order=n)) for n in (2, 3, 4)]
        wait_until(lambda: len(recorder.handles) == 4, 20, what="three more goals")
        for handle in recorder.handles[1:]:
            handle.set_accepted()
        wait_until(
            lambda: all(h.get_comm_state() == actionlib.CommState.ACTIVE for h in handles),
            20,
            what="both goals active",
        )
        ids = [h.get_goal_id().id for h in recorder.handles]
        handles[2].cancel()
        wait_until(lambda: len(recorder.cancels) == 1, 20, what="the cancel by id")
        assert recorder.cancels == [ids[3]]
        recorder.handles[3].set_canceled()
        first_stamp = recorder.handles[1].get_goal_id().stamp
        client.cancel_goals_at_and_before_time(first_stamp)
        wait_until(lambda: len(recorder.cancels) == 2, 20, what="the cancel by stamp")
        assert recorder.cancels[1:] == [ids[1]]
        assert recorder.handles[1].get_goal_status().status == actionlib.GoalStatus.PREEMPTING
        assert recorder.handles[2].get_goal_status().status == actionlib.GoalStatus.ACTIVE
        recorder.handles[1].set_canceled()
        client.cancel_all_goals()
        wait_until(lambda: len(recorder.cancels) == 3, 20, what="the cancel of all")
        assert recorder.cancels[2:] == [ids[2]]  # the others are done: no callback
        recorder.handles[2].set_succeeded(text="finished anyway")
        wait_until(
            lambda: all(h.get_comm_state() == actionlib.CommState.DONE for h in handles),
            20,
            what="the three goals done",
        )
        assert [h.get_goal_status() for h in handles] == [2, 3, 2]  # PREEMPTED, SUCCEEDED
        assert handles[1].get_goal_status_text() == "finished anyway"
        assert all(GOAL_ID.match(h.get_goal_id().id) for h in recorder.handles)
    finally:
        client.stop()
        status_sub.unregister()
        recorder.server.stop()
        rospy.delete_param("/lowlevel/status_list_timeout")


def test_a_cancel_before_its_goal_recalls_the_goal(node: str) -> None:
    """A cancel of an id the server has not seen is kept: the goal is RECALLED when it comes
    and no callback sees it."""
    from actionlib_msgs.msg import GoalID  # type: ignore[import-not-found]

    recorder = Recorder("early_cancel")
    goal_class = _classes()[1]
    action_goal_class = type(_classes()[0]().action_goal)
    client = actionlib.ActionClient("early_cancel", _classes()[0])
    results: list[Any] = []
    watcher = rospy.Subscriber("/early_cancel/result", client.ActionResult, results.append)
    try:
        assert client.wait_for_server(rospy.Duration(scaled(20)))
        wait_until(lambda: watcher.get_num_connections() == 1, 20, what="result link")
        client.pub_cancel.publish(GoalID(id="/elsewhere-1-0.000"))
        wait_until(
            lambda: any(
                s.goal_id.id == "/elsewhere-1-0.000" and s.status == 7
                for s in [t.status for t in recorder.server.status_list]
            ),
            scaled(20),
            what="the cancel kept as RECALLING",
        )
        client.pub_goal.publish(
            action_goal_class(goal_id=GoalID(id="/elsewhere-1-0.000"), goal=goal_class(order=4))
        )
        wait_until(lambda: results, 20, what="the recalled goal's result")
        assert results[0].status.goal_id.id == "/elsewhere-1-0.000"
        assert results[0].status.status == actionlib.GoalStatus.RECALLED
        assert recorder.handles == []
    finally:
        watcher.unregister()
        client.stop()
        recorder.server.stop()


def test_every_exported_name_resolves() -> None:
    import importlib

    module = importlib.import_module("actionlib")
    assert module is actionlib
    for name in actionlib.__all__:
        assert getattr(module, name) is not None, name
    assert actionlib.CommState.to_string(actionlib.CommState.DONE) == "DONE"
    assert actionlib.SimpleGoalState.to_string(1) == "ACTIVE"
    with pytest.raises(actionlib.ActionException, match="not an action spec"):
        actionlib.ActionClient("x", importlib.import_module("actionlib.msg").TestGoal)


def test_wait_for_server_needs_all_five_topics_of_one_server(node: str) -> None:
    """A node with the status, goal, cancel and feedback topics of an action but no result
    publisher is no server yet; it is once that comes (actionlib's check of the
    connections)."""
    from actionlib_msgs.msg import GoalID, GoalStatusArray  # type: ignore[import-not-found]

    action = _classes()[0]()
    status = rospy.Publisher("/half/status", GoalStatusArray, latch=True, queue_size=1)
    status.publish(GoalStatusArray())
    parts: list[Any] = [
        status,
        rospy.Subscriber("/half/goal", type(action.action_goal)),
        rospy.Subscriber("/half/cancel", GoalID),
        rospy.Publisher("/half/feedback", type(action.action_feedback), queue_size=1),
    ]
    client = actionlib.SimpleActionClient("half", _classes()[0])
    try:
        wait_until(
            lambda: client.action_client.last_status_msg is not None,
            20,
            what="the status heard",
        )
        assert client.wait_for_server(rospy.Duration(0.5)) is False
        parts.append(rospy.Publisher("/half/result", type(action.action_result), queue_size=1))
        assert client.wait_for_server(rospy.Duration(scaled(20))) is True
    finally:
        client.action_client.stop()
        for part in parts:
            part.unregister()


def test_status_is_published_at_actionlib_status_frequency(fibonacci: Fibonacci) -> None:
    """5 Hz by default (the Fibonacci server's); the ``actionlib_status_frequency`` parameter
    (found up the node's namespaces) sets it. Lower bounds only: a loaded machine may be late,
    never early."""
    import time as clock

    heard_default, default_sub = _status_lists("/fibonacci")
    try:
        wait_until(lambda: len(heard_default) >= 7, 20, what="status at 5 Hz")
    finally:
        default_sub.unregister()
    rospy.set_param("/actionlib_status_frequency", 1.0)
    slow = Recorder("slow_status")
    heard, sub = _status_lists("/slow_status")
    try:
        wait_until(lambda: heard, 20, what="the latched status")
        start = clock.monotonic()
        wait_until(lambda: len(heard) >= 4, 20, what="three periodic status messages")
        # the first may follow the latched one closely, the next two are 1 s apart at least
        assert clock.monotonic() - start >= 1.5  # at 5 Hz all three would take 0.6 s
        assert slow.server.status_frequency == 1.0
    finally:
        sub.unregister()
        slow.server.stop()
        rospy.delete_param("/actionlib_status_frequency")


def test_search_param_finds_none_as_rospy(node: str) -> None:
    """actionlib looks for ``actionlib_status_frequency`` with ``search_param``: a parameter
    set nowhere is None (the master's code -1), as rospy's, not an error."""
    assert rospy.search_param("no_such_parameter_anywhere") is None
    rospy.set_param("/upper/found_here", 1)
    try:
        assert rospy.search_param("found_here") is None  # the node is /actiontest, in /
        assert rospy.search_param("upper") == "/upper"
    finally:
        rospy.delete_param("/upper/found_here")


def test_an_action_without_ros1_definitions_is_refused_with_what_to_do() -> None:
    """ParallelGripperCommand is a ROS 2 action of control_msgs, with no ROS 1 definition: the
    client says so instead of waiting for a server it could never reach."""
    from robomodel.clientlibs.messages import message_class

    action = message_class("control_msgs/msg/ParallelGripperCommandAction", "genpy")
    with pytest.raises(actionlib.ActionException, match=r"cannot go over ROS 1.*ROS_PACKAGE_PATH"):
        actionlib.SimpleActionClient("/arm_controller/follow_joint_trajectory", action)
