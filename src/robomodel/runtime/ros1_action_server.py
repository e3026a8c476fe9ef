"""ROS 1 actions as actionlib's ``ActionServer`` serves them, for robomodel's own action
servers (the joint trajectory controller's ``follow_joint_trajectory``) on a ROS 1 graph, so
that actionlib clients (rospy's and roscpp's ``SimpleActionClient``, MoveIt) reach them.

Under the action's namespace, genaction's messages of the ROS 1 action ``pkg/Name``: the
topics ``goal`` (``pkg/NameActionGoal``) and ``cancel`` (``actionlib_msgs/GoalID``) in, and
``status`` (``actionlib_msgs/GoalStatusArray``, at ``STATUS_HZ`` and on every change),
``feedback`` (``pkg/NameActionFeedback``) and ``result`` (``pkg/NameActionResult``) out.

The server is given the same ``accept(goal) -> ActionGoal | None`` as the ROS 2 server
(:class:`~robomodel.runtime.action_server.ActionServer`), and polls what it returns at
``monitor_rate_hz``. The ROS 2 statuses it reports are actionlib's: accepted is PENDING,
executing ACTIVE, canceling PREEMPTING (RECALLING before it ran), canceled PREEMPTED
(RECALLED), and a goal ``accept`` refuses is REJECTED, with ``rejected(goal)``'s result. The
cancel message follows actionlib's rules: an empty id and a zero stamp cancel every goal, a
stamp those stamped at or before it, an id that goal, also when it comes before the goal (the
goal is then recalled on arrival). Ended goals stay in the status list for
``STATUS_LIST_TIMEOUT_S``, as actionlib's ``status_list_timeout``.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robomodel.runtime.action_server import ActionGoal
from robomodel.runtime.msg import Header, Message, get_message_type
from robomodel.runtime.msg.types.action_msgs import GoalStatus as Ros2Status

if TYPE_CHECKING:
    from robomodel.runtime.node import Node

__all__ = ["STATUS_HZ", "STATUS_LIST_TIMEOUT_S", "Ros1ActionServer", "converted", "ros1_status"]

STATUS_HZ = 5.0  # actionlib's actionlib_status_frequency default
STATUS_LIST_TIMEOUT_S = 5.0  # actionlib's status_list_timeout default
MAX_EARLY_CANCELS = 100  # ids cancelled before their goal came, kept to recall it
MAX_ENDED_GOALS = 100  # ended goals in the status list at most, as the ROS 2 server keeps

# actionlib_msgs/GoalStatus
PENDING, ACTIVE, PREEMPTED, SUCCEEDED, ABORTED, REJECTED = 0, 1, 2, 3, 4, 5
PREEMPTING, RECALLING, RECALLED = 6, 7, 8
_ENDED = {PREEMPTED, SUCCEEDED, ABORTED, REJECTED, RECALLED}


def ros1_status(ros2_status: int, ran: bool) -> int:
    """actionlib's status of a goal the ROS 2 way reports as ``ros2_status``; ``ran``: it
    was ever executing (a cancel then preempts it, else recalls it)."""
    if ros2_status == Ros2Status.STATUS_EXECUTING:
        return ACTIVE
    if ros2_status == Ros2Status.STATUS_CANCELING:
        return PREEMPTING if ran else RECALLING
    if ros2_status == Ros2Status.STATUS_CANCELED:
        return PREEMPTED if ran else RECALLED
    if ros2_status == Ros2Status.STATUS_SUCCEEDED:
        return SUCCEEDED
    if ros2_status == Ros2Status.STATUS_ABORTED:
        return ABORTED
    return PENDING


def converted(cls: type[Message], msg: Message) -> Message:
    """``msg`` as a ``cls``, field by field: the action's ROS 2 result or feedback as the ROS 1
    message of the same fields (genaction's ``NameResult`` or ``NameFeedback``)."""
    if isinstance(msg, cls):
        return msg
    return cls(**{name: getattr(msg, name) for name, _ in cls.__fields__})


@dataclass(eq=False)
class _Goal:
    goal_id: Any  # actionlib_msgs/GoalID
    goal: ActionGoal | None  # None: rejected or recalled before it ran
    status: int
    ran: bool = False
    ended_ns: int | None = None  # when it ended (node time), for the status list's timeout


class Ros1ActionServer:
    """Serves the ROS 1 action ``action`` (``pkg/Name``) as ``name`` on ``node`` (see the
    module docstring)."""

    def __init__(
        self,
        node: Node,
        action: str,
        name: str,
        accept: Callable[[Any], ActionGoal | None],
        *,
        rejected: Callable[[Any], Message] | None = None,
        monitor_rate_hz: float = 20.0,
    ) -> None:
        package, action_name = action.split("/")
        self._node = node
        self._accept = accept
        self._rejected = rejected
        # classes built from the definitions at run time: their fields are known only then
        types: dict[str, Any] = {
            part: get_message_type(f"{package}/msg/{action_name}{part}")
            for part in ("ActionGoal", "ActionFeedback", "ActionResult", "Feedback", "Result")
        }
        self._types = types
        self._goal_id: Any = get_message_type("actionlib_msgs/msg/GoalID")
        self._status_msg: Any = get_message_type("actionlib_msgs/msg/GoalStatus")
        self._status_array: Any = get_message_type("actionlib_msgs/msg/GoalStatusArray")
        self._goals: dict[str, _Goal] = {}
        self._early_cancels: dict[str, None] = {}
        self._last_cancel_ns = 0
        self._ids = itertools.count(1)
        base = node.resolve_topic_name(name).rstrip("/")
        self._status = node.create_publisher(self._status_array, f"{base}/status", 50)
        self._feedback = node.create_publisher(types["ActionFeedback"], f"{base}/feedback", 50)
        self._result = node.create_publisher(types["ActionResult"], f"{base}/result", 50)
        self._subscriptions = [
            node.create_subscription(types["ActionGoal"], f"{base}/goal", self._on_goal, 50),
            node.create_subscription(self._goal_id, f"{base}/cancel", self._on_cancel, 50),
        ]
        self._timers = [
            node.create_timer(1.0 / monitor_rate_hz, self._monitor),
            node.create_timer(1.0 / STATUS_HZ, self._publish_status),
        ]

    # -- goals and cancels ---------------------------------------------------------------------
    def _on_goal(self, msg: Any) -> None:
        now = self._node.now()
        goal_id = msg.goal_id
        if not goal_id.id:  # actionlib's server names a goal its client did not
            goal_id = self._goal_id(stamp=now, id=f"{self._node.fully_qualified_name}-"
                                    f"{next(self._ids)}-{now.sec}.{now.nanosec}")  # fmt: skip
        elif goal_id.stamp.sec == 0 and goal_id.stamp.nanosec == 0:
            goal_id = self._goal_id(stamp=now, id=goal_id.id)
        if goal_id.id in self._goals:
            return  # a goal sent twice is served once, as actionlib's
        stamp_ns = goal_id.stamp.to_nanoseconds()
        if goal_id.id in self._early_cancels or (stamp_ns and stamp_ns <= self._last_cancel_ns):
            self._early_cancels.pop(goal_id.id, None)
            self._end(_Goal(goal_id, None, RECALLED), self._types["Result"]())
            return
        taken = self._accept(msg.goal)
        if taken is None:
            result = self._rejected(msg.goal) if self._rejected else self._types["Result"]()
            self._end(_Goal(goal_id, None, REJECTED), result)
            return
        self._goals[goal_id.id] = _Goal(goal_id, taken, PENDING)
        self._monitor()

    def _on_cancel(self, msg: Any) -> None:
        stamp_ns = msg.stamp.to_nanoseconds()
        if not msg.id and not stamp_ns:
            chosen = list(self._goals.values())
        else:
            chosen = [
                g for i, g in self._goals.items()
                if i == msg.id or (stamp_ns and g.goal_id.stamp.to_nanoseconds() <= stamp_ns)
            ]  # fmt: skip
            if msg.id and msg.id not in self._goals:
                self._early_cancels[msg.id] = None
                while len(self._early_cancels) > MAX_EARLY_CANCELS:
                    del self._early_cancels[next(iter(self._early_cancels))]
        self._last_cancel_ns = max(self._last_cancel_ns, stamp_ns)
        for entry in chosen:
            if entry.goal is not None and entry.status not in _ENDED:
                entry.goal.cancel()
        self._monitor()

    # -- monitoring ----------------------------------------------------------------------------
    def _monitor(self) -> None:
        """Publish feedback of active goals, the result of goals that ended, and the status
        list on a change (its own timer publishes it at ``STATUS_HZ`` too)."""
        changed = False
        for entry in list(self._goals.values()):
            if entry.goal is None or entry.status in _ENDED:
                continue
            reported = entry.goal.status()
            entry.ran = entry.ran or reported == Ros2Status.STATUS_EXECUTING
            status = ros1_status(reported, entry.ran)
            if status == ACTIVE:
                feedback = entry.goal.feedback()
                if feedback is not None:
                    self._feedback.publish(
                        self._types["ActionFeedback"](
                            self._header(), self._status_of(entry, status),
                            converted(self._types["Feedback"], feedback),
                        )
                    )  # fmt: skip
            if status != entry.status:
                changed = True
                if status in _ENDED:
                    self._end(entry, entry.goal.result(), status)
                else:
                    entry.status = status
        self._forget_ended()
        if changed:
            self._publish_status()

    def _end(self, entry: _Goal, result: Message, status: int | None = None) -> None:
        """``entry`` ended (with ``status``, or its own): its result goes out, and it stays
        in the status list for ``STATUS_LIST_TIMEOUT_S``."""
        if status is not None:
            entry.status = status
        entry.ended_ns = self._node.now().to_nanoseconds()
        self._goals[entry.goal_id.id] = entry
        self._forget_ended()
        self._result.publish(
            self._types["ActionResult"](
                self._header(), self._status_of(entry, entry.status),
                converted(self._types["Result"], result),
            )
        )  # fmt: skip
        self._publish_status()

    def _forget_ended(self) -> None:
        """Ended goals leave the status list after ``STATUS_LIST_TIMEOUT_S``, and the oldest
        first past ``MAX_ENDED_GOALS`` (a flood of goals is not kept for seconds)."""
        oldest = self._node.now().to_nanoseconds() - int(STATUS_LIST_TIMEOUT_S * 1e9)
        ended = [(k, g.ended_ns) for k, g in self._goals.items() if g.ended_ns is not None]
        for number, (key, ended_ns) in enumerate(ended):
            if len(ended) - number > MAX_ENDED_GOALS or ended_ns < oldest:
                del self._goals[key]

    def _publish_status(self) -> None:
        self._status.publish(
            self._status_array(
                self._header(), [self._status_of(g, g.status) for g in self._goals.values()]
            )
        )

    def _status_of(self, entry: _Goal, status: int) -> Any:
        return self._status_msg(goal_id=entry.goal_id, status=status, text="")

    def _header(self) -> Header:
        return Header(stamp=self._node.now())

    def destroy(self) -> None:
        for timer in self._timers:
            timer.cancel()
        for subscription in self._subscriptions:
            subscription.destroy()
        for publisher in (self._status, self._feedback, self._result):
            publisher.destroy()
