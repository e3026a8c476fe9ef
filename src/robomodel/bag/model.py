"""Plain data of the bag layer: storages, topics, messages and what a reader found."""

from __future__ import annotations

import enum
from dataclasses import dataclass

from robomodel.runtime.qos import QoSProfile

__all__ = ["BagMessage", "BagSummary", "Damage", "Storage", "TopicSummary"]


class Storage(enum.Enum):
    """How a bag is stored: rosbag2 with MCAP or SQLite 3 files, or one ROS 1 ``.bag``."""

    MCAP = "mcap"
    SQLITE3 = "sqlite3"
    ROS1 = "ros1"


@dataclass(frozen=True, slots=True)
class TopicSummary:
    """One topic of a bag. ``type`` is the ROS 2 name (``sensor_msgs/msg/JointState``)."""

    name: str
    type: str
    count: int
    serialization_format: str = "cdr"
    offered_qos: tuple[QoSProfile, ...] = ()
    definition: str = ""  # the stored message definition (MCAP schema, rosbag's msgdef)

    @property
    def latched(self) -> bool:
        """Offered transient local by its publishers (as /tf_static, /robot_description)."""
        return any(q.durability.value == "transient_local" for q in self.offered_qos)


@dataclass(frozen=True, slots=True)
class BagMessage:
    """One recorded message.

    ``data`` is in the topic's serialization format (CDR for rosbag2, ROS 1 serialization for
    a ``.bag``); ``log_time_ns`` is when the recorder received it and ``publish_time_ns`` when
    its publisher sent it (the same for ROS 1 bags, which keep one time), both since the epoch.
    """

    topic: str
    type: str
    data: bytes
    log_time_ns: int
    publish_time_ns: int


@dataclass(frozen=True, slots=True)
class Damage:
    """A part of a bag that could not be read: where, and why. The rest was read."""

    path: str
    offset: int | None
    reason: str

    def __str__(self) -> str:
        where = "" if self.offset is None else f"at byte {self.offset}: "
        return f"{self.path}: {where}{self.reason}"


@dataclass(frozen=True, slots=True)
class BagSummary:
    """What ``bag info`` prints: files, size, storage, time span, counts per topic.

    ``damage`` lists what could not be read; counts and times cover what could.
    """

    path: str
    storage: Storage
    files: tuple[str, ...]
    size_bytes: int
    start_ns: int
    end_ns: int
    message_count: int
    topics: tuple[TopicSummary, ...]
    ros_distro: str = ""
    damage: tuple[Damage, ...] = ()

    @property
    def duration_ns(self) -> int:
        return max(0, self.end_ns - self.start_ns)
