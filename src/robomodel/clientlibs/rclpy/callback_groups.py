"""``rclpy.callback_groups``: which callbacks a multi-threaded executor may run at once.

A :class:`MutuallyExclusiveCallbackGroup` runs one of its callbacks at a time (every node's
default group is one); a :class:`ReentrantCallbackGroup` runs any of them in parallel. A
single-threaded executor runs one callback at a time anyway. A group of the user's (a
:class:`CallbackGroup` subclass overriding ``can_execute``, ``beginning_execution`` or
``ending_execution``) is asked before each of its callbacks runs and told after; a call it
refuses is dropped (rclpy's executor leaves the entity ready, to be taken once the group
allows it: a timer's next tick, a subscription's next message here).
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

    def beginning_execution(self, entity: Any) -> bool:
        """Asked before ``entity``'s callback runs: False refuses it."""
        return True

    def ending_execution(self, entity: Any) -> None:
        """Told after ``entity``'s callback ran."""

    def gates(self) -> bool:
        """Whether the group is a user's that decides itself (overrides ``can_execute``,
        ``beginning_execution`` or ``ending_execution``, as a custom rclpy group does):
        then each callback asks it first and tells it after."""
        kind = type(self)
        return (
            kind.can_execute is not CallbackGroup.can_execute
            or kind.beginning_execution is not CallbackGroup.beginning_execution
            or kind.ending_execution is not CallbackGroup.ending_execution
        )


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One callback of the group at a time."""


class ReentrantCallbackGroup(CallbackGroup):
    """Callbacks of the group in parallel (a multi-threaded executor's threads allowing)."""

    reentrant = True
