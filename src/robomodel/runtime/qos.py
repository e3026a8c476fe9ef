"""Quality of service: history (keep last N / keep all), durability (volatile / transient
local), reliability, and the deadline, lifespan and liveliness that ROS 2 peers declare."""

from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = [
    "Durability",
    "History",
    "Liveliness",
    "QoSProfile",
    "Reliability",
    "as_qos",
    "latched",
    "sensor_data",
]


class Durability(enum.Enum):
    VOLATILE = "volatile"
    TRANSIENT_LOCAL = "transient_local"  # late subscribers get the last `depth` messages


class Reliability(enum.Enum):
    RELIABLE = "reliable"
    BEST_EFFORT = "best_effort"


class History(enum.Enum):
    KEEP_LAST = "keep_last"  # at most `depth` messages wait; the oldest go first
    KEEP_ALL = "keep_all"  # every message waits (a RELIABLE publisher blocks rather than drop)


class Liveliness(enum.Enum):
    AUTOMATIC = "automatic"
    MANUAL_BY_TOPIC = "manual_by_topic"


@dataclass(frozen=True, slots=True)
class QoSProfile:
    """ROS 2 QoS. Durations are in nanoseconds, None for infinite (rmw's default).

    Deadline, lifespan and liveliness are declared to peers (rmw_zenoh's tokens) and read from
    theirs; rmw_zenoh enforces none of them, and neither does robomodel.
    """

    depth: int = 10
    durability: Durability = Durability.VOLATILE
    reliability: Reliability = Reliability.RELIABLE
    history: History = History.KEEP_LAST
    deadline_ns: int | None = None
    lifespan_ns: int | None = None
    liveliness: Liveliness = Liveliness.AUTOMATIC
    liveliness_lease_ns: int | None = None


def as_qos(qos: QoSProfile | int) -> QoSProfile:
    """Accept a profile or a bare history depth, as rclpy does."""
    return qos if isinstance(qos, QoSProfile) else QoSProfile(depth=int(qos))


def latched(depth: int = 1) -> QoSProfile:
    """Transient local, as /robot_description and /tf_static use."""
    return QoSProfile(depth, Durability.TRANSIENT_LOCAL)


def sensor_data() -> QoSProfile:
    """rclcpp's SensorDataQoS: best effort, depth 5."""
    return QoSProfile(5, Durability.VOLATILE, Reliability.BEST_EFFORT)
