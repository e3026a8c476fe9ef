"""LaserScan and Axes displays without a browser (a fake scene): points through TF at the
scan's stamp, decay, colour transformers, and RViz's status for a frame without transform."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robomodel.runtime.msg import LaserScan
from robomodel.viewer.displays import StatusLevel, display_class
from robomodel.viewer.displays.laser_scan import rainbow
from tests.viewer.fake_scene import FakeClock, FakeScene, fake_context, lookup_from


def _scan(ranges: list[float], intensities: list[float] | None = None) -> LaserScan:
    scan = LaserScan()
    scan.header.frame_id = "laser"
    scan.angle_min, scan.angle_increment = 0.0, math.pi / 2
    scan.range_min, scan.range_max = 0.1, 10.0
    scan.ranges = ranges
    scan.intensities = intensities or []
    return scan


def _laser_at(xyz: tuple[float, float, float]) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = xyz
    return T


def test_scan_points_are_drawn_in_the_fixed_frame_without_invalid_returns() -> None:
    scene = FakeScene()
    display = display_class("LaserScan")("Scan", fake_context(scene), {"Topic": "/scan", "Color Transformer": "FlatColor", "Color": "0; 255; 0"})  # fmt: skip
    display.receive(_scan([1.0, float("inf"), 0.05, 2.0]))
    status = display.draw(lookup_from({"laser": _laser_at((0.0, 0.0, 0.5))}))
    assert status.level is StatusLevel.OK
    node = scene.nodes["/displays/Scan/points"]
    np.testing.assert_allclose(node.kwargs["points"], [[1.0, 0.0, 0.5], [0.0, -2.0, 0.5]], atol=1e-6)  # fmt: skip
    assert node.kwargs["colors"] == (0, 255, 0) and node.kwargs["point_size"] == 0.01


def test_decay_time_keeps_older_scans_where_they_were() -> None:
    scene, clock = FakeScene(), FakeClock()
    display = display_class("LaserScan")("Scan", fake_context(scene, clock=clock), {"Topic": "/scan", "Decay Time": 1.0})  # fmt: skip
    display.receive(_scan([1.0]))
    display.draw(lookup_from({"laser": _laser_at((0, 0, 0))}))
    clock.ns += 500_000_000
    display.receive(_scan([1.0]))
    display.draw(lookup_from({"laser": _laser_at((0, 3, 0))}))  # the laser moved
    np.testing.assert_allclose(scene.nodes["/displays/Scan/points"].kwargs["points"], [[1, 0, 0], [1, 3, 0]])  # fmt: skip
    clock.ns += 700_000_000
    display.draw(lookup_from({"laser": _laser_at((0, 3, 0))}))
    np.testing.assert_allclose(scene.nodes["/displays/Scan/points"].kwargs["points"], [[1, 3, 0]])  # fmt: skip


def test_intensity_colours_are_rviz_s_rainbow() -> None:
    scene = FakeScene()
    display = display_class("LaserScan")("Scan", fake_context(scene), {"Topic": "/scan"})
    display.receive(_scan([1.0, 1.0, 1.0], [0.0, 50.0, 100.0]))
    display.draw(lookup_from({"laser": np.eye(4)}))
    colors = scene.nodes["/displays/Scan/points"].kwargs["colors"]
    # intensity_pc_transformer.cpp: value = 1 - normalised intensity; the lowest red
    assert colors.tolist() == [[255, 0, 0], [0, 255, 128], [255, 0, 255]]
    assert rainbow(np.array([0.25])).tolist() == [[0, 64, 255]]


def test_a_scan_without_transform_is_an_error_status() -> None:
    display = display_class("LaserScan")("Scan", fake_context(FakeScene()), {"Topic": "/scan"})
    display.receive(_scan([1.0]))
    status = display.draw(lookup_from({}))
    assert (status.level, status.text) == (StatusLevel.ERROR, "No transform from [laser] to [map]")  # fmt: skip


@pytest.mark.parametrize("frame", ["tool", "<Fixed Frame>"])
def test_axes_show_their_frame(frame: str) -> None:
    scene = FakeScene()
    display = display_class("rviz_default_plugins/Axes")("Axes", fake_context(scene), {"Reference Frame": frame, "Length": 0.3})  # fmt: skip
    status = display.draw(lookup_from({"tool": _laser_at((1, 2, 3)), "map": np.eye(4)}))
    assert status.level is StatusLevel.OK
    node = scene.nodes["/displays/Axes/axes"]
    assert node.kwargs["axes_length"] == 0.3
    assert tuple(node.position) == ((1, 2, 3) if frame == "tool" else (0, 0, 0))
    missing = display_class("Axes")("A2", fake_context(scene), {"Reference Frame": "nowhere"})
    assert missing.draw(lookup_from({})).text == "No transform from [nowhere] to [map]"
