"""Displays subscribe with their RViz 2 QoS: Depth (Queue Size), History, Reliability and
Durability Policy, read from and written to ``Topic`` in ROS 2 configs (none in ROS 1's), and
applied on the Zenoh bus (rmw_zenoh's tokens show them; a latched message reaches only a
Transient Local display; Keep Last drops all but the newest ``depth``, Keep All none)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from types import MappingProxyType

import pytest

from robomodel.runtime.context import Context
from robomodel.runtime.msg import Bool, get_message_type
from robomodel.runtime.qos import Durability, History, QoSProfile, Reliability, latched
from robomodel.tf.buffer import BufferCore
from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.manager import DisplayManager
from robomodel.viewer.displays.rviz_io import display_entry, display_values
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import unique_domain
from tests.timing import wait_until
from tests.viewer.fake_scene import FakeScene, fake_context

Marker = get_message_type("visualization_msgs/msg/Marker")

CHOSEN = {
    "Topic": "/scan",
    "Queue Size": 3,
    "Topic/Reliability Policy": "Best Effort",
    "Topic/Durability Policy": "Transient Local",
    "Topic/History Policy": "Keep All",
}


def test_every_topic_display_has_rviz_2_s_policies_with_its_defaults() -> None:
    scan = display_class("LaserScan")("scan", fake_context(FakeScene()), {"Topic": "/scan"})
    assert scan.subscriptions()[0].qos_profile == QoSProfile(
        10
    )  # RViz 2: keep last, reliable, volatile
    assert scan.option("Topic/Reliability Policy") == "Reliable"
    chosen = display_class("LaserScan")("scan", fake_context(FakeScene()), CHOSEN)
    assert chosen.subscriptions()[0].qos_profile == QoSProfile(
        3, Durability.TRANSIENT_LOCAL, Reliability.BEST_EFFORT, History.KEEP_ALL
    )
    # "System Default" is rmw's default profile (QosProfileProperty::updateQosProfile)
    chosen.set_option("Topic/Reliability Policy", "System Default")
    assert chosen.subscriptions()[0].qos_profile.reliability is Reliability.RELIABLE
    # the Map starts Transient Local (map_server's latched map), a choice it keeps in configs
    grid = display_class("Map")("map", fake_context(FakeScene()), {"Topic": "/map"})
    assert grid.subscriptions()[0].qos_profile == QoSProfile(5, Durability.TRANSIENT_LOCAL)
    grid.set_option("Topic/Durability Policy", "Volatile")
    assert grid.subscriptions()[0].qos_profile == QoSProfile(5)


def test_policies_are_read_from_and_written_to_ros_2_topic_maps_only() -> None:
    cls = display_class("LaserScan")
    topic = {"Value": "/scan", "Depth": 3, "Reliability Policy": "Best Effort",
             "Durability Policy": "Transient Local", "History Policy": "Keep All"}  # fmt: skip
    values, skipped = display_values(cls, {"Topic": topic}, RvizDialect.ROS2)
    assert skipped == [] and values == CHOSEN
    display = cls("scan", fake_context(FakeScene()), values)
    written = display_entry(display, RvizDialect.ROS2).settings["Topic"]
    assert dict(written) == topic
    # ROS 1: Topic is a name and Queue Size its own key; RViz 1 has no policies
    ros1 = display_entry(display, RvizDialect.ROS1).settings
    assert ros1["Topic"] == "/scan" and ros1["Queue Size"] == 3
    assert not any("Policy" in key for key in ros1)
    values, _ = display_values(cls, {"Topic": "/scan", "Queue Size": 3}, RvizDialect.ROS1)
    assert values == {"Topic": "/scan", "Queue Size": 3}
    # an unknown policy keeps the default and is named, as for any option RViz would not take
    values, skipped = display_values(cls, {"Topic": {**topic, "History Policy": "Keep Some"}},
                                     RvizDialect.ROS2)  # fmt: skip
    assert "Topic/History Policy" not in values and "Keep Some" in skipped[0]


def test_a_changed_policy_of_a_read_display_is_written_into_its_topic_map() -> None:
    cls = display_class("LaserScan")
    topic = MappingProxyType({"Value": "/scan", "Depth": 5, "Reliability Policy": "Reliable"})
    settings = MappingProxyType({"Topic": topic})
    display = cls("scan", fake_context(FakeScene()), display_values(cls, settings, RvizDialect.ROS2)[0])  # fmt: skip
    from robomodel.viewer.rviz_model import RvizDisplay

    base = RvizDisplay("rviz_default_plugins/LaserScan", "scan", True, settings)
    assert display_entry(display, RvizDialect.ROS2, base).settings == settings  # unchanged
    display.set_option("Topic/Reliability Policy", "Best Effort")
    written = display_entry(display, RvizDialect.ROS2, base).settings["Topic"]
    assert dict(written) == {"Value": "/scan", "Depth": 5, "Reliability Policy": "Best Effort"}


def test_a_changed_queue_size_of_a_read_display_is_written_as_its_topic_s_depth() -> None:
    """RViz 2 keeps Queue Size as the topic map's ``Depth``: Save Config writes the new one,
    whether the topic changed too or not, and keeps the map's other keys."""
    from robomodel.viewer.rviz_model import RvizDisplay

    cls = display_class("LaserScan")
    topic = MappingProxyType({"Value": "/scan", "Depth": 5, "Reliability Policy": "Reliable"})
    settings = MappingProxyType({"Topic": topic})
    base = RvizDisplay("rviz_default_plugins/LaserScan", "scan", True, settings)
    display = cls("scan", fake_context(FakeScene()), display_values(cls, settings, RvizDialect.ROS2)[0])  # fmt: skip
    display.set_option("Queue Size", 20)
    written = display_entry(display, RvizDialect.ROS2, base).settings
    assert dict(written["Topic"]) == {"Value": "/scan", "Depth": 20, "Reliability Policy": "Reliable"}  # fmt: skip
    assert "Queue Size" not in written  # RViz 2 has no key of that name
    display.set_option("Topic", "/scan_front")
    written = display_entry(display, RvizDialect.ROS2, base).settings
    assert dict(written["Topic"]) == {"Value": "/scan_front", "Depth": 20, "Reliability Policy": "Reliable"}  # fmt: skip


