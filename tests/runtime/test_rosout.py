"""Every node publishes its log lines on /rosout (rcl_interfaces/msg/Log off ROS 1,
rcl's /rosout QoS: a late subscriber still gets them), and a launch's lines for a node go out as
that node's."""

from __future__ import annotations

import logging

from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.types.rcl_interfaces import Log
from robomodel.runtime.qos import Durability
from robomodel.runtime.rosout import ROSOUT_QOS, publish_line


def test_a_nodes_warning_reaches_a_late_subscriber_on_rosout() -> None:
    ctx = Context(clock=ManualClock())
    talker = ctx.create_node("talker", "/ns")
    talker.logger.warning("gain %s is high", 3)
    talker.logger.debug("not let through by logging: not published")
    got: list[Log] = []
    ctx.create_node("listener").create_subscription(Log, "/rosout", got.append, ROSOUT_QOS)
    ctx.spin_once(0.0)
    assert [(m.name, m.level, m.msg) for m in got] == [("/ns/talker", 30, "gain 3 is high")]
    assert got[0].function == "test_a_nodes_warning_reaches_a_late_subscriber_on_rosout"
    assert ROSOUT_QOS.durability is Durability.TRANSIENT_LOCAL and ROSOUT_QOS.depth == 1000


def test_launch_lines_go_out_as_the_nodes_and_rosout_can_be_disabled() -> None:
    ctx = Context(clock=ManualClock())
    got: list[Log] = []
    ctx.create_node("listener").create_subscription(Log, "/rosout", got.append, ROSOUT_QOS)
    ctx.create_node("spawner")
    quiet = ctx.create_node("quiet", enable_rosout=False)
    quiet.logger.error("never on /rosout")
    publish_line(ctx, "/spawner", "Loaded controllers: a, b")
    publish_line(ctx, "/nobody", "no node of that name: nothing published")
    ctx.spin_once(0.0)
    assert [(m.name, m.level, m.msg) for m in got] == [
        ("/spawner", logging.INFO, "Loaded controllers: a, b")
    ]
    assert "/rosout" not in {p.topic for p in quiet._publishers}
