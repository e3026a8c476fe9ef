"""Scene overlays as RViz's LaserScan and Odometry displays: scan points and the driven path.

A LaserScan is turned into points in its ``header.frame_id`` (ranges outside
``[range_min, range_max]`` or not finite are dropped, as RViz's laser_geometry projection does)
and drawn where that frame is in the fixed frame. Odometry poses are kept as a path in their
``header.frame_id`` (a point every 1 cm, at most 5000, oldest dropped), drawn as a polyline:
the robot's odometry in blue and, under ``robomodel sim``, the simulator's ground truth
(Gazebo's p3d, ``.../ground_truth/odom``) in orange, so that odometry drift is visible.
Each follows the first topic of its kind the graph shows unless another is chosen.
"""

from __future__ import annotations

import collections
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.runtime.msg import LaserScan, Message, Odometry
from robomodel.runtime.node import Subscription
from robomodel.tf.exceptions import TransformError
from robomodel.viewer.tools.base import ToolContext

__all__ = ["OverlayTool", "path_segments", "scan_points"]

_AUTO = "(first found)"
_PATH_MAX = 5000
_PATH_STEP_M = 0.01


def scan_points(scan: LaserScan) -> NDArray[np.float64]:
    """The scan's valid returns as ``(n, 3)`` points in its frame [m]."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    angles = scan.angle_min + scan.angle_increment * np.arange(ranges.size)
    valid = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
    r, a = ranges[valid], angles[valid]
    return np.stack([r * np.cos(a), r * np.sin(a), np.zeros_like(r)], axis=1)


def path_segments(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """A polyline ``(n, 3)`` as the ``(n - 1, 2, 3)`` segments viser draws."""
    return np.stack([points[:-1], points[1:]], axis=1)


def _transform(T: NDArray[np.float64], points: NDArray[np.float64]) -> NDArray[np.float64]:
    return points @ T[:3, :3].T + T[:3, 3]


class _Follower:
    """One overlay's topic choice and subscription."""

    def __init__(self, tools: ToolContext, label: str, type_name: str, default_on: bool) -> None:
        gui = tools.server.gui
        self.tools = tools
        self.type_name = type_name
        self.enabled = gui.add_checkbox(label, default_on)
        self.dropdown = gui.add_dropdown(f"{label} topic", (_AUTO,), initial_value=_AUTO)
        self.subscription: Subscription[Any] | None = None
        self.topic = ""

    def wanted(self) -> str:
        choice = str(self.dropdown.value)
        if choice != _AUTO:
            return choice
        found = [t for t in self.tools.topics_of_type(self.type_name) if self.accepts(t)]
        # A simulator's ground truth (in a world frame TF may not have) only when alone.
        found.sort(key=lambda t: "ground_truth" in t)
        return found[0] if found else ""

    def accepts(self, topic: str) -> bool:
        """Whether "first found" may pick ``topic``."""
        return True

    def update_options(self) -> None:
        options = (_AUTO, *self.tools.topics_of_type(self.type_name))
        if tuple(self.dropdown.options) != options:
            current = self.dropdown.value
            self.dropdown.options = options
            self.dropdown.value = current if current in options else _AUTO


class _GroundTruthFollower(_Follower):
    def accepts(self, topic: str) -> bool:
        return "ground_truth" in topic


class _PathOverlay:
    """A path of Odometry positions in their frame, drawn as a polyline in the fixed frame."""

    def __init__(self, scene: Any, follower: _Follower, node_name: str, rgb: tuple[int, int, int]) -> None:  # fmt: skip
        self.scene = scene
        self.follower = follower
        self.node_name = node_name
        self.rgb = rgb
        self.points: collections.deque[tuple[float, float, float]] = collections.deque(
            maxlen=_PATH_MAX
        )
        self.frame = ""
        self.node: Any = None
        self._key: tuple[Any, ...] = ()

    def on_odometry(self, msg: Odometry) -> None:
        p = msg.pose.pose.position
        if msg.header.frame_id != self.frame:
            self.points.clear()
            self.frame = msg.header.frame_id
        if self.points and math.dist(self.points[-1], (p.x, p.y, p.z)) < _PATH_STEP_M:
            return
        self.points.append((p.x, p.y, p.z))

    def draw(self, lookup: Any) -> None:
        T = lookup(self.frame) if self.points else None
        if T is None or len(self.points) < 2 or not self.follower.enabled.value:
            if self.node is not None:
                self.node.remove()
                self.node = None
            return
        key = (len(self.points), self.points[-1], self.points[0], T.tobytes())
        if key == self._key and self.node is not None:
            return
        self._key = key
        points = _transform(T, np.asarray(self.points, dtype=np.float64))
        if self.node is not None:
            self.node.remove()
        self.node = self.scene.add_line_segments(
            self.node_name,
            points=path_segments(points),
            colors=self.rgb,
            thickness=3.0,
            thickness_units="screen",
        )