@pytest.fixture
def zenoh_pair() -> Iterator[tuple[Context, Context]]:
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as viewer, Context("zenoh", domain_id=domain) as peer:
        yield viewer, peer


def _until(check: Callable[[], bool], what: str, *contexts: Context) -> None:
    """``wait_until`` that spins ``contexts`` (their callbacks run here) between checks."""

    def spun() -> bool:
        if check():
            return True
        for context in contexts:
            context.spin_once(0.02)
        return False

    wait_until(spun, 20, what=what, interval_s=0)


def _delivered_so_far(viewer: Context, peer: Context) -> None:
    """Until what ``peer`` published before this call has reached ``viewer``'s session.

    A sample published just before a subscription is declared can still be on its way (a new
    peer link forwards samples before the other side's subscriptions are known), and then it
    reaches that subscription, volatile or not, as with rmw_zenoh. A later sample of the same
    reliability and priority travels the same link behind it: once one is received, the
    earlier ones have been routed."""
    heard: list[object] = []
    viewer.create_node("flush").create_subscription(Bool, "/flush", heard.append, 10)
    flush = peer.create_node("flush").create_publisher(Bool, "/flush", 10)

    def through() -> bool:
        flush.publish(Bool(data=True))
        viewer.spin_once(0.05)
        return bool(heard)

    _until(through, "a sample sent after the latched one", viewer)


def _cube(marker_id: int) -> object:
    m = Marker()
    m.header.frame_id, m.type, m.id = "base_link", 1, marker_id
    m.scale.x = m.scale.y = m.scale.z = m.color.a = 1.0
    return m


