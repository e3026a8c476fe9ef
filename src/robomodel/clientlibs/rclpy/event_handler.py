"""``rclpy.event_handler``: QoS event callbacks of publishers and subscriptions, as rclpy
delivers them over rmw_zenoh.

What rmw_zenoh reports (``rmw_zenoh_cpp/src/detail/event.cpp``'s event map), robomodel
reports:

- ``matched``: the entity's match count changed (the graph's subscriptions of a publisher's
  topic and type, the publishers of a subscription's; rmw_zenoh counts them from the graph's
  liveliness tokens, as robomodel's graph does).
- ``message_lost``: gaps in the publishers' sequence numbers (rmw_zenoh's MESSAGE_LOST).
- ``incompatible_qos`` and ``incompatible_type``: accepted, and never called, as with
  rmw_zenoh, which finds no QoS incompatible (``rmw_qos_profile_check_compatible``) and does
  not check types.

``deadline`` is reported from the entity's own traffic: each deadline period without a
message published (a publisher) or received (a subscription), counted from the first one,
is one miss, as a DDS writer or reader counts them per instance. ``liveliness`` is not
reported by rmw_zenoh: a callback for it raises :class:`UnsupportedEventTypeError`, as rclpy
raises it on rmw_zenoh.

Events are seen by a watch on the node's timer every :data:`POLL_PERIOD_S` (or sooner for a
short deadline); the callbacks run on the executor, in the entity's callback group.
"""

from __future__ import annotations

import enum
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup

__all__ = [
    "EventHandler",
    "IncompatibleTypeInfo",
    "PublisherEventCallbacks",
    "QoSLivelinessChangedInfo",
    "QoSLivelinessLostInfo",
    "QoSMessageLostInfo",
    "QoSOfferedDeadlineMissedInfo",
    "QoSOfferedIncompatibleQoSInfo",
    "QoSPublisherEventType",
    "QoSPublisherMatchedInfo",
    "QoSRequestedDeadlineMissedInfo",
    "QoSRequestedIncompatibleQoSInfo",
    "QoSSubscriptionEventType",
    "QoSSubscriptionMatchedInfo",
    "SubscriptionEventCallbacks",
    "UnsupportedEventTypeError",
]

POLL_PERIOD_S = 0.05  # how often match counts, lost counts and deadlines are looked at


class UnsupportedEventTypeError(RuntimeError):
    """A callback for an event the middleware does not report (rclpy's, raised on rmw_zenoh
    for liveliness events)."""


class QoSPublisherEventType(enum.IntEnum):
    """rcl's ``rcl_publisher_event_type_t``."""

    RCL_PUBLISHER_OFFERED_DEADLINE_MISSED = 0
    RCL_PUBLISHER_LIVELINESS_LOST = 1
    RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS = 2
    RCL_PUBLISHER_INCOMPATIBLE_TYPE = 3
    RCL_PUBLISHER_MATCHED = 4


class QoSSubscriptionEventType(enum.IntEnum):
    """rcl's ``rcl_subscription_event_type_t``."""

    RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED = 0
    RCL_SUBSCRIPTION_LIVELINESS_CHANGED = 1
    RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS = 2
    RCL_SUBSCRIPTION_MESSAGE_LOST = 3
    RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE = 4
    RCL_SUBSCRIPTION_MATCHED = 5


# The statuses, as rmw's structs (rmw/events_statuses/*.h): counts since the entity was made
# (``total_count``, ``current_count``) and their change since the last callback.
@dataclass(frozen=True, slots=True)
class _CountStatus:
    total_count: int = 0
    total_count_change: int = 0


class QoSRequestedDeadlineMissedInfo(_CountStatus):
    """rmw_requested_deadline_missed_status_t."""


class QoSOfferedDeadlineMissedInfo(_CountStatus):
    """rmw_offered_deadline_missed_status_t."""


class QoSLivelinessLostInfo(_CountStatus):
    """rmw_liveliness_lost_status_t."""


class QoSMessageLostInfo(_CountStatus):
    """rmw_message_lost_status_t."""


class IncompatibleTypeInfo(_CountStatus):
    """rmw_incompatible_type_status_t."""


@dataclass(frozen=True, slots=True)
class QoSRequestedIncompatibleQoSInfo:
    """rmw_requested_qos_incompatible_event_status_t (``last_policy_kind``: a QoSPolicyKind)."""

    total_count: int = 0
    total_count_change: int = 0
    last_policy_kind: int = 1


QoSOfferedIncompatibleQoSInfo = QoSRequestedIncompatibleQoSInfo


@dataclass(frozen=True, slots=True)
class QoSLivelinessChangedInfo:
    """rmw_liveliness_changed_status_t."""

    alive_count: int = 0
    not_alive_count: int = 0
    alive_count_change: int = 0
    not_alive_count_change: int = 0


