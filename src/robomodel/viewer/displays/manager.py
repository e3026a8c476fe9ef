"""The viewer's displays: their subscriptions on the viewer's node, drawing and statuses.

:class:`DisplayManager` lives on the viewer's loop thread: :meth:`DisplayManager.update`
(~10 Hz) subscribes each display to what it asks for, lets it draw through TF in the fixed
frame, and keeps its status. Adding, removing, renaming and options are also loop-thread
calls (the panel posts them).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from robomodel.errors import RobomodelError
from robomodel.runtime.clock import BackwardJumps
from robomodel.runtime.msg import MessageTypeError, get_message_type
from robomodel.tf.exceptions import ExtrapolationError, TransformError
from robomodel.viewer.displays.base import (
    Display,
    DisplayContext,
    DisplayStatus,
    Placement,
    SubscriptionSpec,
    display_class,
)

__all__ = ["DisplayManager", "DisplayNameError", "tf_lookup"]

log = logging.getLogger("robomodel.viewer")


class DisplayNameError(RobomodelError):
    """A display name that is empty or already taken."""


def tf_lookup(buffer: Any, fixed_frame: str) -> Callable[[str, int], Placement]:
    """A :data:`~robomodel.viewer.displays.base.FrameLookup` on a TF buffer.

    ``stamp_ns`` 0 is the latest transform; a stamp the buffer has no data for yet (the
    message came before its transform) falls back to the latest, as RViz's message filter
    would show it once the transform arrived. Messages follow RViz's FrameManager.
    """

    def lookup(frame: str, stamp_ns: int = 0) -> Placement:
        if frame.lstrip("/") == fixed_frame:
            return Placement(np.eye(4))
        if not frame:
            return Placement(None, f"No transform from [] to [{fixed_frame}]")
        source = frame.lstrip("/")  # tf2 takes no leading slash (ROS 1 frames may have one)
        try:
            try:
                T = buffer.lookup_transform(fixed_frame, source, stamp_ns).matrix()
            except ExtrapolationError:
                T = buffer.lookup_transform(fixed_frame, source, 0).matrix()
        except TransformError:
            if source not in buffer.frames:
                return Placement(None, f"Frame [{source}] does not exist")
            return Placement(None, f"No transform from [{source}] to [{fixed_frame}]")
        return Placement(np.asarray(T, dtype=np.float64))

    return lookup


class DisplayManager:
    """The displays in panel order, their subscriptions and statuses (loop thread).

    Args:
        context: What each display gets.
        node: The viewer's node (the subscriptions' owner).
        buffer: The viewer's TF buffer.
    """

    def __init__(self, context: DisplayContext, node: Any, buffer: Any) -> None:
        self.context = context
        self.node = node
        self.buffer = buffer
        self.displays: list[Display] = []
        self._subscribed: dict[tuple[int, str], tuple[SubscriptionSpec, Any]] = {}
        # specs whose type could not be found: not asked for again until the spec changes
        # (finding a type may ask the bus's peers, too slow for every update)
        self._failed: dict[tuple[int, str], tuple[SubscriptionSpec, DisplayStatus]] = {}
        self.listeners: list[Callable[[], None]] = []  # told after each update
        self.updates = 0
        self._jumps = BackwardJumps(context.now_ns)  # ROS time, looked at each update

    # -- the list ------------------------------------------------------------------------------
    def unique_name(self, name: str) -> str:
        """``name``, or ``name (2)``... when a display already has it."""
        taken = {d.name for d in self.displays}
        out, n = name, 2
        while out in taken:
            out, n = f"{name} ({n})", n + 1
        return out

    def add(
        self,
        class_name: str,
        name: str | None = None,
        values: Mapping[str, Any] | None = None,
        *,
        enabled: bool = True,
    ) -> Display:
        """A new display of ``class_name`` (``Marker`` or ``rviz/Marker``) at the end.

        Raises:
            UnknownDisplayError: no such display class.
            DisplayOptionError: a value in ``values`` the display cannot take.
        """
        cls = display_class(class_name)
        display = cls(
            self.unique_name(name or cls.class_name), self.context, values, enabled=enabled
        )
        display.option_listeners.append(self._subscribe)
        self.displays.append(display)
        return display

    def get(self, name: str) -> Display:
        for display in self.displays:
            if display.name == name:
                return display
        raise DisplayNameError(f"no display named '{name}'")

    def remove(self, display: Display) -> None:
        self._unsubscribe(display)
        display.close()
        self.displays.remove(display)

    def rename(self, display: Display, name: str) -> None:
        name = name.strip()
        if not name:
            raise DisplayNameError("a display needs a name")
        if name != display.name and any(d.name == name for d in self.displays):
            raise DisplayNameError(f"a display is already named '{name}'")
        display.rename(name)

    def close(self) -> None:
        for display in list(self.displays):
            self.remove(display)

    # -- the loop ------------------------------------------------------------------------------
    def update(self) -> None:
        """Subscribe, draw and collect statuses (loop thread, ~10 Hz)."""
        if self._jumps.back_ns():
            # ROS time went back (a simulation reset, a bag played again, use_sim_time
            # switched on): every display starts over, as RViz's VisualizationManager does
            # on its clock's jump callback (resetTime)
            for display in self.displays:
                display.on_time_jump()
        lookup = tf_lookup(self.buffer, self.context.fixed_frame())
        for display in self.displays:
            problem = self._subscribe(display)
            try:
                status = display.draw(lookup) if display.enabled else DisplayStatus.ok("Disabled")
            except Exception as exc:  # one broken display must not stop the others
                log.exception("display %s failed to draw", display.name)
                status = DisplayStatus.error(f"{type(exc).__name__}: {exc}")
            display.status = status if problem is None else problem.worst(status)
        self.updates += 1
        for listener in self.listeners:
            listener()

    def _subscribe(self, display: Display) -> DisplayStatus | None:
        wanted = {spec.key: spec for spec in display.subscriptions()}
        problem = None
        for (owner, key), (spec, sub) in list(self._subscribed.items()):
            if owner == id(display) and wanted.get(key) != spec:
                _end(sub)
                del self._subscribed[(owner, key)]
        for key, spec in wanted.items():
            if (id(display), key) in self._subscribed:
                continue
            failed = self._failed.get((id(display), key))
            if failed is not None and failed[0] == spec:
                problem = failed[1]
                continue
            try:
                msg_type = get_message_type(spec.type_name)
            except MessageTypeError as exc:
                problem = DisplayStatus.error(f"Error subscribing: {exc}")
                self._failed[(id(display), key)] = (spec, problem)
                continue
            delivery = _Delivery(spec.callback)
            sub = self.node.create_subscription(msg_type, spec.topic, delivery, spec.qos_profile)
            self._subscribed[(id(display), key)] = (spec, _Live(sub, delivery))
        return problem

    def _unsubscribe(self, display: Display) -> None:
        for failed in [k for k in self._failed if k[0] == id(display)]:
            del self._failed[failed]
        for (owner, key), (_spec, sub) in list(self._subscribed.items()):
            if owner == id(display):
                _end(sub)
                del self._subscribed[(owner, key)]


class _Delivery:
    """A subscription's callback that stops at once when the subscription is replaced: a
    message of the old topic already queued must not count for the new one (RViz resets a
    display when its topic changes)."""

    def __init__(self, callback: Callable[[Any], object]) -> None:
        self.callback = callback
        self.live = True

    def __call__(self, msg: Any) -> None:
        if self.live:
            self.callback(msg)


@dataclass(frozen=True, slots=True)
class _Live:
    """A display's subscription and the callback that ends with it."""

    subscription: Any
    delivery: _Delivery


def _end(live: _Live) -> None:
    live.delivery.live = False
    live.subscription.destroy()
