"""``rclpy.qos``: QoS profiles, their policies and the named presets, as robomodel's
:class:`robomodel.runtime.qos.QoSProfile` (which the Zenoh bus declares in rmw_zenoh's tokens).

The values are rmw's: ``qos_profile_sensor_data`` is best effort, keep last 5, volatile;
``qos_profile_services_default`` and ``qos_profile_parameters`` keep last 10 and 1000 reliably.
"""

from __future__ import annotations

import enum
from typing import Any

from robomodel.clientlibs.rclpy.duration import Duration, Infinite
from robomodel.runtime import qos as rm

__all__ = [
    "DurabilityPolicy",
    "HistoryPolicy",
    "LivelinessPolicy",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSLivelinessPolicy",
    "QoSPolicyKind",
    "QoSPresetProfiles",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ReliabilityPolicy",
    "qos_policy_name_from_kind",
    "qos_profile_action_status_default",
    "qos_profile_parameter_events",
    "qos_profile_parameters",
    "qos_profile_rosout_default",
    "qos_profile_sensor_data",
    "qos_profile_services_default",
    "qos_profile_system_default",
    "qos_profile_unknown",
]


class HistoryPolicy(enum.IntEnum):
    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class ReliabilityPolicy(enum.IntEnum):
    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(enum.IntEnum):
    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class LivelinessPolicy(enum.IntEnum):
    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_NODE = 2  # deprecated in rmw, as MANUAL_BY_TOPIC for robomodel
    MANUAL_BY_TOPIC = 3
    UNKNOWN = 4
    BEST_AVAILABLE = 5


class QoSPolicyKind(enum.IntEnum):
    """The QoS policies by kind, with rmw's values (``rmw/incompatible_qos_events_statuses.h``):
    an incompatible-QoS event's ``last_policy_kind`` and the QoS overriding parameters."""

    INVALID = 1 << 0
    DURABILITY = 1 << 1
    DEADLINE = 1 << 2
    LIVELINESS = 1 << 3
    RELIABILITY = 1 << 4
    HISTORY = 1 << 5
    LIFESPAN = 1 << 6
    DEPTH = 1 << 7
    LIVELINESS_LEASE_DURATION = 1 << 8
    AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9


def qos_policy_name_from_kind(policy_kind: QoSPolicyKind | int) -> str:
    """The policy's name (``"DURABILITY"``) from its kind."""
    return QoSPolicyKind(policy_kind).name


# The older names rclpy keeps.
QoSHistoryPolicy = HistoryPolicy
QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSLivelinessPolicy = LivelinessPolicy

_UNSET = object()


def _duration(value: Any) -> Duration:
    if isinstance(value, Duration):
        return value
    if isinstance(value, (int, float)):  # rclpy takes seconds
        return Duration(seconds=value)
    return Duration(seconds=value.sec, nanoseconds=value.nanosec)  # builtin_interfaces/Duration


