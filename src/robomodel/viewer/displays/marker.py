"""RViz's Marker and MarkerArray displays.

Markers are kept by ``(ns, id)`` (:mod:`.marker_store`) and drawn as RViz draws them
(:mod:`.marker_geometry`). Placement follows RViz's MarkerBase: a marker is put in the fixed
frame once, through TF at its ``header.stamp`` (0: the latest transform), and stays there; a
``frame_locked`` marker is looked up again at every draw and moves with its frame. A marker
whose frame has no transform is hidden and named in the status ("ns/id: No transform from
[x] to [y]"). The ``Namespaces`` option holds every namespace seen with whether it is shown,
as RViz saves it; a namespace switched off hides its markers without forgetting them.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.errors import RobomodelError
from robomodel.viewer._poses import wxyz_xyz_from_matrix
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
    stamp_ns,
)
from robomodel.viewer.displays.marker_geometry import (
    MarkerShapeError,
    bounded_marker,
    marker_drawables,
)
from robomodel.viewer.displays.marker_store import MarkerKey, MarkerStore

__all__ = ["MarkerArrayDisplay", "MarkerDisplay", "pose_matrix"]


def pose_matrix(pose: Any) -> NDArray[np.float64]:
    """A ``geometry_msgs/Pose`` as a 4x4 (an all-zero quaternion as the identity, as RViz 1
    and most publishers of "no orientation" expect)."""
    q = pose.orientation
    x, y, z, w = float(q.x), float(q.y), float(q.z), float(q.w)
    norm = (x * x + y * y + z * z + w * w) ** 0.5
    x, y, z, w = (0.0, 0.0, 0.0, 1.0) if norm == 0.0 else (x / norm, y / norm, z / norm, w / norm)
    T = np.eye(4)
    T[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    T[:3, 3] = (pose.position.x, pose.position.y, pose.position.z)
    return T


# What places a marker rather than shapes it (RViz's MarkerBase::transform reads these)
_PLACEMENT_FIELDS = frozenset({"header", "pose", "lifetime", "frame_locked", "action"})


def _same_shape(a: Any, b: Any) -> bool:
    """Whether two markers of one key draw the same nodes (they may be placed elsewhere)."""
    names = a.field_names() if hasattr(a, "field_names") else ()
    return (
        type(a) is type(b)
        and bool(names)
        and all(
            getattr(a, name) == getattr(b, name) for name in names if name not in _PLACEMENT_FIELDS
        )
    )


@dataclass
class _Drawn:
    """A marker on the page: its version, nodes and where it was placed."""

    version: int
    msg: Any
    keys: tuple[str, ...]
    facing: tuple[str, ...] = ()  # nodes turned to the camera (view-facing text)
    T_fixed_marker: NDArray[np.float64] | None = None
    fixed_frame: str = ""
    error: str = ""  # why it cannot be drawn (RViz's marker status)
    note: str = ""  # what of it is not drawn (over a bound of robomodel.viewer.limits)


class MarkerDisplay(Display):
    """RViz's Marker display (``visualization_msgs/Marker`` on one topic)."""

    class_name = "Marker"
    message_types = ("visualization_msgs/msg/Marker",)
    options = (
        Option("Topic", "/visualization_marker", OptionKind.TOPIC, help="Marker topic"),
        Option("Queue Size", 100, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Namespaces", {}, OptionKind.MAP, help="Namespaces seen; false hides one"),
    )
    ros1_keys = MappingProxyType({"Topic": "Marker Topic"})

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.store = MarkerStore()
        self.store.namespaces.update({str(k): bool(v) for k, v in self.option("Namespaces").items()})  # fmt: skip
        self._drawn: dict[MarkerKey, _Drawn] = {}
        self._ns_index: dict[str, int] = {}

    # -- messages ------------------------------------------------------------------------------
    def on_message(self, msg: Any) -> None:
        self.store.apply(msg, self.context.now_ns())

    # -- options -------------------------------------------------------------------------------
    def on_option_changed(self, name: str) -> None:
        if name == "Namespaces":
            self.store.namespaces.update({str(k): bool(v) for k, v in self.option(name).items()})
        elif name == "Topic":  # RViz's onTopicChanged: a new topic starts empty
            self.store.clear()
            self.messages_received = 0
        self.reset()

    def set_namespace_enabled(self, ns: str, enabled: bool) -> None:
        """Show or hide a namespace (the ``Namespaces`` option's entry)."""
        self.set_option("Namespaces", {**self.option("Namespaces"), ns: enabled})

    def reset(self) -> None:
        super().reset()
        self._drawn.clear()

    def on_renamed(self) -> None:
        self._drawn.clear()

    def on_enabled_changed(self) -> None:
        if not self.enabled:  # RViz's onDisable clears the markers
            self.store.clear()

    # -- drawing -------------------------------------------------------------------------------
    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        for key in self.store.expire(self.context.now_ns()):
            self._undraw(key)
        new = {ns: True for ns in self.store.namespaces if ns not in self.option("Namespaces")}
        if new:
            self.values["Namespaces"] = MappingProxyType({**self.option("Namespaces"), **new})
        shown = self.store.shown()
        for key, drawn in list(self._drawn.items()):
            entry = shown.get(key)
            if entry is not None and entry.version != drawn.version and _same_shape(entry.msg, drawn.msg):  # fmt: skip
                # the same marker sent again: placed anew, its nodes kept (a re-sent mesh or
                # text is not loaded again, so it does not flicker)
                drawn.version, drawn.msg, drawn.T_fixed_marker = entry.version, entry.msg, None
            elif entry is None or entry.version != drawn.version:
                self._undraw(key)
        problems: list[str] = [*self.store.errors]
        fixed = self.context.fixed_frame()
        for key, entry in shown.items():
            problem = self._draw_marker(key, entry, lookup, fixed)
            if problem:
                problems.append(f"{key[0]}/{key[1]}: {problem}")
        self._face_camera()
        notes = [f"{k[0]}/{k[1]}: {d.note}" for k, d in self._drawn.items() if d.note]
        return self._status(problems, [*self.store.notes, *notes])

    def _face_camera(self) -> None:
        """Turn view-facing text to the page's camera: an image node with the camera's
        orientation lies in the screen's plane, upright (viser's camera: +z forward, -y up)."""
        view = self.context.view_wxyz() if self.context.view_wxyz is not None else None
        if view is None:
            return
        for drawn in self._drawn.values():
            for node_key in drawn.facing:
                node = self.node(node_key)
                if node is not None and not np.allclose(node.wxyz, view, atol=1e-6):
                    node.wxyz = view

    def _status(self, problems: list[str], notes: list[str]) -> DisplayStatus:
        waiting = self.topic_status()
        if problems:
            more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
            return DisplayStatus.error(problems[0] + more)
        if waiting is not None:
            return waiting
        if notes:
            more = f" (and {len(notes) - 1} more)" if len(notes) > 1 else ""
            return DisplayStatus.warn(notes[0] + more)
        return DisplayStatus.ok(f"{self.messages_received} messages received")

    def _draw_marker(self, key: MarkerKey, entry: Any, lookup: FrameLookup, fixed: str) -> str:
        msg = entry.msg
        drawn = self._drawn.get(key)
        if drawn is None:
            bounded, note = bounded_marker(msg)
            try:
                drawables = marker_drawables(bounded, self.context.load_mesh)
            except (MarkerShapeError, RobomodelError) as exc:
                self._drawn[key] = _Drawn(entry.version, msg, (), error=str(exc))
                return str(exc)
            prefix = self._node_prefix(key)
            keys = tuple(f"{prefix}/{i}" for i in range(len(drawables)))
            for node_key, drawable in zip(keys, drawables, strict=True):
                self.add_node(node_key, drawable.kind, visible=False, **drawable.kwargs)
            facing = tuple(k for k, d in zip(keys, drawables, strict=True) if d.view_facing)
            drawn = self._drawn[key] = _Drawn(entry.version, msg, keys, facing, note=note)
        if drawn.error:
            return drawn.error
        if drawn.T_fixed_marker is None or msg.frame_locked or drawn.fixed_frame != fixed:
            placement = lookup(msg.header.frame_id, 0 if msg.frame_locked else stamp_ns(msg.header.stamp))  # fmt: skip
            if placement.T_fixed_frame is None:
                self._show(drawn, False)
                drawn.T_fixed_marker = None
                return placement.reason
            drawn.T_fixed_marker = placement.T_fixed_frame @ pose_matrix(msg.pose)
            drawn.fixed_frame = fixed
            wxyz, xyz = wxyz_xyz_from_matrix(drawn.T_fixed_marker)
            for node_key in drawn.keys:
                node = self.node(node_key)
                node.position = xyz
                if node_key not in drawn.facing:
                    node.wxyz = wxyz
        self._show(drawn, True)
        return ""

    def _show(self, drawn: _Drawn, visible: bool) -> None:
        for node_key in drawn.keys:
            node = self.node(node_key)
            if node is not None and node.visible != visible:
                node.visible = visible

    def _node_prefix(self, key: MarkerKey) -> str:
        # Namespaces by index: any text is a valid ns, not every text a scene path.
        index = self._ns_index.setdefault(key[0], len(self._ns_index))
        return f"ns{index}/{key[1]}"

    def _undraw(self, key: MarkerKey) -> None:
        drawn = self._drawn.pop(key, None)
        for node_key in drawn.keys if drawn is not None else ():
            self.remove_node(node_key)

    def close(self) -> None:
        super().close()
        self.store.clear()


register_display(MarkerDisplay)


@register_display
class MarkerArrayDisplay(MarkerDisplay):
    """RViz's MarkerArray display (``visualization_msgs/MarkerArray`` on one topic)."""

    class_name = "MarkerArray"
    message_types = ("visualization_msgs/msg/MarkerArray",)
    options = (
        Option("Topic", "/visualization_marker_array", OptionKind.TOPIC, help="Marker topic"),
        *MarkerDisplay.options[1:],
    )

    def on_message(self, msg: Any) -> None:
        now = self.context.now_ns()
        for marker in msg.markers:
            self.store.apply(marker, now)
