"""The PointCloud2, Image, Camera and Map displays on a fake scene (no browser): what they
draw, where, and their statuses."""

from __future__ import annotations

import struct

import numpy as np

from robomodel.runtime.msg import get_message_type
from robomodel.viewer.displays import display_class
from tests.viewer.fake_scene import FakeClock, FakeScene, fake_context, lookup_from

PointCloud2 = get_message_type("sensor_msgs/msg/PointCloud2")
PointField = get_message_type("sensor_msgs/msg/PointField")


def three_point_cloud(frame: str = "lidar", stamp_s: int = 0) -> object:
    """Red at (1, 0, 0), green at (0, 1, 0), blue at (0, 0, 1), rgb packed as PCL does."""
    rows = [((1.0, 0.0, 0.0), 0xFF0000), ((0.0, 1.0, 0.0), 0x00FF00), ((0.0, 0.0, 1.0), 0x0000FF)]
    data = b"".join(struct.pack("<fff4xI", *p, c) for p, c in rows)
    msg = PointCloud2(height=1, width=3, point_step=20, row_step=60, data=list(data), is_dense=True)
    msg.fields = [PointField(name=n, offset=o, datatype=d, count=1)
                  for n, o, d in (("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("rgb", 16, 7))]  # fmt: skip
    msg.header.frame_id = frame
    msg.header.stamp.sec = stamp_s
    return msg


def shifted(x: float) -> np.ndarray:
    T = np.eye(4)
    T[0, 3] = x
    return T


def test_point_cloud2_places_points_through_tf_with_rgb_and_status() -> None:
    scene = FakeScene()
    display = display_class("PointCloud2")("cloud", fake_context(scene), {"Topic": "/points"})
    status = display.draw(lookup_from({}))
    assert status.text == "No messages received"
    display.receive(three_point_cloud())
    status = display.draw(lookup_from({}))
    assert status.level.value == "error" and "No transform from [lidar] to [map]" in status.text
    assert not scene.visible("/displays/cloud")
    status = display.draw(lookup_from({"lidar": shifted(2.0)}))
    assert status.text == "Showing [3] points from [1] messages"
    (node,) = scene.visible("/displays/cloud").values()
    assert node.kind == "point_cloud" and node.position == (2.0, 0.0, 0.0)
    np.testing.assert_array_equal(node.kwargs["colors"], [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    np.testing.assert_array_equal(node.kwargs["points"], np.eye(3, dtype=np.float32))
    assert node.kwargs["point_size"] == 0.01
    assert display.option("Color Transformer") == "RGB8"  # chosen for a cloud with rgb


def test_point_cloud2_decay_time_keeps_recent_clouds() -> None:
    scene, clock = FakeScene(), FakeClock()
    values = {"Topic": "/points", "Decay Time": 1.0, "Size (m)": 0.2}
    display = display_class("PointCloud2")("cloud", fake_context(scene, clock=clock), values)
    lookup = lookup_from({"lidar": np.eye(4)})
    for _ in range(3):
        display.receive(three_point_cloud())
        display.draw(lookup)
        clock.ns += 300_000_000
    assert display.draw(lookup).text == "Showing [9] points from [3] messages"
    clock.ns += 200_000_000  # the first is now 1.1 s old
    assert display.draw(lookup).text == "Showing [6] points from [2] messages"
    display.set_option("Decay Time", 0.0)
    display.receive(three_point_cloud())
    assert display.draw(lookup).text == "Showing [3] points from [1] messages"
    assert len(scene.visible("/displays/cloud")) == 1
    assert next(iter(scene.nodes.values())).kwargs["point_size"] == 0.2


def test_point_cloud2_bad_cloud_is_an_error_status_and_config_transformer_kept() -> None:
    scene = FakeScene()
    display = display_class("PointCloud2")("c", fake_context(scene), {"Topic": "/p", "Color Transformer": "Intensity"})  # fmt: skip
    bad = three_point_cloud(frame="map")
    bad.width = 4
    display.receive(bad)
    status = display.draw(lookup_from({"map": np.eye(4)}))
    assert status.level.value == "error" and "Data size (60 bytes)" in status.text
    display.receive(three_point_cloud(frame="map"))
    assert display.draw(lookup_from({"map": np.eye(4)})).text == "Showing [3] points from [1] messages"
    assert display.option("Color Transformer") == "Intensity"  # the config's choice kept