@dataclass(frozen=True, slots=True)
class _MatchedStatus:
    """rmw_matched_status_t: ``total_count`` counts matches made, ``current_count`` those
    standing."""

    total_count: int = 0
    total_count_change: int = 0
    current_count: int = 0
    current_count_change: int = 0


class QoSSubscriptionMatchedInfo(_MatchedStatus):
    """A subscription's publishers changed (rmw_matched_status_t)."""


class QoSPublisherMatchedInfo(_MatchedStatus):
    """A publisher's subscriptions changed (rmw_matched_status_t)."""


class EventHandler:
    """One event callback of a publisher or subscription (made by the ``*EventCallbacks``)."""

    def __init__(
        self,
        *,
        callback_group: CallbackGroup,
        callback: Callable[[Any], Any],
        event_type: enum.IntEnum,
    ) -> None:
        self.callback_group = callback_group
        self.callback = callback
        self.event_type = event_type
        self.destroyed = False

    def destroy(self) -> None:
        self.destroyed = True


def _unsupported(event_type: enum.IntEnum) -> UnsupportedEventTypeError:
    return UnsupportedEventTypeError(
        f"Failed to initialize event: provided event_type {int(event_type)} "
        f"({event_type.name}) is not supported by rmw_zenoh_cpp"
    )


def _handlers(
    callback_group: CallbackGroup, wanted: tuple[tuple[Callable[[Any], Any] | None, Any], ...]
) -> list[EventHandler]:
    """A handler for each callback given, of its event type."""
    return [
        EventHandler(callback_group=callback_group, callback=callback, event_type=kind)
        for callback, kind in wanted
        if callback is not None
    ]


class SubscriptionEventCallbacks:
    """The event callbacks of a subscription (``create_subscription(event_callbacks=...)``)."""

    def __init__(
        self,
        *,
        deadline: Callable[[QoSRequestedDeadlineMissedInfo], None] | None = None,
        incompatible_qos: Callable[[QoSRequestedIncompatibleQoSInfo], None] | None = None,
        liveliness: Callable[[QoSLivelinessChangedInfo], None] | None = None,
        message_lost: Callable[[QoSMessageLostInfo], None] | None = None,
        incompatible_type: Callable[[IncompatibleTypeInfo], None] | None = None,
        matched: Callable[[QoSSubscriptionMatchedInfo], None] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.message_lost = message_lost
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, callback_group: CallbackGroup) -> list[EventHandler]:
        """The handlers of the callbacks given; UnsupportedEventTypeError for liveliness."""
        kinds = QoSSubscriptionEventType
        if self.liveliness is not None:
            raise _unsupported(kinds.RCL_SUBSCRIPTION_LIVELINESS_CHANGED)
        wanted = (
            (self.deadline, kinds.RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED),
            (self.incompatible_qos, kinds.RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS),
            (self.message_lost, kinds.RCL_SUBSCRIPTION_MESSAGE_LOST),
            (self.incompatible_type, kinds.RCL_SUBSCRIPTION_INCOMPATIBLE_TYPE),
            (self.matched, kinds.RCL_SUBSCRIPTION_MATCHED),
        )
        return _handlers(callback_group, wanted)


class PublisherEventCallbacks:
    """The event callbacks of a publisher (``create_publisher(event_callbacks=...)``)."""

    def __init__(
        self,
        *,
        deadline: Callable[[QoSOfferedDeadlineMissedInfo], None] | None = None,
        liveliness: Callable[[QoSLivelinessLostInfo], None] | None = None,
        incompatible_qos: Callable[[QoSRequestedIncompatibleQoSInfo], None] | None = None,
        incompatible_type: Callable[[IncompatibleTypeInfo], None] | None = None,
        matched: Callable[[QoSPublisherMatchedInfo], None] | None = None,
        use_default_callbacks: bool = True,
    ) -> None:
        self.deadline = deadline
        self.liveliness = liveliness
        self.incompatible_qos = incompatible_qos
        self.incompatible_type = incompatible_type
        self.matched = matched
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, callback_group: CallbackGroup) -> list[EventHandler]:
        """The handlers of the callbacks given; UnsupportedEventTypeError for liveliness."""
        kinds = QoSPublisherEventType
        if self.liveliness is not None:
            raise _unsupported(kinds.RCL_PUBLISHER_LIVELINESS_LOST)
        wanted = (
            (self.deadline, kinds.RCL_PUBLISHER_OFFERED_DEADLINE_MISSED),
            (self.incompatible_qos, kinds.RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS),
            (self.incompatible_type, kinds.RCL_PUBLISHER_INCOMPATIBLE_TYPE),
            (self.matched, kinds.RCL_PUBLISHER_MATCHED),
        )
        return _handlers(callback_group, wanted)


def _kind(event_type: enum.IntEnum) -> tuple[type, int]:
    """An event type as a key: the two enums share values (0 is a deadline on both sides, 3 a
    lost message or a publisher's incompatible type), so the enum is part of it."""
    return (type(event_type), int(event_type))


