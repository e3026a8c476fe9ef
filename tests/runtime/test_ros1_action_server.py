"""The ROS 1 action server's protocol (actionlib's), in one process: statuses, results,
feedback, rejection, and the cancel rules (every goal, by stamp, by id, before the goal)."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import pytest

from robomodel.runtime import Context
from robomodel.runtime.msg import Time, get_message_type
from robomodel.runtime.msg.types.action_msgs import GoalStatus as Ros2Status
from robomodel.runtime.ros1_action_server import (
    ABORTED,
    ACTIVE,
    PENDING,
    PREEMPTED,
    RECALLED,
    REJECTED,
    SUCCEEDED,
    Ros1ActionServer,
)
from tests.timing import wait_until

ACTION_GOAL = get_message_type("control_msgs/msg/FollowJointTrajectoryActionGoal")
RESULT = get_message_type("control_msgs/msg/FollowJointTrajectoryResult")
FEEDBACK = get_message_type("control_msgs/msg/FollowJointTrajectoryFeedback")
GOAL_ID = get_message_type("actionlib_msgs/msg/GoalID")
STATUS_ARRAY = get_message_type("actionlib_msgs/msg/GoalStatusArray")
ACTION_RESULT = get_message_type("control_msgs/msg/FollowJointTrajectoryActionResult")
ACTION_FEEDBACK = get_message_type("control_msgs/msg/FollowJointTrajectoryActionFeedback")


@dataclass
class Job:
    """An ActionGoal whose status the test sets (ROS 2's statuses, as the controller's)."""

    state: int = Ros2Status.STATUS_EXECUTING
    cancelled: bool = False

    def status(self) -> int:
        return self.state

    def result(self) -> Any:
        return get_message_type("control_msgs/action/FollowJointTrajectory_Result")(
            error_code=0, error_string="done"
        )

    def feedback(self) -> Any:
        return get_message_type("control_msgs/action/FollowJointTrajectory_Feedback")(
            joint_names=["a"]
        )

    def cancel(self) -> bool:
        self.cancelled = True
        self.state = Ros2Status.STATUS_CANCELED
        return True


@dataclass
class Bench:
    ctx: Context
    jobs: list[Job] = field(default_factory=list)
    results: list[Any] = field(default_factory=list)
    feedback: list[Any] = field(default_factory=list)
    statuses: list[Any] = field(default_factory=list)
    accept_next: bool = True
    server: Any = None
    goal_pub: Any = None
    cancel_pub: Any = None

    def send(self, goal_id: str, stamp_s: int = 0) -> None:
        msg = ACTION_GOAL(goal_id=GOAL_ID(stamp=Time(stamp_s, 0), id=goal_id))
        self.goal_pub.publish(msg)
        self.ctx.spin_once(0.01)

    def cancel(self, goal_id: str = "", stamp_s: int = 0) -> None:
        self.cancel_pub.publish(GOAL_ID(stamp=Time(stamp_s, 0), id=goal_id))
        self.ctx.spin_once(0.01)

    def tick(self) -> None:
        self.server._monitor()
        self.ctx.spin_once(0.01)

    def result_of(self, goal_id: str) -> Any:
        found = [r for r in self.results if r.status.goal_id.id == goal_id]
        assert len(found) == 1, [r.status.goal_id.id for r in self.results]
        return found[0]

    def last_status(self, goal_id: str) -> int:
        for array in reversed(self.statuses):
            for entry in array.status_list:
                if entry.goal_id.id == goal_id:
                    return int(entry.status)
        raise AssertionError(f"no status of {goal_id}")


@pytest.fixture
def bench() -> Iterator[Bench]:
    ctx = Context()
    found = Bench(ctx)
    node = ctx.create_node("controller")

    def accept(goal: Any) -> Job | None:
        if not found.accept_next:
            return None
        job = Job()
        found.jobs.append(job)
        return job

    found.server = Ros1ActionServer(
        node, "control_msgs/FollowJointTrajectory", "/arm/follow", accept,
        rejected=lambda g: RESULT(error_code=-1, error_string="bad goal"), monitor_rate_hz=1e-3,
    )  # fmt: skip
    client = ctx.create_node("client")
    found.goal_pub = client.create_publisher(ACTION_GOAL, "/arm/follow/goal", 50)
    found.cancel_pub = client.create_publisher(GOAL_ID, "/arm/follow/cancel", 50)
    client.create_subscription(ACTION_RESULT, "/arm/follow/result", found.results.append, 50)
    client.create_subscription(ACTION_FEEDBACK, "/arm/follow/feedback", found.feedback.append, 50)
    client.create_subscription(STATUS_ARRAY, "/arm/follow/status", found.statuses.append, 50)
    yield found
    ctx.shutdown()


def test_a_goal_runs_gives_feedback_and_succeeds_with_its_result(bench: Bench) -> None:
    bench.send("g1", 1)
    bench.tick()
    assert bench.last_status("g1") == ACTIVE
    assert bench.feedback and bench.feedback[-1].feedback.joint_names == ["a"]
    assert bench.feedback[-1].status.status == ACTIVE
    bench.jobs[0].state = Ros2Status.STATUS_SUCCEEDED
    bench.tick()
    done = bench.result_of("g1")
    assert done.status.status == SUCCEEDED and done.result.error_string == "done"
    assert bench.last_status("g1") == SUCCEEDED
    bench.jobs[0].state = Ros2Status.STATUS_ABORTED  # an ended goal's result goes out once
    bench.tick()
    assert len(bench.results) == 1


def test_an_accepted_goal_that_has_not_run_is_pending_and_an_abort_is_aborted(
    bench: Bench,
) -> None:
    bench.send("g1", 1)
    bench.jobs[0].state = Ros2Status.STATUS_ACCEPTED
    bench.tick()
    assert bench.last_status("g1") == PENDING
    bench.jobs[0].state = Ros2Status.STATUS_ABORTED
    bench.tick()
    assert bench.result_of("g1").status.status == ABORTED


def test_a_refused_goal_is_rejected_with_the_rejection_result(bench: Bench) -> None:
    bench.accept_next = False
    bench.send("g1", 1)
    done = bench.result_of("g1")
    assert done.status.status == REJECTED
    assert (done.result.error_code, done.result.error_string) == (-1, "bad goal")


def test_a_goal_sent_twice_is_served_once(bench: Bench) -> None:
    bench.send("g1", 1)
    bench.send("g1", 1)
    assert len(bench.jobs) == 1


def test_cancel_by_id_preempts_that_goal_only(bench: Bench) -> None:
    bench.send("g1", 1)
    bench.send("g2", 2)
    bench.tick()
    bench.cancel("g1")
    assert [j.cancelled for j in bench.jobs] == [True, False]
    assert bench.result_of("g1").status.status == PREEMPTED


def test_cancel_by_stamp_takes_the_goals_stamped_at_or_before_it(bench: Bench) -> None:
    for n in (1, 2, 3):
        bench.send(f"g{n}", n)
    bench.tick()
    bench.cancel(stamp_s=2)
    assert [j.cancelled for j in bench.jobs] == [True, True, False]
    bench.send("g0", 1)  # a goal stamped before the last cancel's stamp is recalled on arrival
    assert bench.result_of("g0").status.status == RECALLED
    assert len(bench.jobs) == 3


def test_an_empty_cancel_takes_every_goal(bench: Bench) -> None:
    for n in (1, 2):
        bench.send(f"g{n}", n)
    bench.cancel()
    assert all(j.cancelled for j in bench.jobs)


def test_a_goal_cancelled_before_it_came_is_recalled(bench: Bench) -> None:
    bench.cancel("early")
    bench.send("early", 5)
    assert bench.result_of("early").status.status == RECALLED
    assert not bench.jobs


def test_a_goal_without_an_id_gets_one_from_the_server(bench: Bench) -> None:
    bench.send("", 0)
    bench.tick()
    ids = [e.goal_id.id for e in bench.statuses[-1].status_list]
    assert len(ids) == 1 and ids[0].startswith("/controller-1-")


def test_a_flood_of_goals_keeps_a_bounded_status_list(bench: Bench) -> None:
    """Goals that end at once (refused ones) stay in the status list for its timeout, but no
    more than MAX_ENDED_GOALS of them: a flood is not kept for seconds."""
    from robomodel.runtime.ros1_action_server import MAX_ENDED_GOALS

    bench.accept_next = False
    for n in range(MAX_ENDED_GOALS + 50):
        bench.send(f"g{n}", n + 1)
    bench.tick()
    listed = [e.goal_id.id for e in bench.statuses[-1].status_list]
    assert len(listed) == MAX_ENDED_GOALS
    assert listed[-1] == f"g{MAX_ENDED_GOALS + 49}"  # the newest kept, the oldest gone
    assert len(bench.results) == MAX_ENDED_GOALS + 50


def test_the_status_list_also_goes_out_periodically(bench: Bench) -> None:
    """actionlib's clients learn of a server from its status topic: the list is published at
    STATUS_HZ even when nothing changes (the fixture's monitor never runs on its own)."""
    bench.send("g1", 1)
    before = len(bench.statuses)

    def two_more() -> bool:
        bench.ctx.spin_once(0.05)
        return len(bench.statuses) >= before + 2

    wait_until(two_more, 10, what="two status lists with no change")
    assert bench.last_status("g1") == ACTIVE