class OverlayTool:
    """The "Overlays" folder and the scene nodes it draws (below ``/overlays``)."""

    def __init__(self, tools: ToolContext) -> None:
        self.tools = tools
        self.scene = tools.server.scene
        gui = tools.server.gui
        self.scan = _Follower(tools, "LaserScan", LaserScan.__typename__, True)
        self.point_size = gui.add_number("Scan point size [m]", 0.02, min=0.001, step=0.005)
        self.odom = _Follower(tools, "Odometry", Odometry.__typename__, True)
        self.truth = _GroundTruthFollower(tools, "Ground truth", Odometry.__typename__, True)
        clear = gui.add_button("Clear paths")
        self.last_scan: LaserScan | None = None
        self.odom_path = _PathOverlay(self.scene, self.odom, "/overlays/odometry_path", (40, 200, 255))  # fmt: skip
        self.truth_path = _PathOverlay(self.scene, self.truth, "/overlays/ground_truth_path", (255, 150, 0))  # fmt: skip
        self.scans_drawn = 0
        self._scan_node: Any = None
        self._scan_key: tuple[Any, ...] = ()

        def clear_paths() -> None:
            self.odom_path.points.clear()
            self.truth_path.points.clear()

        clear.on_click(lambda _e: tools.post(clear_paths))
        tools.post(lambda: tools.node.create_timer(0.1, self.refresh))

    # -- subscriptions (loop thread) ----------------------------------------------------------
    def _follow(self, follower: _Follower, msg_type: type[Message], callback: Any) -> None:
        topic = follower.wanted() if follower.enabled.value else ""
        if topic == follower.topic:
            return
        if follower.subscription is not None:
            follower.subscription.destroy()
            follower.subscription = None
        follower.topic = topic
        if topic:
            follower.subscription = self.tools.node.create_subscription(
                msg_type, topic, callback, 10
            )

    def _on_scan(self, msg: LaserScan) -> None:
        self.last_scan = msg

    # -- drawing (loop thread, 10 Hz) ---------------------------------------------------------
    def refresh(self) -> None:
        self.scan.update_options()
        self.odom.update_options()
        self.truth.update_options()
        self._follow(self.scan, LaserScan, self._on_scan)
        self._follow(self.odom, Odometry, self.odom_path.on_odometry)
        self._follow(self.truth, Odometry, self.truth_path.on_odometry)
        self._draw_scan()
        self.odom_path.draw(self._lookup)
        self.truth_path.draw(self._lookup)

    def _lookup(self, frame: str) -> NDArray[np.float64] | None:
        fixed = self.tools.fixed_frame()
        if not frame or frame == fixed:
            return np.eye(4)
        try:
            matrix: NDArray[np.float64] = self.tools.buffer.lookup_transform(fixed, frame).matrix()
        except TransformError:
            return None
        return matrix

    def _draw_scan(self) -> None:
        scan = self.last_scan
        T = self._lookup(scan.header.frame_id) if scan is not None else None
        if scan is None or T is None or not self.scan.enabled.value:
            if self._scan_node is not None:
                self._scan_node.visible = False
            return
        key = (id(scan), T.tobytes(), float(self.point_size.value))
        if key == self._scan_key and self._scan_node is not None:
            self._scan_node.visible = True
            return
        self._scan_key = key
        points = _transform(T, scan_points(scan))
        if points.shape[0] == 0:
            points = np.zeros((1, 3))
        if self._scan_node is not None:
            self._scan_node.remove()
        self._scan_node = self.scene.add_point_cloud(
            "/overlays/scan",
            points=points.astype(np.float32),
            colors=(255, 40, 40),
            point_size=float(self.point_size.value),
            point_shape="circle",
            point_shading="flat",
        )
        self.scans_drawn += 1