_PUB, _SUB = QoSPublisherEventType, QoSSubscriptionEventType
_DEADLINE: dict[tuple[type, int], type] = {
    _kind(_PUB.RCL_PUBLISHER_OFFERED_DEADLINE_MISSED): QoSOfferedDeadlineMissedInfo,
    _kind(_SUB.RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED): QoSRequestedDeadlineMissedInfo,
}
_MATCHED: dict[tuple[type, int], type] = {
    _kind(_PUB.RCL_PUBLISHER_MATCHED): QoSPublisherMatchedInfo,
    _kind(_SUB.RCL_SUBSCRIPTION_MATCHED): QoSSubscriptionMatchedInfo,
}
_LOST: dict[tuple[type, int], type] = {
    _kind(_SUB.RCL_SUBSCRIPTION_MESSAGE_LOST): QoSMessageLostInfo,
}


class EventWatch:
    """Looks at one entity's counts on each poll and calls the handlers whose event happened.

    ``matched_count()`` is the entity's match count now, ``lost_count()`` the messages lost
    so far; ``deadline_ns`` (0: none) the QoS deadline, against :meth:`activity` (a message
    published or received). Each handler's status is its own, as each rmw event is.
    """

    def __init__(
        self,
        handlers: list[EventHandler],
        *,
        matched_count: Callable[[], int],
        lost_count: Callable[[], int],
        deadline_ns: int,
    ) -> None:
        self.handlers = handlers
        self._matched_count = matched_count
        self._lost_count = lost_count
        self.deadline_ns = deadline_ns
        self._matched = (0, 0)  # (total_count, current_count) last reported
        self._lost = 0
        self._missed = 0
        self._next_deadline_ns: int | None = None  # counted from the first message
        self._unreported = 0  # deadline periods missed since the last poll
        self._lock = threading.Lock()
        self.stopped = False
        self._on_stop: list[Callable[[], None]] = []

    def on_stop(self, callback: Callable[[], None]) -> None:
        """Call ``callback`` when the watch stops (cancels its timer)."""
        self._on_stop.append(callback)

    @property
    def period_s(self) -> float:
        """How often to poll: a quarter of the deadline when that is shorter."""
        if self.deadline_ns and self.wants(_DEADLINE):
            return min(POLL_PERIOD_S, self.deadline_ns / 4e9)
        return POLL_PERIOD_S

    def wants(self, kinds: dict[tuple[type, int], type]) -> bool:
        return any(_kind(h.event_type) in kinds for h in self.handlers)

    def activity(self) -> None:
        """A message was published or received now (any thread): the deadline restarts, and
        periods that passed without one count as missed, however soon the poll comes."""
        now = time.monotonic_ns()
        with self._lock:
            due = self._next_deadline_ns
            if due is not None and now >= due:
                self._unreported += (now - due) // self.deadline_ns + 1
            self._next_deadline_ns = now + self.deadline_ns

    def noting(self, call: Callable[..., Any]) -> Callable[..., Any]:
        """``call`` (a publish, or a subscription's delivery) restarting the deadline each
        time it runs."""

        def noted(*args: Any) -> Any:
            self.activity()
            return call(*args)

        return noted

    def poll(self) -> list[tuple[EventHandler, Any]]:
        """The (handler, status) calls due now."""
        if self.stopped:
            return []
        due: list[tuple[EventHandler, Any]] = []
        matched = self._poll_matched()
        lost = self._poll_lost()
        missed = self._poll_deadline()
        for handler in self.handlers:
            kind = _kind(handler.event_type)
            if handler.destroyed:
                continue
            for statuses, counts in ((_MATCHED, matched), (_LOST, lost), (_DEADLINE, missed)):
                if counts is not None and kind in statuses:
                    due.append((handler, statuses[kind](*counts)))
        return due

    def _poll_matched(self) -> tuple[int, int, int, int] | None:
        if not self.wants(_MATCHED):
            return None
        total, current = self._matched
        now = self._matched_count()
        if now == current:
            return None
        change = now - current
        made = max(change, 0)  # as rmw_zenoh's GraphCache::update_event_counters
        self._matched = (total + made, now)
        return (total + made, made, now, change)

    def _poll_lost(self) -> tuple[int, int] | None:
        if not self.wants(_LOST):
            return None
        lost = self._lost_count()
        if lost == self._lost:
            return None
        change, self._lost = lost - self._lost, lost
        return (lost, change)

    def _poll_deadline(self) -> tuple[int, int] | None:
        if not self.deadline_ns:
            return None
        now = time.monotonic_ns()
        with self._lock:
            due = self._next_deadline_ns
            if due is not None and now >= due:  # still nothing: these periods are missed
                periods = (now - due) // self.deadline_ns + 1
                self._next_deadline_ns = due + periods * self.deadline_ns
                self._unreported += periods
            missed, self._unreported = self._unreported, 0
        if not missed:
            return None
        self._missed += missed
        return (self._missed, missed)

    def stop(self) -> None:
        self.stopped = True
        for callback in self._on_stop:
            callback()
