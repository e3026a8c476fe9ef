"""RViz's PointCloud2 display (point_cloud2_display.cpp, point_cloud_common.cpp).

A cloud is placed once, through TF at its stamp, when it is first drawn, and stays there (as
RViz's CloudInfo); "Decay Time" keeps the clouds received in the last that many seconds (0:
only the newest). Each kept cloud is one scene node posed at its frame, so the points are
sent as they are in the message and never transformed on the CPU; a new cloud takes the node
of the one it replaces (its points, colours and pose updated: cheaper than a new node, in
this process and in the browser). Positions go as float16 where that moves no point by more
than half its size (:func:`wire_precision`), FlatColor as one colour. Sizes are in metres: a
browser point's size is a world size, so the "Points" style, whose size RViz gives in pixels,
is drawn with "Size (m)" too. "Alpha" and "Selectable" are kept for the config only.
"""

from __future__ import annotations

import collections
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer.displays._placed import combine, place, pose_kwargs
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    StatusLevel,
    color_rgb,
    register_display,
)
from robomodel.viewer.displays.cloud import (
    COLOR_TRANSFORMERS,
    CloudColorOptions,
    CloudError,
    DecodedCloud,
    color_transformers_for,
    decode_cloud,
    default_color_transformer,
)
from robomodel.viewer.limits import MAX_CLOUD_BYTES_KEPT, MAX_CLOUD_POINTS, MAX_CLOUDS_KEPT

__all__ = ["PointCloud2Display", "wire_precision"]

_STYLES = ("Points", "Squares", "Flat Squares", "Spheres", "Boxes", "Tiles")
_SHAPES = {"Points": "circle", "Spheres": "circle"}  # the others are squares
_FRAME_NS = 1_000_000_000 // 30  # RViz's default frame rate


@dataclass
class _Cloud:
    """A received cloud: placed (key set) once drawn."""

    msg: Any
    received_ns: int
    key: str = ""
    points: int = 0
    failed: bool = False


