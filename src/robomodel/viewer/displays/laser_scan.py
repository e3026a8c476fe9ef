"""RViz's LaserScan display: a scan's returns as points, placed through TF at the scan's stamp.

Returns outside ``[range_min, range_max]`` or not finite are dropped (laser_geometry's
projection, :func:`scan_points`). Each scan is put in the
fixed frame at its ``header.stamp``; with a Decay Time above 0 the scans of that many seconds
stay drawn where they were, as RViz's point cloud common keeps them. Colour Transformers:
Intensity (RViz's rainbow over the intensities, bounds computed from the data, the lowest
red), AxisColor (the same over z in the fixed frame) and FlatColor (the Color option).
"""

from __future__ import annotations

import collections
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    color_rgb,
    register_display,
    stamp_ns,
)

__all__ = ["LaserScanDisplay", "rainbow", "scan_points"]

_STYLES = ("Points", "Squares", "Flat Squares", "Spheres", "Boxes")
_TRANSFORMERS = ("Intensity", "AxisColor", "FlatColor")
_MAX_SCANS = 1000  # RViz keeps every scan within the decay time; this bounds a long decay


def _rainbow_table() -> NDArray[np.uint8]:
    """Row ``256 * i + q``: the colour of segment ``i`` (1..6 of ``h = 5 v + 1``) at
    ``q = round(255 n)``. Per segment each channel is 0, 255 or ``n`` (getRainbowColor)."""
    q = np.arange(256, dtype=np.uint8)
    zero, full = np.zeros(256, np.uint8), np.full(256, 255, np.uint8)
    segments = [(full, zero, full), (q, zero, full), (zero, q, full), (zero, full, q),
                (q, full, zero), (full, q, zero), (full, q, zero)]  # fmt: skip
    table = np.concatenate([np.stack(rgb, axis=1) for rgb in segments])
    table.setflags(write=False)
    return table


_RAINBOW = _rainbow_table()


