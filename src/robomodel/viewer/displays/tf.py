"""RViz's TF display: every TF frame's axes, name and arrow to its parent, in the fixed frame.

Options and defaults are RViz's (rviz_default_plugins/displays/tf/tf_display.cpp, ros2/rviz at
f7112b1; RViz 1's are the same): Show Names, Show Axes, Show Arrows, Marker Scale (axes
0.1 m long at 1), Update Interval (0: every update), Frame Timeout (a frame looks as usual
for the first third of it, fades to grey over the second and out over the last, and is not
drawn once older: :mod:`.tf_fade`; static transforms never age) and Frames (``All
Enabled`` and one entry per frame seen, false hides that frame; written as RViz does,
``Frames: {All Enabled: true, base_link: {Value: true}}``).
Arrows go from each frame to its parent, shaft yellow and head pink at the parent
(``FrameInfo::ARROW_SHAFT_COLOR``, ``ARROW_HEAD_COLOR``).

The viewer looks every frame up in the fixed frame when it sends a scene update (at its Frame
Rate, with the robots' links) and hands the result to :meth:`TFDisplay.show_frames`.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.tf.exceptions import TransformError
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
)
from robomodel.viewer.displays.tf_fade import AXES_RGBA, HEAD_RGBA, SHAFT_RGBA, aged_rgba, rgb8
from robomodel.viewer.tf_display import TFDisplay as FrameMarkers

__all__ = ["TFDisplay", "frame_enabled"]

_ARROW_RGBA = (SHAFT_RGBA, HEAD_RGBA)  # from the child to the parent
_ALL = "All Enabled"


def frame_enabled(frames: Mapping[str, Any], frame: str) -> bool:
    """Whether ``frame`` is drawn by a Frames option (its own entry, a bool or RViz's
    ``{Value: bool}``; a frame without one follows All Enabled)."""
    entry = frames.get(frame, frames.get(_ALL, True))
    if isinstance(entry, Mapping):
        entry = entry.get("Value", True)
    return bool(entry)


def _latest_time_ns(buffer: Any, fixed_frame: str, frame: str) -> int | None:
    """The newest time ``frame`` is known at in the fixed frame (tf2's latest common time, as
    TFDisplay::updateFrame asks it: a static frame below a moving one ages with it); None if
    only static transforms join them (never ages) or nothing does (not drawn anyway)."""
    try:
        return int(buffer.latest_common_time_ns(fixed_frame, frame)) or None
    except TransformError:
        return None


@register_display
class TFDisplay(Display):
    """RViz's TF display with its options and defaults."""

    class_name = "TF"
    options = (
        Option("Show Names", False, OptionKind.BOOL,
               help="Whether or not names should be shown next to the frames."),
        Option("Show Axes", True, OptionKind.BOOL,
               help="Whether or not the axes of each frame should be shown."),
        Option("Show Arrows", True, OptionKind.BOOL,
               help="Whether or not arrows from child to parent should be shown."),
        Option("Marker Scale", 1.0, OptionKind.FLOAT, minimum=0.0,
               help="Scaling factor for all names, axes and arrows."),
        Option("Update Interval", 0.0, OptionKind.FLOAT, minimum=0.0,
               help="The interval, in seconds, at which to update the frame transforms. 0 means "
               "to do so every update cycle."),
        Option("Frame Timeout", 15.0, OptionKind.FLOAT, minimum=1.0,
               help="The length of time, in seconds, before a frame that has not been updated is "
               "considered 'dead'."),
        Option("Frames", MappingProxyType({_ALL: True}), OptionKind.MAP,
               help="The list of all frames; false hides one"),
    )  # fmt: skip

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.markers = self._new_markers()
        self.shown: tuple[str, ...] = ()  # the frames drawn at the last update
        self._last_update_ns: int | None = None
        self._arrows_key: bytes = b""
        self._all_enabled = frame_enabled(self.option("Frames"), _ALL)
        self.seen: dict[str, None] = {}  # every frame shown so far, in order
        # frame -> (its newest stamp [ns], when that stamp was first seen [ns]): the frame's
        # age is the time since (FrameInfo::setLastUpdate). Kept through resets: RViz would
        # draw a long dead frame again for a Frame Timeout after a reset, a quirk not copied.
        self._last_update: dict[str, tuple[int, int]] = {}

    def _new_markers(self) -> FrameMarkers:
        v = self.values
        return FrameMarkers(self.context.scene, self.root, show_axes=bool(v["Show Axes"]),
                            show_names=bool(v["Show Names"]),
                            marker_scale=float(v["Marker Scale"]))  # fmt: skip

    def reset(self) -> None:
        super().reset()
        self.markers.remove()
        self.markers = self._new_markers()
        self.shown = ()
        self._last_update_ns = None
        self._arrows_key = b""

    def on_renamed(self) -> None:
        self.reset()

    def on_time_jump(self) -> None:
        self.reset()
        self._last_update.clear()  # ages on the clock before the jump mean nothing after it

    def close(self) -> None:
        super().close()
        self.markers.remove()  # drawn below root, not through add_node

    def on_option_changed(self, name: str) -> None:
        if name == "Frames":  # a frame switched on or off: drawn again at the next update
            self._follow_all_enabled()
            self._last_update_ns = None
            return
        self.reset()

    def _follow_all_enabled(self) -> None:
        """All Enabled switched: every frame follows it (TFDisplay::allEnabledChanged)."""
        frames = self.option("Frames")
        everything = frame_enabled(frames, _ALL)
        if everything == self._all_enabled:
            return
        self._all_enabled = everything
        self.values["Frames"] = MappingProxyType(
            {k: v if k == _ALL else {"Value": everything} for k, v in frames.items()}
        )

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        return DisplayStatus.ok(f"{len(self.shown)} frames")

    def show_frames(
        self,
        frames: tuple[str, ...],
        wxyz: NDArray[np.float64],
        xyz: NDArray[np.float64],
        visible: NDArray[np.bool_],
        buffer: Any,
    ) -> None:
        """Draw ``frames`` at their poses in the fixed frame (``visible``: found there); the
        ``buffer`` gives each one's parent and the age of its newest transform."""
        if not self.enabled:
            return
        now_ns = self.context.now_ns()
        interval_ns = int(float(self.option("Update Interval")) * 1e9)
        if self._last_update_ns is not None and now_ns - self._last_update_ns < interval_ns:
            return
        self._last_update_ns = now_ns
        self.seen.update(dict.fromkeys(frames))
        parents = {f: buffer.latest_parent(f) for f in frames}
        timeout_s = float(self.option("Frame Timeout"))
        fixed = self.context.fixed_frame()
        age_s = np.array([self._age_s(f, _latest_time_ns(buffer, fixed, f), now_ns) for f in frames])  # fmt: skip
        enabled = [frame_enabled(self.option("Frames"), f) for f in frames]
        drawn = np.asarray(visible, dtype=bool) & (age_s <= timeout_s) & np.array(enabled, bool)
        self.markers.update(frames, wxyz, xyz, drawn, aged_rgba(AXES_RGBA, age_s, timeout_s))
        self.shown = tuple(f for f, on in zip(frames, drawn, strict=True) if on)
        arrows_rgba = aged_rgba(_ARROW_RGBA, age_s, timeout_s)
        self._draw_arrows(frames, xyz, drawn, {f: p[1] for f, p in parents.items()}, arrows_rgba)

    def fading(self) -> bool:
        """Whether a frame drawn at the last update is now older than a third of Frame Timeout
        (it greys, fades and goes as time passes): the viewer then updates the scene though
        nothing moved."""
        if not self.enabled:
            return False
        since_ns = self.context.now_ns() - float(self.option("Frame Timeout")) * 1e9 / 3
        return any(self._last_update[f][1] < since_ns for f in self.shown if f in self._last_update)

    def map_entries(self, name: str) -> Mapping[str, Any]:
        """Frames lists every frame seen (as RViz's tree does); the option holds only the
        entries read or switched, so what the viewer happened to see is not saved."""
        entries: Mapping[str, Any] = self.values[name]
        if name != "Frames":
            return entries
        seen = {f: {"Value": frame_enabled(entries, f)} for f in self.seen if f not in entries}
        return MappingProxyType({**entries, **seen})

    def _age_s(self, frame: str, stamp_ns: int | None, now_ns: int) -> float:
        """Seconds since ``frame``'s newest stamp changed; 0 for static transforms (None)."""
        if stamp_ns is None:
            self._last_update.pop(frame, None)
            return 0.0
        seen = self._last_update.get(frame)
        if seen is None or seen[0] != stamp_ns:
            seen = self._last_update[frame] = (stamp_ns, now_ns)
        return max(0.0, (now_ns - seen[1]) / 1e9)

    def _draw_arrows(self, frames: tuple[str, ...], xyz: NDArray[np.float64], drawn: NDArray[np.bool_], parents: Mapping[str, str | None], rgba: NDArray[np.float64]) -> None:  # fmt: skip
        """Arrows from each drawn frame to its drawn parent, in the child's ``rgba`` (shape
        (n, 2, 4): shaft and head; viser's line segments take no alpha, so a frame's arrow
        stays opaque grey over the last third of its Frame Timeout)."""
        index = {f: i for i, f in enumerate(frames) if drawn[i]}
        pairs = [(index[f], index[p]) for f, p in parents.items()
                 if f in index and p is not None and p in index]  # fmt: skip
        if not self.option("Show Arrows") or not pairs:
            self.remove_node("arrows")
            self._arrows_key = b""
            return
        points = np.array([[xyz[c], xyz[p]] for c, p in pairs], dtype=np.float32)
        colors = rgb8(rgba[[c for c, _ in pairs]])
        key = points.tobytes() + colors.tobytes()
        if key == self._arrows_key and self.node("arrows") is not None:
            return
        self._arrows_key = key
        self.add_node("arrows", "line_segments", points=points, colors=colors,
                      thickness=2.0 * float(self.option("Marker Scale")),
                      thickness_units="screen")  # fmt: skip
