"""``rclpy.subscription.Subscription``: a robomodel subscription under rclpy's names."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.event_handler import EventHandler, EventWatch
    from robomodel.clientlibs.rclpy.qos import QoSProfile
    from robomodel.runtime.node import Subscription as RobomodelSubscription

__all__ = ["Subscription"]


class Subscription:
    """Calls ``callback(msg)`` for each message on ``topic_name`` (``Node.create_subscription``);
    ``msg`` is of the class the subscription was created with."""

    def __init__(
        self,
        subscription: RobomodelSubscription[Any],
        callback: Callable[[Any], Any],
        callback_group: CallbackGroup,
        qos_profile: QoSProfile,
    ) -> None:
        self.robomodel_subscription = subscription
        self.msg_type = subscription.msg_type
        self.callback = callback
        self.callback_group = callback_group
        self.qos_profile = qos_profile
        self.raw = False
        self.event_handlers: list[EventHandler] = []
        self._event_watch: EventWatch | None = None

    @property
    def topic_name(self) -> str:
        return self.robomodel_subscription.topic

    @property
    def topic(self) -> str:
        return self.robomodel_subscription.topic

    @property
    def handle(self) -> Any:
        not_offered("Subscription.handle (rcl's handle)")

    def _watch(self, watch: EventWatch) -> None:
        """Events of this subscription are watched (their handlers listed in ``event_handlers``)."""
        self._event_watch = watch
        self.event_handlers = watch.handlers

    def destroy(self) -> None:
        if self._event_watch is not None:
            self._event_watch.stop()
        self.robomodel_subscription.destroy()

    def __enter__(self) -> Subscription:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy()