def scan_points(scan: Any) -> NDArray[np.float64]:
    """The scan's valid returns as ``(n, 3)`` points in its frame [m]."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    angles = scan.angle_min + scan.angle_increment * np.arange(ranges.size)
    valid = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
    r, a = ranges[valid], angles[valid]
    return np.stack([r * np.cos(a), r * np.sin(a), np.zeros_like(r)], axis=1)


def rainbow(values: NDArray[np.float64]) -> NDArray[np.uint8]:
    """RViz's getRainbowColor (point_cloud_helpers.hpp) for values in [0, 1]: magenta, blue,
    cyan, green, yellow, red; ``(n, 3)`` RGB (NaN: red, as 1). One table lookup per value:
    a 100,000-point cloud is coloured in a few milliseconds."""
    h = np.nan_to_num(np.asarray(values, dtype=np.float64), nan=1.0)  # a copy, then in place
    np.clip(h, 0.0, 1.0, out=h)
    h *= 5.0
    h += 1.0
    i = h.astype(np.intp)  # floor: h >= 1
    h -= i  # f
    n = np.abs((i & 1) - h)  # odd segments 1 - f, even f (f flipped, then n = 1 - f)
    n *= 255.0
    index = np.rint(n).astype(np.intp)
    index += i * 256
    return _RAINBOW[index]


def _normalized(values: NDArray[np.float64]) -> NDArray[np.float64]:
    if values.size == 0:
        return values
    low, high = float(values.min()), float(values.max())
    return (values - low) / (high - low) if high > low else np.zeros_like(values)


@register_display
class LaserScanDisplay(Display):
    """RViz's LaserScan display (``sensor_msgs/LaserScan``)."""

    class_name = "LaserScan"
    message_types = ("sensor_msgs/msg/LaserScan",)
    options = (
        Option("Topic", "", OptionKind.TOPIC, help="LaserScan topic"),
        Option("Queue Size", 10, OptionKind.INT, minimum=0),
        Option("Style", "Flat Squares", OptionKind.CHOICE, choices=_STYLES),
        Option("Size (m)", 0.01, OptionKind.FLOAT, minimum=0.0001, help="Point size [m]"),
        Option("Decay Time", 0.0, OptionKind.FLOAT, minimum=0.0, help="Scans stay so long [s]"),
        Option("Color Transformer", "Intensity", OptionKind.CHOICE, choices=_TRANSFORMERS),
        Option("Color", "255; 255; 255", OptionKind.COLOR, help="FlatColor's colour"),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._pending: collections.deque[Any] = collections.deque(maxlen=_MAX_SCANS)
        # (received [ns], points in the fixed frame, intensities) per scan drawn
        self._kept: collections.deque[tuple[int, NDArray[np.float64], NDArray[np.float64]]] = (
            collections.deque(maxlen=_MAX_SCANS)
        )
        self._fixed = ""
        self._drawn_key: tuple[Any, ...] = ()

    def on_message(self, msg: Any) -> None:
        self._pending.append(msg)

    def reset(self) -> None:
        super().reset()
        self._kept.clear()
        self._drawn_key = ()

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        fixed = self.context.fixed_frame()
        if fixed != self._fixed:  # RViz's fixedFrameChanged: the kept scans go
            self._fixed = fixed
            self.reset()
        problem = self._place_pending(lookup)
        self._decay()
        self._redraw()
        if problem:
            return DisplayStatus.error(problem)
        return self.topic_status() or DisplayStatus.ok(f"{self.messages_received} messages received")  # fmt: skip

    def _place_pending(self, lookup: FrameLookup) -> str:
        problem = ""
        while self._pending:
            scan = self._pending[0]
            placement = lookup(scan.header.frame_id, stamp_ns(scan.header.stamp))
            if placement.T_fixed_frame is None:
                problem = placement.reason  # kept: the transform may come
                if len(self._pending) > 1:  # a newer scan supersedes it
                    self._pending.popleft()
                    continue
                return problem
            self._pending.popleft()
            T = placement.T_fixed_frame
            points = scan_points(scan)
            valid = self._valid_intensities(scan, len(scan.ranges))
            if self.option("Decay Time") <= 0:
                self._kept.clear()
            self._kept.append((self.context.now_ns(), points @ T[:3, :3].T + T[:3, 3], valid))
        return problem

    @staticmethod
    def _valid_intensities(scan: Any, n: int) -> NDArray[np.float64]:
        ranges = np.asarray(scan.ranges, dtype=np.float64)
        valid = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
        intensities = np.asarray(scan.intensities, dtype=np.float64)
        if intensities.size != n:
            intensities = np.zeros(n)
        out: NDArray[np.float64] = intensities[valid]
        return out

    def _decay(self) -> None:
        decay_ns = int(self.option("Decay Time") * 1e9)
        if decay_ns <= 0:
            return
        now = self.context.now_ns()
        while len(self._kept) > 1 and now - self._kept[0][0] > decay_ns:
            self._kept.popleft()

    def _colors(self, points: NDArray[np.float64], intensities: NDArray[np.float64]) -> Any:
        transformer = self.option("Color Transformer")
        if transformer == "FlatColor":
            return color_rgb(self.option("Color"))
        if transformer == "AxisColor":
            return rainbow(1.0 - _normalized(points[:, 2]))  # axis_color_pc_transformer.cpp
        return rainbow(1.0 - _normalized(intensities))  # intensity_pc_transformer.cpp

    def _redraw(self) -> None:
        key = (tuple(id(k[1]) for k in self._kept), self.option("Size (m)"), self.option("Color Transformer"), self.option("Color"), self.option("Style"))  # fmt: skip
        if key == self._drawn_key:
            return
        self._drawn_key = key
        if not self._kept:
            self.remove_node("points")
            return
        points = np.concatenate([k[1] for k in self._kept])
        intensities = np.concatenate([k[2] for k in self._kept])
        if len(points) == 0:
            self.remove_node("points")
            return
        shape = "circle" if self.option("Style") in ("Points", "Spheres") else "square"
        self.add_node(
            "points",
            "point_cloud",
            points=points.astype(np.float32),
            colors=self._colors(points, intensities),
            point_size=float(self.option("Size (m)")),
            point_shape=shape,
            point_shading="flat",
        )
