"""The message definitions an ``.action`` file gives, for the resolver.

An ``.action`` file is three message definitions split by lines ``---``: the goal, the result
and the feedback (:func:`.definition.split_parts`).

ROS 2 names them ``pkg/action/Name_Goal``, ``_Result`` and ``_Feedback`` and derives two
services and a message from them (:mod:`.action`). ROS 1's genaction (actionlib_msgs'
``genaction.py``) names them ``pkg/NameGoal``, ``pkg/NameResult`` and ``pkg/NameFeedback`` and
wraps each for the action's topics::

    NameActionGoal:     Header header, actionlib_msgs/GoalID goal_id, NameGoal goal
    NameActionResult:   Header header, actionlib_msgs/GoalStatus status, NameResult result
    NameActionFeedback: Header header, actionlib_msgs/GoalStatus status, NameFeedback feedback
    NameAction:         NameActionGoal action_goal, NameActionResult action_result,
                        NameActionFeedback action_feedback
"""

from __future__ import annotations

import re
from collections.abc import Mapping

__all__ = ["action_part", "ros1_wrapper_text"]

_PARTS = ("Goal", "Result", "Feedback")
_ROS2_PART = re.compile(r"(\w+)/action/(\w+)_(Goal|Result|Feedback)")
_ROS1_SUFFIXES = (
    "ActionGoal",
    "ActionResult",
    "ActionFeedback",
    "Action",
    "Goal",
    "Result",
    "Feedback",
)

# genaction.py's wrapper messages, by suffix; %s is the action's name.
_ROS1_WRAPPERS = {
    "ActionGoal": "Header header\nactionlib_msgs/GoalID goal_id\n%sGoal goal\n",
    "ActionResult": "Header header\nactionlib_msgs/GoalStatus status\n%sResult result\n",
    "ActionFeedback": "Header header\nactionlib_msgs/GoalStatus status\n%sFeedback feedback\n",
    "Action": (
        "%sActionGoal action_goal\n%sActionResult action_result\n%sActionFeedback action_feedback\n"
    ),
}


def action_part(name: str, files: Mapping[str, object]) -> tuple[str, int, str | None] | None:
    """Which ``.action`` file (``pkg/action/Name`` in ``files``) defines message ``name``.

    Returns:
        The action's key, the index of the part whose text the type is built from (0 goal,
        1 result, 2 feedback), and for a ROS 1 type (``pkg/msg/NameActionGoal`` etc.) its
        genaction suffix; None if no action on the package path gives ``name``.
    """
    ros2 = _ROS2_PART.fullmatch(name)
    if ros2 is not None:
        key = f"{ros2[1]}/action/{ros2[2]}"
        return (key, _PARTS.index(ros2[3]), None) if key in files else None
    ros1 = re.fullmatch(r"(\w+)/msg/(\w+)", name)
    if ros1 is None:
        return None
    for suffix in _ROS1_SUFFIXES:
        action = ros1[2].removesuffix(suffix)
        key = f"{ros1[1]}/action/{action}"
        if action != ros1[2] and action and key in files:
            part = suffix.removeprefix("Action") or "Goal"
            return key, _PARTS.index(part), suffix
    return None


def ros1_wrapper_text(name: str, part: str, suffix: str) -> str:
    """The definition of ROS 1 type ``name`` (``pkg/msg/Name<suffix>``): the part's own text
    for ``Goal``/``Result``/``Feedback``, genaction's wrapper for the ``Action*`` types."""
    wrapper = _ROS1_WRAPPERS.get(suffix)
    if wrapper is None:
        return part
    action = name.rsplit("/", 1)[-1].removesuffix(suffix)
    return wrapper.replace("%s", action)
