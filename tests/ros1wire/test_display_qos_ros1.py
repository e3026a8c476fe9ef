"""Displays on ROS 1 (Debian's roscore and rostopic): the Queue Size is the subscriber's queue
size, and a latched topic (``rostopic pub -l``) reaches a display whatever its Durability
Policy, as it reaches RViz 1, which has none: latching is the publisher's choice."""

from __future__ import annotations

import os

from robomodel.runtime.context import Context
from robomodel.tf.buffer import BufferCore
from robomodel.viewer.displays.manager import DisplayManager
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled
from tests.viewer.fake_scene import FakeScene, fake_context


def test_a_volatile_display_hears_a_latched_ros_1_topic_with_its_queue_size(ros1: Ros1) -> None:
    ros1.roscore()
    marker = ("{header: {frame_id: base_link}, type: 1, scale: {x: 1, y: 1, z: 1}, "
              "color: {a: 1}, pose: {orientation: {w: 1}}}")  # fmt: skip
    ros1.start(["/usr/bin/rostopic", "pub", "-l", "/latched", "visualization_msgs/Marker", marker])
    ros1.until(lambda: "/latched" in ros1.names("topics"), "the publisher")
    os.environ["ROS_IP"] = "127.0.0.1"
    try:
        _hear_it(ros1)
    finally:
        os.environ.pop("ROS_IP", None)


def _hear_it(ros1: Ros1) -> None:
    with Context("ros1", master=ros1.uri) as ctx:
        manager = DisplayManager(fake_context(FakeScene(), fixed="base_link"), ctx.create_node("viewer"), BufferCore())  # fmt: skip
        display = manager.add("Marker", values={"Topic": "/latched", "Queue Size": 2})
        assert display.option("Topic/Durability Policy") == "Volatile"
        manager.update()
        ctx.spin(duration_s=scaled(60), until=lambda: display.messages_received >= 1)
        manager.update()
        assert display.messages_received == 1 and display.status.text == "1 messages received"
        ((_spec, live),) = manager._subscribed.values()
        assert live.subscription.qos.depth == 2
        (queue,) = ctx.transport._nodes["/viewer"].subscriptions["/latched"]
        assert queue._pending.maxlen == 2  # the TCPROS subscriber's queue
