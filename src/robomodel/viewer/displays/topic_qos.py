"""A display's topic QoS: RViz 2's Depth, History, Reliability and Durability Policy.

RViz 2 gives every display on a topic (``rviz_common::RosTopicDisplay``) a
``QosProfileProperty`` below its Topic property: ``Depth`` (robomodel's ``Queue Size``, as
RViz 1 calls it) and three policies, each "System Default" or one of rmw's values
(rviz_common/src/rviz_common/properties/qos_profile_property.cpp, ros2/rviz at f7112b1).
They are written in the config inside ``Topic`` (``Topic: {Value, Depth, History Policy,
Reliability Policy, Durability Policy}``), so their option names are ``Topic/...``.

:func:`topic_qos` is ``QosProfileProperty::updateQosProfile``: rmw's default profile (keep
last, reliable, volatile) with the depth and each policy that is not "System Default". On the
Zenoh bus the profile is rmw_zenoh's subscription QoS; ROS 1 has only the queue size (a
latched topic reaches every subscriber: latching is the publisher's, not a subscriber's
choice, so RViz 1 has no such options and they are not written in ROS 1 configs).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from robomodel.runtime.qos import Durability, History, QoSProfile, Reliability
from robomodel.viewer.displays.options import Option, OptionKind

__all__ = [
    "DURABILITY",
    "HISTORY",
    "QOS_OPTION_NAMES",
    "RELIABILITY",
    "qos_options",
    "topic_qos",
]

SYSTEM_DEFAULT = "System Default"
HISTORY = {SYSTEM_DEFAULT: None, "Keep Last": History.KEEP_LAST, "Keep All": History.KEEP_ALL}
RELIABILITY = {SYSTEM_DEFAULT: None, "Reliable": Reliability.RELIABLE,
               "Best Effort": Reliability.BEST_EFFORT}  # fmt: skip
DURABILITY = {SYSTEM_DEFAULT: None, "Transient Local": Durability.TRANSIENT_LOCAL,
              "Volatile": Durability.VOLATILE}  # fmt: skip

_HISTORY_HELP = (
    "Set the history policy: 'Keep all' will keep every message and ignore the depth, while "
    "'keep last' will only keep the last messages up to the depth."
)
_RELIABILITY_HELP = (
    "Set the reliability policy: When choosing 'Best effort', no guarantee will be given that "
    "the messages will be delivered, choosing 'Reliable', messages will be sent until received."
)
_DURABILITY_HELP = (
    "Set the durability policy: When choosing 'Transient Local' the publisher will be "
    "responsible for persisting data for late joining subscribers, choosing 'Volatile', no "
    "attempt at persistence will be made."
)

QOS_OPTION_NAMES = (
    "Topic/History Policy",
    "Topic/Reliability Policy",
    "Topic/Durability Policy",
)


def qos_options(defaults: Mapping[str, str] | None = None) -> tuple[Option, ...]:
    """The three policy options of a display's ``Topic`` (RViz 2's defaults: rclcpp's
    ``QoS(5)``, keep last, reliable, volatile; ``defaults`` by policy name changes them)."""
    chosen = {"History Policy": "Keep Last", "Reliability Policy": "Reliable",
              "Durability Policy": "Volatile", **(defaults or {})}  # fmt: skip
    tables = (("History Policy", HISTORY, _HISTORY_HELP),
              ("Reliability Policy", RELIABILITY, _RELIABILITY_HELP),
              ("Durability Policy", DURABILITY, _DURABILITY_HELP))  # fmt: skip
    return tuple(
        Option(f"Topic/{name}", chosen[name], OptionKind.CHOICE, choices=tuple(table), help=text)
        for name, table, text in tables
    )


def _policy(values: Mapping[str, Any], option: str, table: Mapping[str, Any], default: Any) -> Any:
    chosen = table.get(str(values.get(option, SYSTEM_DEFAULT)))
    return default if chosen is None else chosen


def topic_qos(values: Mapping[str, Any], depth: int) -> QoSProfile:
    """The subscription profile of a display's option ``values`` with queue ``depth``
    (rmw_qos_profile_default where a policy is "System Default" or absent)."""
    return QoSProfile(
        depth,
        durability=_policy(values, "Topic/Durability Policy", DURABILITY, Durability.VOLATILE),
        reliability=_policy(values, "Topic/Reliability Policy", RELIABILITY, Reliability.RELIABLE),
        history=_policy(values, "Topic/History Policy", HISTORY, History.KEEP_LAST),
    )