class QoSProfile:
    """A QoS profile; ``QoSProfile(depth=10)`` keeps the last 10, as rclpy. A profile must name
    its history or its depth (rclpy's rule); the rest default to rmw's defaults."""

    __slots__ = ("_deadline", "_depth", "_durability", "_history", "_lifespan", "_liveliness",
                 "_liveliness_lease", "_reliability", "avoid_ros_namespace_conventions")  # fmt: skip

    def __init__(self, **kwargs: Any) -> None:
        unknown = set(kwargs) - {
            "history", "depth", "reliability", "durability", "lifespan", "deadline",
            "liveliness", "liveliness_lease_duration", "avoid_ros_namespace_conventions",
        }  # fmt: skip
        if unknown:
            raise TypeError(
                f"Invalid arguments passed to constructor: {', '.join(sorted(unknown))}"
            )
        if "history" not in kwargs and "depth" not in kwargs:
            raise TypeError("QoSProfile needs 'history' and/or 'depth' (e.g. QoSProfile(depth=10))")
        history = kwargs.get("history", HistoryPolicy.KEEP_LAST)
        self._history = HistoryPolicy(history)
        self._depth = int(kwargs.get("depth", 0))
        if self._history == HistoryPolicy.KEEP_LAST and self._depth == 0 and "depth" in kwargs:
            raise ValueError("A KEEP_LAST QoSProfile needs a depth > 0")
        self._reliability = ReliabilityPolicy(kwargs.get("reliability", 1))
        self._durability = DurabilityPolicy(kwargs.get("durability", 2))
        self._liveliness = LivelinessPolicy(kwargs.get("liveliness", 1))
        self._deadline = _duration(kwargs.get("deadline", Duration()))
        self._lifespan = _duration(kwargs.get("lifespan", Duration()))
        self._liveliness_lease = _duration(kwargs.get("liveliness_lease_duration", Duration()))
        self.avoid_ros_namespace_conventions = bool(
            kwargs.get("avoid_ros_namespace_conventions", False)
        )

    # rclpy's profiles are mutable: code sets profile.depth after making one.
    @property
    def history(self) -> HistoryPolicy:
        return self._history

    @history.setter
    def history(self, value: Any) -> None:
        self._history = HistoryPolicy(value)

    @property
    def depth(self) -> int:
        return self._depth

    @depth.setter
    def depth(self, value: int) -> None:
        self._depth = int(value)

    @property
    def reliability(self) -> ReliabilityPolicy:
        return self._reliability

    @reliability.setter
    def reliability(self, value: Any) -> None:
        self._reliability = ReliabilityPolicy(value)

    @property
    def durability(self) -> DurabilityPolicy:
        return self._durability

    @durability.setter
    def durability(self, value: Any) -> None:
        self._durability = DurabilityPolicy(value)

    @property
    def liveliness(self) -> LivelinessPolicy:
        return self._liveliness

    @liveliness.setter
    def liveliness(self, value: Any) -> None:
        self._liveliness = LivelinessPolicy(value)

    @property
    def deadline(self) -> Duration:
        return self._deadline

    @deadline.setter
    def deadline(self, value: Any) -> None:
        self._deadline = _duration(value)

    @property
    def lifespan(self) -> Duration:
        return self._lifespan

    @lifespan.setter
    def lifespan(self, value: Any) -> None:
        self._lifespan = _duration(value)

    @property
    def liveliness_lease_duration(self) -> Duration:
        return self._liveliness_lease

    @liveliness_lease_duration.setter
    def liveliness_lease_duration(self, value: Any) -> None:
        self._liveliness_lease = _duration(value)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, QoSProfile):
            return NotImplemented
        return all(getattr(self, s) == getattr(other, s) for s in self.__slots__)

    def __hash__(self) -> int:
        return hash(tuple(getattr(self, s) for s in self.__slots__))

    def __repr__(self) -> str:
        return (
            f"QoSProfile(history={self._history.name}, depth={self._depth}, "
            f"reliability={self._reliability.name}, durability={self._durability.name})"
        )

    def deadline_ns(self) -> int:
        """The deadline in nanoseconds; 0 for none (rmw's 0 or infinite)."""
        return _ns_or_none(self._deadline) or 0

    def to_robomodel(self) -> rm.QoSProfile:
        """The profile as robomodel's (what the bus declares and applies)."""
        return rm.QoSProfile(
            depth=self._depth if self._history != HistoryPolicy.KEEP_ALL else max(self._depth, 0),
            durability=(
                rm.Durability.TRANSIENT_LOCAL
                if self._durability == DurabilityPolicy.TRANSIENT_LOCAL
                else rm.Durability.VOLATILE
            ),
            reliability=(
                rm.Reliability.BEST_EFFORT
                if self._reliability == ReliabilityPolicy.BEST_EFFORT
                else rm.Reliability.RELIABLE
            ),
            history=(
                rm.History.KEEP_ALL
                if self._history == HistoryPolicy.KEEP_ALL
                else rm.History.KEEP_LAST
            ),
            deadline_ns=_ns_or_none(self._deadline),
            lifespan_ns=_ns_or_none(self._lifespan),
            liveliness=(
                rm.Liveliness.MANUAL_BY_TOPIC
                if self._liveliness
                in (LivelinessPolicy.MANUAL_BY_TOPIC, LivelinessPolicy.MANUAL_BY_NODE)
                else rm.Liveliness.AUTOMATIC
            ),
            liveliness_lease_ns=_ns_or_none(self._liveliness_lease),
        )