def test_the_zenoh_bus_sees_and_applies_the_display_s_qos(
    zenoh_pair: tuple[Context, Context],
) -> None:
    viewer, peer = zenoh_pair
    manager = DisplayManager(fake_context(FakeScene(), fixed="base_link"), viewer.create_node("viewer"), BufferCore())  # fmt: skip
    publisher = peer.create_node("pub").create_publisher(Marker, "/latched", latched(1))
    publisher.publish(_cube(7))  # before anyone subscribes
    _delivered_so_far(viewer, peer)
    volatile = manager.add("Marker", "volatile", {"Topic": "/latched"})
    durable = manager.add("Marker", "durable", {"Topic": "/latched", "Queue Size": 2,
                                                "Topic/Durability Policy": "Transient Local",
                                                "Topic/Reliability Policy": "Best Effort"})  # fmt: skip
    manager.update()

    def subscribers() -> list[QoSProfile]:
        info = peer.graph(timeout_s=1.0).topics.get("/latched")  # one probe: _until retries it
        return sorted((e.qos for e in info.subscribers), key=lambda q: q.depth) if info else []

    _until(lambda: len(subscribers()) == 2, "the two subscriptions in the graph", viewer)
    assert subscribers() == [
        QoSProfile(2, Durability.TRANSIENT_LOCAL, Reliability.BEST_EFFORT),
        QoSProfile(100),  # the Marker's Queue Size, RViz 2's policies
    ]
    heard: list[int] = []  # the markers the volatile display was given
    on_message = volatile.on_message

    def record(msg: Marker) -> None:
        heard.append(msg.id)
        on_message(msg)

    volatile.on_message = record  # type: ignore[method-assign]
    _until(lambda: durable.messages_received == 1, "the latched marker", viewer)

    def new_marker_on_both() -> bool:
        # Seeing the subscription's token does not mean the publisher's session has learnt of
        # it yet (a quiet full run lost a single publish): publish until both have one.
        if 8 not in heard or durable.messages_received < 2:
            publisher.publish(_cube(8))
        viewer.spin_once(0.1)
        return 8 in heard and durable.messages_received >= 2

    _until(new_marker_on_both, "the new marker on both", viewer)
    assert 7 not in heard  # the volatile display never got the latched one


@pytest.mark.parametrize(("history", "expected"), [("Keep Last", 3), ("Keep All", 12)])
def test_keep_last_keeps_the_newest_depth_messages_and_keep_all_every_one(
    zenoh_pair: tuple[Context, Context], history: str, expected: int
) -> None:
    """Twelve markers arrive while the viewer's loop is busy: the display sees the newest
    three with Keep Last and depth 3, all twelve with Keep All (rmw_zenoh's queue)."""
    viewer, peer = zenoh_pair
    manager = DisplayManager(fake_context(FakeScene(), fixed="base_link"), viewer.create_node("viewer"), BufferCore())  # fmt: skip
    display = manager.add("Marker", values={"Topic": "/m", "Queue Size": 3,
                                            "Topic/History Policy": history})  # fmt: skip
    seen: list[int] = []
    display.on_message = lambda msg: seen.append(msg.id)  # type: ignore[method-assign]
    manager.update()
    publisher = peer.create_node("pub").create_publisher(Marker, "/m", 20)

    def handshake() -> bool:  # until the subscription hears the publisher
        publisher.publish(_cube(0))
        viewer.spin_once(0.1)
        return bool(seen)

    _until(handshake, "the first marker", viewer)
    # the handshake may have sent more markers than the one seen, still on their way: one sent
    # after them, once received, has come behind them all (one publisher, one link, in order)
    publisher.publish(_cube(99))
    _until(lambda: 99 in seen, "the marker sent after the handshake", viewer)
    (live,) = [sub for _spec, sub in manager._subscribed.values()]
    handle = live.subscription._handle
    _until(lambda: not handle._pending, "the handshake's markers", viewer)
    del seen[:]
    dropped = handle.dropped
    for marker_id in range(1, 13):
        publisher.publish(_cube(marker_id))
    # not spinning: the samples wait in the subscription's queue (or were dropped from it)
    _until(lambda: handle.dropped - dropped + len(handle._pending) >= 12, "the twelve samples")
    assert handle.dropped - dropped + len(handle._pending) == 12
    _until(lambda: seen[-1:] == [12], "the newest marker", viewer)
    assert seen == list(range(13 - expected, 13))


