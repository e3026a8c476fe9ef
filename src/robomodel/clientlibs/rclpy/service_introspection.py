"""``rclpy.service_introspection``: a service's or client's events on
``<service>/_service_event`` (``<pkg>/srv/<Name>_Event``), as rcl publishes them once
``configure_introspection`` turns them on.

Each event carries ``service_msgs/ServiceEventInfo``: the event type (a client's
REQUEST_SENT and RESPONSE_RECEIVED, a service's REQUEST_RECEIVED and RESPONSE_SENT), the
stamp from the clock given, and the request's id, the client's GID and sequence number as
rmw_zenoh's request attachment carries them (zeros on the in-process bus, which has no
ids). With CONTENTS the request or response rides along; with METADATA only the info.
"""

from __future__ import annotations

import enum
import threading
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.clock import Clock
    from robomodel.clientlibs.rclpy.qos import QoSProfile
    from robomodel.runtime.node import Node as RobomodelNode
    from robomodel.runtime.node import Publisher as RobomodelPublisher
    from robomodel.runtime.transport.base import RequestId

__all__ = ["ServiceIntrospectionState"]

EVENT_TOPIC_SUFFIX = "/_service_event"


class ServiceIntrospectionState(enum.IntEnum):
    """What introspection publishes: nothing, the events' info, or the info and contents."""

    OFF = 0
    METADATA = 1
    CONTENTS = 2


class Introspection:
    """The events of one service or client of ``node``; OFF until :meth:`configure`."""

    REQUEST_SENT = 0
    REQUEST_RECEIVED = 1
    RESPONSE_SENT = 2
    RESPONSE_RECEIVED = 3

    def __init__(self, node: RobomodelNode, srv_type: Any, service_name: str) -> None:
        self._node = node
        self._srv_type = srv_type
        self._topic = service_name + EVENT_TOPIC_SUFFIX
        self._state = ServiceIntrospectionState.OFF
        self._clock: Clock | None = None
        self._publisher: RobomodelPublisher[Any] | None = None
        self._lock = threading.Lock()

    def configure(
        self, clock: Clock, qos_profile: QoSProfile, state: ServiceIntrospectionState
    ) -> None:
        """Publish events from now on as ``state`` says (OFF: none, and the publisher goes)."""
        state = ServiceIntrospectionState(state)
        with self._lock:
            if state == ServiceIntrospectionState.OFF:
                if self._publisher is not None:
                    self._publisher.destroy()
                    self._publisher = None
            elif self._publisher is None:
                event_type = getattr(self._srv_type, "Event", None)
                if event_type is None:
                    raise RuntimeError(
                        f"service introspection of {self._srv_type.__typename__} needs its "
                        "rosidl-shaped class (with Event, made when robomodel's types have "
                        "service_msgs/msg/ServiceEventInfo); this one has none, as genpy's "
                        "(in a process that imported rospy too) have not"
                    )
                self._publisher = self._node.create_publisher(
                    event_type, self._topic, qos_profile.to_robomodel()
                )
            self._clock = clock
            self._state = state

    def publish(self, event_type: int, request_id: RequestId | None, message: Any) -> None:
        """Publish one event (nothing while OFF); ``message`` is the request or response."""
        with self._lock:
            publisher, state, clock = self._publisher, self._state, self._clock
        if publisher is None or clock is None:
            return
        # the Event's own nested classes (rosidl's, whatever flavour this process imports)
        info_class = dict(publisher.msg_type.__fields__)["info"]
        sec, nanosec = divmod(clock.now().nanoseconds, 1_000_000_000)
        info = info_class(
            event_type=event_type,
            stamp=dict(info_class.__fields__)["stamp"](sec=sec, nanosec=nanosec),
            client_gid=request_id.client_gid if request_id is not None else bytes(16),
            sequence_number=request_id.sequence_number if request_id is not None else 0,
        )
        event = publisher.msg_type(info=info)
        if state == ServiceIntrospectionState.CONTENTS:
            is_request = event_type in (self.REQUEST_SENT, self.REQUEST_RECEIVED)
            setattr(event, "request" if is_request else "response", [message])
        publisher.publish(event)

    def destroy(self) -> None:
        with self._lock:
            if self._publisher is not None:
                self._publisher.destroy()
                self._publisher = None