def from_robomodel(qos: rm.QoSProfile) -> QoSProfile:
    """robomodel's profile (a graph endpoint's) as rclpy's."""
    return QoSProfile(
        history=HistoryPolicy.KEEP_ALL
        if qos.history == rm.History.KEEP_ALL
        else HistoryPolicy.KEEP_LAST,
        depth=qos.depth,
        reliability=(
            ReliabilityPolicy.BEST_EFFORT
            if qos.reliability == rm.Reliability.BEST_EFFORT
            else ReliabilityPolicy.RELIABLE
        ),
        durability=(
            DurabilityPolicy.TRANSIENT_LOCAL
            if qos.durability == rm.Durability.TRANSIENT_LOCAL
            else DurabilityPolicy.VOLATILE
        ),
        deadline=Duration(nanoseconds=qos.deadline_ns or 0),
        lifespan=Duration(nanoseconds=qos.lifespan_ns or 0),
        liveliness=(
            LivelinessPolicy.MANUAL_BY_TOPIC
            if qos.liveliness == rm.Liveliness.MANUAL_BY_TOPIC
            else LivelinessPolicy.AUTOMATIC
        ),
        liveliness_lease_duration=Duration(nanoseconds=qos.liveliness_lease_ns or 0),
    )


def _ns_or_none(value: Duration) -> int | None:
    """rmw's 0 and infinite durations are robomodel's None (infinite)."""
    return None if value.nanoseconds in (0, Infinite.nanoseconds) else value.nanoseconds


def as_robomodel_qos(qos: QoSProfile | int) -> rm.QoSProfile:
    """A profile or a bare depth (rclpy takes both) as robomodel's profile."""
    if isinstance(qos, QoSProfile):
        return qos.to_robomodel()
    if isinstance(qos, bool) or not isinstance(qos, int):
        raise TypeError(f"qos_profile must be a QoSProfile or a history depth, got {qos!r}")
    if qos < 0:
        raise ValueError(f"a history depth must be >= 0, got {qos}")
    return rm.QoSProfile(depth=qos)


qos_profile_system_default = QoSProfile(
    history=HistoryPolicy.SYSTEM_DEFAULT,
    reliability=ReliabilityPolicy.SYSTEM_DEFAULT,
    durability=DurabilityPolicy.SYSTEM_DEFAULT,
    depth=10,  # rmw_zenoh's default depth
)
qos_profile_sensor_data = QoSProfile(
    history=HistoryPolicy.KEEP_LAST,
    depth=5,
    reliability=ReliabilityPolicy.BEST_EFFORT,
    durability=DurabilityPolicy.VOLATILE,
)
qos_profile_services_default = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=10, reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)  # fmt: skip
qos_profile_parameters = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1000, reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)  # fmt: skip
qos_profile_parameter_events = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1000, reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.VOLATILE,
)  # fmt: skip
qos_profile_action_status_default = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1, reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)  # fmt: skip
qos_profile_rosout_default = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1000, reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)  # fmt: skip
qos_profile_unknown = QoSProfile(
    history=HistoryPolicy.UNKNOWN, reliability=ReliabilityPolicy.UNKNOWN,
    durability=DurabilityPolicy.UNKNOWN, liveliness=LivelinessPolicy.UNKNOWN,
)  # fmt: skip


class QoSPresetProfiles(enum.Enum):
    """The presets by name (``QoSPresetProfiles.SENSOR_DATA.value``)."""

    UNKNOWN = qos_profile_unknown
    SYSTEM_DEFAULT = qos_profile_system_default
    SENSOR_DATA = qos_profile_sensor_data
    SERVICES_DEFAULT = qos_profile_services_default
    PARAMETERS = qos_profile_parameters
    PARAMETER_EVENTS = qos_profile_parameter_events
    ACTION_STATUS_DEFAULT = qos_profile_action_status_default
    ROSOUT_DEFAULT = qos_profile_rosout_default

    @classmethod
    def short_keys(cls) -> list[str]:
        return [m.name.lower() for m in cls]

    @classmethod
    def get_from_short_key(cls, name: str) -> QoSProfile:
        profile: QoSProfile = cls[name.upper()].value
        return profile
