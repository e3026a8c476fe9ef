"""viser's node pose messages, serialised without viser's generic per-field walk.

viser turns every outgoing message into a dict by walking its fields against their type
hints (``Message.as_serializable_dict``: ~7 us for a ``SetOrientationMessage``). A large
robot sends one or two of these per link per scene update, so at 1,000 links that walk was
most of viser's own work per update (~14 ms). The subclasses here build the same dict
directly (~0.3 us) and keep the base class's redundancy key, so the client and viser's
message buffer cannot tell them apart.

They depend on viser's private message module; :func:`pose_message_types` checks, once,
that the fast dicts and keys equal what viser itself produces for a probe message and
returns None otherwise (:func:`write_pose` then sets poses through viser's public setters).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any, NamedTuple

__all__ = ["PoseMessageTypes", "pose_message_types", "write_pose"]


class PoseMessageTypes(NamedTuple):
    """Message classes for a node's orientation (``wxyz``) and position (``xyz`` [m])."""

    orientation: type
    position: type


@functools.cache
def pose_message_types() -> PoseMessageTypes | None:
    """The fast pose message classes, or None if this viser's messages differ from 1.1's."""
    try:
        from viser import _messages
    except ImportError:
        return None
    base_orientation = getattr(_messages, "SetOrientationMessage", None)
    base_position = getattr(_messages, "SetPositionMessage", None)
    if base_orientation is None or base_position is None:
        return None
    try:
        types = PoseMessageTypes(
            _fast_subclass(base_orientation, "wxyz"), _fast_subclass(base_position, "position")
        )
        same = _same_as_viser(types.orientation, base_orientation, (1.0, 0.0, 0.0, 0.0))
        same = same and _same_as_viser(types.position, base_position, (0.5, -1.0, 2.0))
    except Exception:  # any change in viser's message machinery: use its own classes
        return None
    return types if same else None


def write_pose(scene: Any, handle: Any, wxyz: list[float] | None, xyz: list[float] | None) -> None:
    """Set a node's orientation and/or position (None: unchanged), known to have changed.

    viser's ``wxyz``/``position`` setters cast, compare (``np.allclose``) and copy on every
    call, which is most of the cost of a 60-link update. When this viser has the same
    internals as 1.1 (``scene._queue_scene_message``, its pose messages), the messages are
    queued directly, as the quickly serialised subclasses of :func:`pose_message_types`, and
    the handle's state updated in place; otherwise the public setters.

    Args:
        scene: viser's scene API (``server.scene``) the node belongs to.
        handle: The node's viser handle.
        wxyz: The new orientation, or None to keep it.
        xyz: The new position [m], or None to keep it.
    """
    queue = getattr(scene, "_queue_scene_message", None)
    impl = getattr(handle, "_impl", None)
    messages = pose_message_types()
    if queue is None or impl is None or messages is None:
        if wxyz is not None:
            handle.wxyz = wxyz
        if xyz is not None:
            handle.position = xyz
        return
    if wxyz is not None:
        w, x, y, z = wxyz
        impl.wxyz[:] = (w, x, y, z)
        queue(messages.orientation(impl.name, (w, x, y, z)))
    if xyz is not None:
        px, py, pz = xyz
        impl.position[:] = (px, py, pz)
        queue(messages.position(impl.name, (px, py, pz)))


def _fast_subclass(base: type, field: str) -> type:
    """A subclass of ``base`` (fields ``name``, ``field``, ``owner``) with a direct dict."""
    type_name = base.__name__

    def as_serializable_dict(self: Any, binary_buffers: Any = None) -> dict[str, Any]:
        del binary_buffers  # pose tuples carry no binary payload
        return {
            "name": self.name,
            field: getattr(self, field),
            "owner": self.owner,
            "type": type_name,
        }

    def redundancy_key(self: Any) -> str:
        # viser keys updates by the class name: keep the base's, so a pose sent through
        # viser's own setters and one sent here replace each other in its buffer.
        return f"{self.entity_type}:{self.name}:update:{type_name}"

    def entity_state_key(self: Any) -> tuple[str, str]:
        # viser asks this (and the key above) up to three times per message it queues.
        return (self.entity_type, self.name)

    namespace = {
        "__module__": __name__,
        "as_serializable_dict": as_serializable_dict,
        "redundancy_key": redundancy_key,
        "entity_state_key": entity_state_key,
    }
    # The leading underscore keeps the class out of viser's name -> class table for messages
    # arriving from clients (Message.get_subclasses skips such names).
    cls = type(f"_Fast{type_name}", (base,), {**namespace, "__qualname__": f"_Fast{type_name}"})
    return dataclasses.dataclass(cls)


def _same_as_viser(fast: type, base: type, value: tuple[float, ...]) -> bool:
    """Whether ``fast`` serialises and keys a probe message exactly as viser's ``base`` does."""
    ours, theirs = fast("/probe", value), base("/probe", value)
    ours.owner = theirs.owner = "probe-owner"
    return bool(
        ours.as_serializable_dict() == theirs.as_serializable_dict()
        and ours.redundancy_key() == theirs.redundancy_key()
        and ours.entity_state_key() == theirs.entity_state_key()
    )
