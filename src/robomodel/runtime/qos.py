"""Quality of service: history depth, durability (volatile / transient local), reliability."""

from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = ["Durability", "QoSProfile", "Reliability", "as_qos", "latched", "sensor_data"]


class Durability(enum.Enum):
    VOLATILE = "volatile"
    TRANSIENT_LOCAL = "transient_local"  # late subscribers get the last `depth` messages


class Reliability(enum.Enum):
    RELIABLE = "reliable"
    BEST_EFFORT = "best_effort"


@dataclass(frozen=True, slots=True)
class QoSProfile:
    """The subset of ROS 2 QoS that changes what robomodel delivers."""

    depth: int = 10
    durability: Durability = Durability.VOLATILE
    reliability: Reliability = Reliability.RELIABLE


def as_qos(qos: QoSProfile | int) -> QoSProfile:
    """Accept a profile or a bare history depth, as rclpy does."""
    return qos if isinstance(qos, QoSProfile) else QoSProfile(depth=int(qos))


def latched(depth: int = 1) -> QoSProfile:
    """Transient local, as /robot_description and /tf_static use."""
    return QoSProfile(depth, Durability.TRANSIENT_LOCAL)


def sensor_data() -> QoSProfile:
    """rclcpp's SensorDataQoS: best effort, depth 5."""
    return QoSProfile(5, Durability.VOLATILE, Reliability.BEST_EFFORT)