@register_display
class PointCloud2Display(Display):
    """RViz's PointCloud2 display with its options and defaults."""

    class_name = "PointCloud2"
    message_types = ("sensor_msgs/msg/PointCloud2",)
    options = (
        Option("Topic", "", OptionKind.TOPIC, help="sensor_msgs/PointCloud2 topic"),
        # rviz_common's QosProfileProperty: depth 5 by default
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Selectable", True, OptionKind.BOOL),
        Option("Style", "Flat Squares", OptionKind.CHOICE, choices=_STYLES),
        Option("Size (m)", 0.01, OptionKind.FLOAT, minimum=0.0001, help="Point size in meters"),
        Option("Size (Pixels)", 3.0, OptionKind.FLOAT, minimum=0.0),
        Option("Alpha", 1.0, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Decay Time", 0.0, OptionKind.FLOAT, minimum=0.0, help="Seconds to keep points"),
        Option("Position Transformer", "XYZ", OptionKind.CHOICE, choices=("XYZ",)),
        Option("Color Transformer", "Intensity", OptionKind.CHOICE, choices=COLOR_TRANSFORMERS),
        Option("Channel Name", "intensity", OptionKind.TEXT),
        Option("Use rainbow", True, OptionKind.BOOL),
        Option("Invert Rainbow", False, OptionKind.BOOL),
        Option("Min Color", "0; 0; 0", OptionKind.COLOR),
        Option("Max Color", "255; 255; 255", OptionKind.COLOR),
        Option("Autocompute Intensity Bounds", True, OptionKind.BOOL),
        Option("Min Intensity", 0.0, OptionKind.FLOAT),
        Option("Max Intensity", 4096.0, OptionKind.FLOAT),
        Option("Axis", "Z", OptionKind.CHOICE, choices=("X", "Y", "Z")),
        Option("Autocompute Value Bounds", True, OptionKind.BOOL),
        Option("Min Value", -10.0, OptionKind.FLOAT),
        Option("Max Value", 10.0, OptionKind.FLOAT),
        Option("Use Fixed Frame", True, OptionKind.BOOL),
        Option("Color", "255; 255; 255", OptionKind.COLOR),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        values = args[2] if len(args) > 2 else kwargs.get("values")
        # RViz starts with no colour transformer and picks one for the first cloud (RGB8
        # when it has rgb); one given by a config is kept.
        self._auto_color = not (values and "Color Transformer" in values)
        self._clouds: collections.deque[_Cloud] = collections.deque()
        self._seq = 0
        self._message_error = ""  # RViz's "Message" status: the last cloud that failed
        self._truncated_note = ""  # the last cloud drawn truncated (over MAX_CLOUD_POINTS)
        self._last_lookup: tuple[str, FrameLookup] | None = None  # (fixed frame, lookup)
        self._drawn_ns = 0  # when a cloud was last put in the scene [ns, bus time]
        self._dropped_keys: list[str] = []  # scene nodes of clouds dropped past the bound
        self._bound_note = ""  # set once Decay Time kept more than the bound allows

    def on_message(self, msg: Any) -> None:
        now = self.context.now_ns()
        self._clouds.append(_Cloud(msg, now))
        self._keep_within_bound()
        # RViz draws a new cloud at its next render (30 fps); the page's displays are drawn
        # at 10 Hz, so a 10 Hz cloud would often wait behind the next one and be dropped.
        # Drawn at once instead (with the last draw's TF lookup, for the same fixed frame),
        # at most at RViz's frame rate.
        last = self._last_lookup
        if last is not None and last[0] == self.context.fixed_frame() and now - self._drawn_ns >= _FRAME_NS:  # fmt: skip
            self.draw(last[1])

    def on_option_changed(self, name: str) -> None:
        if name == "Color Transformer":
            self._auto_color = False
        if name in ("Topic", "Queue Size"):
            self._clouds.clear()
            self._bound_note = ""
            self.messages_received = 0
        self.remove_nodes()  # redrawn from the kept messages with the new options
        self._dropped_keys.clear()
        for cloud in self._clouds:
            cloud.key = ""

    def reset(self) -> None:
        super().reset()
        self._clouds.clear()
        self._dropped_keys.clear()
        self._bound_note = ""

    def on_renamed(self) -> None:
        for cloud in self._clouds:
            cloud.key = ""

    def color_options(self) -> CloudColorOptions:
        """The colour options as the cloud decoder takes them."""
        v = self.values
        return CloudColorOptions(
            transformer=str(v["Color Transformer"]),
            channel_name=str(v["Channel Name"]),
            use_rainbow=bool(v["Use rainbow"]),
            invert_rainbow=bool(v["Invert Rainbow"]),
            min_color=color_rgb(v["Min Color"]),
            max_color=color_rgb(v["Max Color"]),
            autocompute_intensity_bounds=bool(v["Autocompute Intensity Bounds"]),
            min_intensity=float(v["Min Intensity"]),
            max_intensity=float(v["Max Intensity"]),
            axis=str(v["Axis"]),
            autocompute_value_bounds=bool(v["Autocompute Value Bounds"]),
            min_value=float(v["Min Value"]),
            max_value=float(v["Max Value"]),
            use_fixed_frame=bool(v["Use Fixed Frame"]),
            color=color_rgb(v["Color"]),
        )

    def _choose_transformer(self, msg: Any) -> None:
        """RViz's updateTransformers: keep a valid choice, else RGB8 or the best score."""
        current = self.values["Color Transformer"]
        if self._auto_color or current not in color_transformers_for(msg):
            self.values["Color Transformer"] = default_color_transformer(msg)
            self._auto_color = False

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        self._last_lookup = (self.context.fixed_frame(), lookup)
        spare = self._expire()
        problems: list[str] = []
        for cloud in [c for c in self._clouds if not c.key]:
            problem = self._place(cloud, lookup, spare)
            if problem:
                problems.append(problem)
        for key in spare:
            self.remove_node(key)
        # a cloud that could not be placed is dropped once a newer one is shown (RViz)
        newest = self._clouds[-1] if self._clouds else None
        self._clouds = collections.deque(
            c for c in self._clouds if c.key or (c is newest and not c.failed)
        )
        if self._message_error:
            problems.append(self._message_error)
        shown = [c for c in self._clouds if c.key]
        total = sum(c.points for c in shown)
        ok = f"Showing [{total}] points from [{len(shown)}] messages"
        status = combine(self.topic_status(), problems, ok)
        notes = "; ".join(note for note in (self._truncated_note, self._bound_note) if note)
        if notes and status.level is StatusLevel.OK:
            return DisplayStatus.warn(f"{ok}; {notes}")
        return status

    def _keep_within_bound(self) -> None:
        """Drop the oldest clouds while more than ``MAX_CLOUDS_KEPT`` clouds or
        ``MAX_CLOUD_BYTES_KEPT`` bytes of point data are kept (a long Decay Time at a high
        rate), keeping the newest; RViz keeps them all."""
        kept = sum(len(cloud.msg.data) for cloud in self._clouds)
        while len(self._clouds) > 1 and (
            len(self._clouds) > MAX_CLOUDS_KEPT or kept > MAX_CLOUD_BYTES_KEPT
        ):
            old = self._clouds.popleft()
            kept -= len(old.msg.data)
            if old.key:
                self._dropped_keys.append(old.key)
            self._bound_note = (
                f"Decay Time keeps at most {MAX_CLOUDS_KEPT} clouds and "
                f"{MAX_CLOUD_BYTES_KEPT // 2**20} MiB of points: older clouds dropped"
            )

    def _expire(self) -> list[str]:
        """Drop clouds older than "Decay Time", keeping the newest (cloudInfoIsDecayed); the
        keys of their scene nodes (and of those dropped past the bound), for the new clouds to
        take (removed if none does)."""
        decay_ns = float(self.values["Decay Time"]) * 1e9
        now = self.context.now_ns()
        spare, self._dropped_keys = self._dropped_keys, []
        while len(self._clouds) > 1 and now - self._clouds[0].received_ns > decay_ns:
            old = self._clouds.popleft()
            if old.key:
                spare.append(old.key)
        return spare

    def _place(self, cloud: _Cloud, lookup: FrameLookup, spare: list[str]) -> str:
        placement = place(lookup, cloud.msg.header)
        if placement.T_fixed_frame is None:
            return placement.reason
        try:
            self._choose_transformer(cloud.msg)
            decoded = decode_cloud(cloud.msg, self.color_options(), T_fixed_cloud=placement.T_fixed_frame)  # fmt: skip
        except CloudError as exc:
            cloud.failed = True
            self._message_error = str(exc)
            return ""
        self._message_error = ""
        self._truncated_note = (
            f"a cloud of {MAX_CLOUD_POINTS + decoded.truncated} points "
            f"drawn truncated to its first {MAX_CLOUD_POINTS}"
            if decoded.truncated
            else ""
        )
        self._remember_bounds(decoded.transformer, decoded.bounds)
        self._show(cloud, decoded, placement.T_fixed_frame, spare)
        return ""

    def _show(self, cloud: _Cloud, decoded: DecodedCloud, T_fixed_cloud: NDArray[np.float64], spare: list[str]) -> None:  # fmt: skip
        """Put a decoded cloud in the scene: in a spare node (a dropped cloud's) or a new one."""
        self._seq += 1
        self._drawn_ns = self.context.now_ns()
        cloud.points = int(decoded.points_m.shape[0])
        size_m = float(self.values["Size (m)"])
        points = _at_least_one(decoded.points_m)
        node = {
            "precision": wire_precision(points, size_m),  # before points: their dtype
            "points": points,
            "colors": _wire_colors(decoded),
            "point_size": size_m,
            "point_shape": _SHAPES.get(str(self.values["Style"]), "square"),
            "point_shading": "flat",
            "visible": cloud.points > 0,
            **pose_kwargs(T_fixed_cloud),
        }
        handle = self.node(spare[-1]) if spare else None
        if handle is not None:  # the node of a cloud just dropped: its props updated
            cloud.key = spare.pop()
            for name, value in node.items():
                setattr(handle, name, value)
        else:
            cloud.key = f"cloud{self._seq}"
            self.add_node(cloud.key, "point_cloud", **node)

    def _remember_bounds(self, transformer: str, bounds: tuple[float, float] | None) -> None:
        """RViz writes the computed bounds into Min/Max (Intensity or Value) as it goes."""
        if bounds is None:
            return
        if transformer == "Intensity" and self.values["Autocompute Intensity Bounds"]:
            self.values["Min Intensity"], self.values["Max Intensity"] = bounds
        elif transformer == "AxisColor" and self.values["Autocompute Value Bounds"]:
            self.values["Min Value"], self.values["Max Value"] = bounds


def wire_precision(points_m: NDArray[np.float32], size_m: float) -> Literal["float16", "float32"]:
    """float16 (half the bytes to the page) when rounding to it moves no point by more than
    half a point's size: a float16 is within ``|x| / 2048`` of ``x`` (10-bit fraction), so
    when every coordinate is within ``1024 * size_m``; else float32."""
    if points_m.size == 0:
        return "float16"
    largest = max(-float(points_m.min()), float(points_m.max()))
    return "float16" if largest <= 1024.0 * size_m else "float32"


def _wire_colors(decoded: DecodedCloud) -> NDArray[np.uint8] | tuple[int, int, int]:
    """FlatColor as one colour (3 bytes to the page instead of 3 per point), else per point."""
    if decoded.transformer == "FlatColor" and decoded.colors.shape[0] > 0:
        r, g, b = (int(c) for c in decoded.colors[0])
        return (r, g, b)
    return _at_least_one(decoded.colors)


def _at_least_one(array: NDArray[Any]) -> NDArray[Any]:
    """viser needs one point at least: an empty cloud is drawn as one hidden point."""
    return array if array.shape[0] else np.zeros((1, 3), dtype=array.dtype)
