"""``rclpy.guard_condition.GuardCondition``: a callback run by the executor holding its node
when any thread calls :meth:`GuardCondition.trigger` (``Node.create_guard_condition``).

As rclpy's: triggers that come before the callback ran call it once, on the executor's thread,
in its callback group.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered
from robomodel.clientlibs.rclpy.utilities import get_default_context

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.context import Context

__all__ = ["GuardCondition"]


class GuardCondition:
    """Run ``callback()`` after :meth:`trigger`. One made by ``Node.create_guard_condition``
    runs on the executor holding the node; one made directly has no node to run on, as in
    rclpy, and its trigger only wakes the executors waiting on ``context``."""

    def __init__(
        self,
        callback: Callable[[], Any] | None,
        callback_group: CallbackGroup | None,
        context: Context | None = None,
        *,
        fire: Callable[[], None] | None = None,
    ) -> None:
        self.callback = callback
        self.callback_group = callback_group
        self._context = context or get_default_context()
        self._fire = fire  # the node's delivery of the callback (robomodel's, from the node)
        self._destroyed = False
        self._pending = threading.Lock()  # held from a trigger until its callback is delivered

    def trigger(self) -> None:
        """Have the callback run (once for the triggers before it runs); any thread."""
        if self._destroyed:
            return
        if self._fire is None or self.callback is None:
            self._context.wake()
        elif self._pending.acquire(blocking=False):  # else: one delivery waits already
            self._context._post(self._deliver)

    def _deliver(self) -> None:
        self._pending.release()  # a trigger from now on calls again
        if self._fire is not None and not self._destroyed:
            self._fire()

    @property
    def handle(self) -> Any:
        not_offered("GuardCondition.handle (rcl's handle)")

    def destroy(self) -> None:
        self._destroyed = True

    def __enter__(self) -> GuardCondition:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy()
