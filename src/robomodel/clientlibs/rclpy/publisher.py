"""``rclpy.publisher.Publisher``: a robomodel publisher under rclpy's names."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered
from robomodel.clientlibs.rclpy.exceptions import InvalidHandle

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.event_handler import EventHandler, EventWatch
    from robomodel.clientlibs.rclpy.qos import QoSProfile
    from robomodel.runtime.node import Publisher as RobomodelPublisher

__all__ = ["Publisher"]


class Publisher:
    """Publishes messages of ``msg_type`` on ``topic_name`` (made by ``Node.create_publisher``)."""

    def __init__(self, publisher: RobomodelPublisher[Any], qos_profile: QoSProfile) -> None:
        self.robomodel_publisher = publisher
        self.msg_type = publisher.msg_type
        self.qos_profile = qos_profile
        self._typename = publisher.msg_type.__typename__
        self._publish = publisher.publish
        self.event_handlers: list[EventHandler] = []
        self._event_watch: EventWatch | None = None
        self._destroyed = False

    @property
    def topic_name(self) -> str:
        return self.robomodel_publisher.topic

    @property
    def topic(self) -> str:
        return self.robomodel_publisher.topic

    def publish(self, msg: Any) -> None:
        """Publish ``msg``: an instance of the publisher's type (any flavour of it)."""
        if msg.__class__ is not self.msg_type and (
            getattr(msg, "__typename__", None) != self._typename
        ):
            if isinstance(msg, (bytes, bytearray, memoryview)):
                not_offered("Publisher.publish() of serialized bytes", "publish the message")
            raise TypeError(f"Expected {self._typename}, got {type(msg)}")
        self._publish(msg)

    def get_subscription_count(self) -> int:
        return self.robomodel_publisher.get_subscription_count()

    def assert_liveliness(self) -> None:
        """As rmw_zenoh's: the publisher's liveliness is its graph token, alive as long as the
        publisher is, so there is nothing more to assert; a destroyed one raises."""
        if self._destroyed:
            raise InvalidHandle(f"publisher on {self.topic_name} was destroyed")

    def wait_for_all_acked(self, timeout: Any = None) -> bool:
        not_offered("Publisher.wait_for_all_acked()")

    @property
    def handle(self) -> Any:
        not_offered("Publisher.handle (rcl's handle)")

    def _watch(self, watch: EventWatch) -> None:
        """Events of this publisher are watched (their handlers listed in ``event_handlers``)."""
        self._event_watch = watch
        self.event_handlers = watch.handlers
        if watch.deadline_ns:  # each publish restarts the deadline
            self._publish = watch.noting(self._publish)

    def destroy(self) -> None:
        self._destroyed = True
        if self._event_watch is not None:
            self._event_watch.stop()
        self.robomodel_publisher.destroy()

    def __enter__(self) -> Publisher:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy()