def test_option_values_read_per_dialect_and_refused_in_one_line() -> None:
    robot = display_class("RobotModel")
    # RViz 1 has no Description File: a ROS 1 config's key of that name is not read
    assert display_values(robot, {"Description File": "/r.urdf"}, RvizDialect.ROS1) == ({}, [])
    assert display_values(robot, {"Description File": "/r.urdf"}, RvizDialect.ROS2) == (
        {"Description File": "/r.urdf"}, [],
    )  # fmt: skip
    # a topic map's Depth is a Queue Size only for displays that have one
    values, skipped = display_values(
        robot, {"Description Topic": {"Value": "/robot_description", "Depth": 5}},
        RvizDialect.ROS2,
    )  # fmt: skip
    assert values == {"Description Topic": "/robot_description"} and skipped == []
    values, skipped = display_values(
        display_class("LaserScan"), {"Topic": {"Value": "/s", "Depth": "many"}}, RvizDialect.ROS2
    )
    assert values == {"Topic": "/s"}
    assert skipped == ["option 'Queue Size' takes a int value, not 'many'"]


def test_new_displays_are_written_with_each_dialect_s_class_and_nested_keys() -> None:
    wrench = display_class("Wrench")("w", fake_context(FakeScene()), {"Topic": "/wrench"})
    assert display_entry(wrench, RvizDialect.ROS1).class_name == "rviz/WrenchStamped"
    assert display_entry(wrench, RvizDialect.ROS2).class_name == "rviz_default_plugins/Wrench"
    pose = display_class("PoseWithCovariance")("p", fake_context(FakeScene()), {})
    for dialect in (RvizDialect.ROS1, RvizDialect.ROS2):
        covariance = display_entry(pose, dialect).settings["Covariance"]
        assert covariance["Value"] is True
        assert covariance["Position"]["Color"] == "204; 51; 204"
        assert covariance["Position"]["Alpha"] == 0.3


def test_a_read_display_is_written_back_as_read_and_changed_by_its_dialect_s_keys() -> None:
    from robomodel.viewer.rviz_model import RvizDisplay

    # a ROS 2 topic map without a Depth stays without one when nothing changed
    cls = display_class("LaserScan")
    settings = MappingProxyType({"Topic": MappingProxyType({"Value": "/scan"})})
    base = RvizDisplay("rviz_default_plugins/LaserScan", "scan", True, settings)
    display = cls("scan", fake_context(FakeScene()), display_values(cls, settings, RvizDialect.ROS2)[0])  # fmt: skip
    assert display_entry(display, RvizDialect.ROS2, base).settings == settings
    # RViz 1's Marker Topic, set back to the default, is written under RViz 1's key
    marker = display_class("Marker")
    ros1 = MappingProxyType({"Marker Topic": "/my_markers"})
    base = RvizDisplay("rviz/Marker", "m", True, ros1)
    shown = marker("m", fake_context(FakeScene()), display_values(marker, ros1, RvizDialect.ROS1)[0])  # fmt: skip
    assert shown.option("Topic") == "/my_markers"
    shown.set_option("Topic", "/visualization_marker")
    written = display_entry(shown, RvizDialect.ROS1, base).settings
    assert written["Marker Topic"] == "/visualization_marker" and "Topic" not in written
