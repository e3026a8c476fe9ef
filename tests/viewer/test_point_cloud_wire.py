"""What the PointCloud2 display sends to the page: float16 positions only where rounding moves
no point by more than half its size, one colour for FlatColor, and a cloud drawn when it
arrives (at most at RViz's 30 fps) rather than at the next 10 Hz draw."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.point_cloud2 import wire_precision
from tests.viewer.fake_scene import FakeClock, FakeScene, fake_context, lookup_from
from tests.viewer.test_sensor_displays import three_point_cloud


@pytest.mark.parametrize("size_m", [0.001, 0.01, 0.05])
@pytest.mark.parametrize("extent_m", [0.5, 5.0, 10.0, 11.0, 50.0, 5000.0, 1e5])
def test_float16_only_where_it_moves_no_point_by_half_its_size(size_m: float, extent_m: float) -> None:  # fmt: skip
    points = np.random.default_rng(1).uniform(-extent_m, extent_m, (5000, 3)).astype(np.float32)
    if wire_precision(points, size_m) == "float16":
        moved = np.abs(points.astype(np.float16).astype(np.float64) - points)
        assert moved.max() <= size_m / 2
    else:  # float16 chosen only when it may move a point more than half its size
        assert float(np.abs(points).max()) > 1024 * size_m


def test_flat_color_is_sent_as_one_colour() -> None:
    scene = FakeScene()
    values = {"Topic": "/p", "Color Transformer": "FlatColor", "Color": "10; 20; 30"}
    display = display_class("PointCloud2")("c", fake_context(scene), values)
    display.receive(three_point_cloud())
    display.draw(lookup_from({"lidar": np.eye(4)}))
    (node,) = scene.visible().values()
    assert node.kwargs["colors"] == (10, 20, 30) and node.kwargs["points"].shape == (3, 3)


def cloud_at(x: float) -> object:
    """The three-point cloud moved ``x`` along its x (the points differ: a new cloud)."""
    msg = three_point_cloud()
    data = bytearray(bytes(msg.data))
    for k in range(3):
        struct.pack_into("<f", data, 20 * k, struct.unpack_from("<f", data, 20 * k)[0] + x)
    msg.data = bytes(data)
    return msg


def _xs(scene: FakeScene) -> list[float]:
    return [float(n.kwargs["points"][:, 0].min()) for n in scene.visible().values()]


def test_a_cloud_is_drawn_when_it_arrives_at_most_at_30_fps_in_the_node_it_replaces() -> None:
    scene, clock = FakeScene(), FakeClock()
    display = display_class("PointCloud2")("c", fake_context(scene, clock=clock), {"Topic": "/p"})
    display.receive(cloud_at(0.0))
    assert not scene.nodes  # before the first draw there is no TF lookup to place it with
    lookup = lookup_from({"lidar": np.eye(4)})
    display.draw(lookup)
    (node,) = scene.nodes.values()
    clock.ns += 100_000_000
    display.receive(cloud_at(10.0))  # 100 ms later: drawn at once, in the same node
    assert _xs(scene) == [10.0] and list(scene.nodes.values()) == [node]
    clock.ns += 10_000_000
    display.receive(cloud_at(20.0))  # 10 ms later: waits for the next draw
    assert _xs(scene) == [10.0]
    assert display.draw(lookup).text == "Showing [3] points from [1] messages"
    assert _xs(scene) == [20.0] and list(scene.nodes.values()) == [node]
    display.set_option("Decay Time", 1.0)  # two clouds kept: two nodes
    clock.ns += 100_000_000
    display.receive(cloud_at(30.0))
    assert sorted(_xs(scene)) == [20.0, 30.0]
