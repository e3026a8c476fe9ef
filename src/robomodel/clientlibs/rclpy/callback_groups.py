"""``rclpy.callback_groups``: which callbacks a multi-threaded executor may run at once.

A :class:`MutuallyExclusiveCallbackGroup` runs one of its callbacks at a time (every node's
default group is one); a :class:`ReentrantCallbackGroup` runs any of them in parallel. A
single-threaded executor runs one callback at a time anyway.
"""

from __future__ import annotations

from typing import Any

__all__ = ["CallbackGroup", "MutuallyExclusiveCallbackGroup", "ReentrantCallbackGroup"]


class CallbackGroup:
    """The base: the entities (timers, subscriptions, ...) put in the group."""

    reentrant: bool = False

    def __init__(self) -> None:
        self.entities: list[Any] = []

    def add_entity(self, entity: Any) -> None:
        self.entities.append(entity)

    def has_entity(self, entity: Any) -> bool:
        return any(e is entity for e in self.entities)

    def can_execute(self, entity: Any) -> bool:
        """Whether the group lets ``entity``'s callback start now (the executor decides, in
        robomodel; a mutually exclusive group's callbacks queue for their turn)."""
        return self.has_entity(entity)


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One callback of the group at a time."""


class ReentrantCallbackGroup(CallbackGroup):
    """Callbacks of the group in parallel (a multi-threaded executor's threads allowing)."""

    reentrant = True
