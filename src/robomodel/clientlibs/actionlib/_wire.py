"""What the action server and client share: the classes of an action's messages, the
actionlib_msgs classes (rospy's genpy flavour), the action's topic names and stamps as
nanoseconds, and which peers the topics of a client are connected to."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from robomodel.clientlibs.actionlib.exceptions import ActionException
from robomodel.clientlibs.rospy import core

__all__ = [
    "ActionTypes",
    "action_types",
    "goal_id_class",
    "goal_status_array_class",
    "goal_status_class",
    "header_class",
    "nsec",
    "publisher_ids",
    "subscriber_ids",
    "topic",
]


@dataclass(frozen=True, slots=True)
class ActionTypes:
    """The classes of an action (genaction's ``FibonacciAction`` and the messages it holds)."""

    spec: type
    action_goal: type
    action_result: type
    action_feedback: type
    goal: type
    result: type
    feedback: type


def action_types(spec: Any) -> ActionTypes:
    """The message classes of the action class ``spec``; ActionException for a class that is
    no action (as actionlib: one with no ``action_goal``, ``action_result``,
    ``action_feedback``)."""
    try:
        made = spec()
        wrappers = (made.action_goal, made.action_result, made.action_feedback)
        parts = (wrappers[0].goal, wrappers[1].result, wrappers[2].feedback)
    except (AttributeError, TypeError):
        raise ActionException(
            f"Type is not an action spec: {spec!r} (give the action's class, as "
            f"from actionlib_tutorials.msg import FibonacciAction)"
        ) from None
    found = ActionTypes(spec, *(type(m) for m in wrappers), *(type(m) for m in parts))
    _check_ros1(found)
    return found


def _check_ros1(types: ActionTypes) -> None:
    """ActionException unless the action's messages have ROS 1 definitions: without, robomodel
    would keep its topics in the process, and no ROS 1 peer would ever be found."""
    from robomodel.runtime.transport.ros1.ros1_types import Ros1TypeError, ros1_type

    for cls in (types.action_goal, types.action_result, types.action_feedback):
        try:
            ros1_type(cls)
        except Ros1TypeError as exc:
            raise ActionException(
                f"{getattr(types.spec, '__typename__', types.spec)!s} cannot go over ROS 1: "
                f"{exc} (robomodel knows this action from a ROS 2 package only); put the ROS 1 "
                f"package's folder, with its action/ files, on ROS_PACKAGE_PATH"
            ) from None


def _genpy(typename: str) -> Any:
    from robomodel.clientlibs.messages import message_class

    return message_class(typename, "genpy")


def goal_id_class() -> Any:
    return _genpy("actionlib_msgs/msg/GoalID")


def goal_status_class() -> Any:
    return _genpy("actionlib_msgs/msg/GoalStatus")


def goal_status_array_class() -> Any:
    return _genpy("actionlib_msgs/msg/GoalStatusArray")


def header_class() -> Any:
    return _genpy("std_msgs/msg/Header")


def nsec(stamp: Any) -> int:
    """A stamp (any class with genpy's ``secs``/``nsecs``) in nanoseconds."""
    return int(stamp.secs) * 1_000_000_000 + int(stamp.nsecs)


def topic(ns: str, name: str) -> str:
    """The action's topic ``name`` (``goal``, ``status``...) under its namespace ``ns``,
    resolved as the node resolves ``ns`` (its remappings applied, as actionlib's
    ``remap_name(ns)``)."""
    return core.resolve_name(ns).rstrip("/") + "/" + name


def _transport() -> Any:
    node_state = core.state()
    return node_state.node.fully_qualified_name, node_state.context.transport


def subscriber_ids(resolved_topic: str) -> set[str]:
    """The caller ids of the subscribers connected now to this node's publisher of the topic."""
    node, transport = _transport()
    return set(transport.subscriber_ids(node, resolved_topic))


def publisher_ids(resolved_topic: str) -> set[str]:
    """The caller ids of the publishers this node's subscription of the topic reads now."""
    node, transport = _transport()
    return set(transport.publisher_ids(node, resolved_topic))
