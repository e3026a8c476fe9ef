"""QoS event callbacks (``rclpy.event_handler``) and QoS overriding parameters
(``rclpy.qos_overriding_options``), written as demo_nodes_py's matched_event_detect and
quality_of_service_demo_py's nodes use them, on the in-process bus.

Message modules are imported in the tests, not at collection: the first import of a message
module decides its flavour for the process, and the rospy tests want genpy's."""

from __future__ import annotations

import time
from typing import Any

import pytest
import rclpy
from rclpy.duration import Duration
from rclpy.event_handler import (
    PublisherEventCallbacks,
    QoSOfferedDeadlineMissedInfo,
    QoSPublisherEventType,
    QoSPublisherMatchedInfo,
    QoSSubscriptionMatchedInfo,
    SubscriptionEventCallbacks,
    UnsupportedEventTypeError,
)
from rclpy.exceptions import InvalidHandle, ParameterImmutableException
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import InvalidQosOverridesError, QoSOverridingOptions

from tests.timing import scaled


class MatchWatcher(Node):
    """Logs its publisher's and subscription's matched events."""

    def __init__(self) -> None:
        super().__init__("match_watcher")
        from std_msgs.msg import String

        self.pub_events: list[QoSPublisherMatchedInfo] = []
        self.sub_events: list[QoSSubscriptionMatchedInfo] = []
        self.pub = self.create_publisher(
            String,
            "out",
            10,
            event_callbacks=PublisherEventCallbacks(matched=self.pub_events.append),
        )
        self.sub = self.create_subscription(
            String,
            "in",
            lambda msg: None,
            10,
            event_callbacks=SubscriptionEventCallbacks(matched=self.sub_events.append),
        )


def _spin_until(executor: SingleThreadedExecutor, events: list[Any], count: int) -> None:
    """Spin until ``events`` holds ``count`` entries (at most a scaled 10 s)."""
    deadline = time.monotonic() + scaled(10)
    while len(events) < count and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.05)
    assert len(events) == count, events


def test_matched_events_follow_the_counterparts_coming_and_going(rclpy_inproc: None) -> None:
    from std_msgs.msg import Int32, String

    watcher = MatchWatcher()
    other = rclpy.create_node("counterparts")
    executor = SingleThreadedExecutor()
    executor.add_node(watcher)
    executor.add_node(other)

    sub1 = other.create_subscription(String, "out", lambda msg: None, 10)
    _spin_until(executor, watcher.pub_events, 1)
    sub2 = other.create_subscription(String, "out", lambda msg: None, 10)
    _spin_until(executor, watcher.pub_events, 2)
    other.destroy_subscription(sub1)
    _spin_until(executor, watcher.pub_events, 3)
    other.destroy_subscription(sub2)
    _spin_until(executor, watcher.pub_events, 4)
    assert [(e.current_count, e.current_count_change) for e in watcher.pub_events] == [
        (1, 1), (2, 1), (1, -1), (0, -1),
    ]  # fmt: skip
    assert [e.total_count for e in watcher.pub_events] == [1, 2, 2, 2]  # matches ever made
    assert watcher.sub_events == []  # nothing published on "in" yet

    pub = other.create_publisher(String, "in", 10)
    _spin_until(executor, watcher.sub_events, 1)
    assert isinstance(watcher.sub_events[0], QoSSubscriptionMatchedInfo)
    assert watcher.sub_events[0].current_count == 1
    other.destroy_publisher(pub)
    _spin_until(executor, watcher.sub_events, 2)
    assert watcher.sub_events[1].current_count == 0
    other.create_publisher(Int32, "in", 10)  # another type: no match
    executor.spin_once(timeout_sec=0.2)
    assert len(watcher.sub_events) == 2


def test_deadline_misses_are_counted_on_both_sides_from_the_first_message(
    rclpy_inproc: None,
) -> None:
    from std_msgs.msg import String

    node = rclpy.create_node("deadlined")
    missed: dict[str, list[Any]] = {"pub": [], "sub": []}
    qos = QoSProfile(depth=10, deadline=Duration(seconds=0.05))
    pub = node.create_publisher(
        String, "beat", qos, event_callbacks=PublisherEventCallbacks(deadline=missed["pub"].append)
    )
    node.create_subscription(
        String,
        "beat",
        lambda msg: None,
        qos,
        event_callbacks=SubscriptionEventCallbacks(deadline=missed["sub"].append),
    )
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    pub.publish(String(data="once"))  # then silence: each 50 ms without one is a miss
    _spin_until(executor, missed["pub"], 1)
    _spin_until(executor, missed["sub"], 1)
    first = missed["pub"][0]
    assert isinstance(first, QoSOfferedDeadlineMissedInfo)
    assert first.total_count == first.total_count_change >= 1


def test_deadline_counting_with_a_clock_of_the_test_s(monkeypatch: pytest.MonkeyPatch) -> None:
    from rclpy import event_handler

    now = [0]
    monkeypatch.setattr(event_handler.time, "monotonic_ns", lambda: now[0])
    handler = event_handler.EventHandler(
        callback_group=None,  # type: ignore[arg-type]
        callback=print,
        event_type=QoSPublisherEventType.RCL_PUBLISHER_OFFERED_DEADLINE_MISSED,
    )
    watch = event_handler.EventWatch(
        [handler], matched_count=lambda: 0, lost_count=lambda: 0, deadline_ns=100
    )
    now[0] = 1_000
    assert watch.poll() == []  # no message yet: nothing to miss
    watch.activity()  # deadline at 1100
    now[0] = 1_099
    assert watch.poll() == []
    now[0] = 1_100
    [(_, status)] = watch.poll()
    assert (status.total_count, status.total_count_change) == (1, 1)
    now[0] = 1_350  # periods ending 1200 and 1300 missed
    [(_, status)] = watch.poll()
    assert (status.total_count, status.total_count_change) == (3, 2)
    now[0] = 1_420  # a message 20 ns late, before any poll: the miss is still counted
    watch.activity()
    [(_, status)] = watch.poll()
    assert (status.total_count, status.total_count_change) == (4, 1)
    now[0] = 1_500
    assert watch.poll() == []


def test_message_lost_reports_the_change_of_the_lost_count() -> None:
    from rclpy import event_handler
    from rclpy.event_handler import QoSMessageLostInfo, QoSSubscriptionEventType

    lost = [0]
    handler = event_handler.EventHandler(
        callback_group=None,  # type: ignore[arg-type]
        callback=print,
        event_type=QoSSubscriptionEventType.RCL_SUBSCRIPTION_MESSAGE_LOST,
    )
    watch = event_handler.EventWatch(
        [handler], matched_count=lambda: 0, lost_count=lambda: lost[0], deadline_ns=0
    )
    assert watch.poll() == []
    lost[0] = 3
    assert watch.poll() == [(handler, QoSMessageLostInfo(total_count=3, total_count_change=3))]
    assert watch.poll() == []
    lost[0] = 5
    assert watch.poll()[0][1] == QoSMessageLostInfo(total_count=5, total_count_change=2)


def test_liveliness_events_are_unsupported_as_on_rmw_zenoh(rclpy_inproc: None) -> None:
    from std_msgs.msg import String

    node = rclpy.create_node("lively")
    with pytest.raises(UnsupportedEventTypeError, match=r"LIVELINESS_CHANGED.*rmw_zenoh_cpp"):
        node.create_subscription(
            String,
            "t",
            lambda msg: None,
            10,
            event_callbacks=SubscriptionEventCallbacks(liveliness=print),
        )
    with pytest.raises(UnsupportedEventTypeError, match="LIVELINESS_LOST"):
        node.create_publisher(
            String, "t", 10, event_callbacks=PublisherEventCallbacks(liveliness=print)
        )
    # incompatible QoS: accepted (rmw_zenoh finds none incompatible, so it is never called)
    pub = node.create_publisher(
        String, "t", 10, event_callbacks=PublisherEventCallbacks(incompatible_qos=print)
    )
    assert [h.event_type for h in pub.event_handlers] == [
        QoSPublisherEventType.RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS
    ]
    pub.assert_liveliness()  # as rmw_zenoh's: the token is its liveliness, alive with it
    node.destroy_publisher(pub)
    with pytest.raises(InvalidHandle, match="destroyed"):
        pub.assert_liveliness()


class OverridableTalker(Node):
    """Its publisher's history, depth and reliability are parameters (qos_overrides_talker)."""

    def __init__(self, **kwargs: Any) -> None:
        super().__init__("overridable", **kwargs)
        from std_msgs.msg import String

        self.pub = self.create_publisher(
            String,
            "chatter",
            QoSProfile(depth=10),
            qos_overriding_options=QoSOverridingOptions.with_default_policies(callback=self.check),
        )

    def check(self, qos: QoSProfile) -> Any:
        from rclpy.qos_overriding_options import QosCallbackResult

        result = QosCallbackResult()
        result.successful = qos.depth <= 10
        result.reason = "" if result.successful else "depth must be at most 10"
        return result


def test_qos_overrides_come_from_parameters_and_are_read_only(rclpy_inproc: None) -> None:
    talker = OverridableTalker(
        cli_args=[
            "--ros-args", "-p", "qos_overrides./chatter.publisher.depth:=4",
            "-p", "qos_overrides./chatter.publisher.reliability:=best_effort",
        ]
    )  # fmt: skip
    assert talker.pub.qos_profile.depth == 4
    assert talker.pub.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT
    robomodel_qos = talker.pub.robomodel_publisher.qos  # what the bus was given
    assert robomodel_qos.depth == 4 and robomodel_qos.reliability.name == "BEST_EFFORT"
    history = talker.get_parameter("qos_overrides./chatter.publisher.history")
    assert history.value == "keep_last"  # not overridden: the profile's
    with pytest.raises(ParameterImmutableException):  # read-only, as rclpy declares them
        talker.set_parameters([Parameter("qos_overrides./chatter.publisher.depth", value=2)])


def test_the_overriding_callback_refuses_a_profile(rclpy_inproc: None) -> None:
    with pytest.raises(InvalidQosOverridesError, match="depth must be at most 10"):
        OverridableTalker(
            parameter_overrides=[Parameter("qos_overrides./chatter.publisher.depth", value=11)]
        )


def test_an_entity_id_and_a_subscription_get_their_own_parameters(rclpy_inproc: None) -> None:
    from std_msgs.msg import String

    node = rclpy.create_node("ids")
    options = QoSOverridingOptions(
        [rclpy.qos.QoSPolicyKind.DEPTH, rclpy.qos.QoSPolicyKind.LIFESPAN], entity_id="fast"
    )
    node.create_subscription(String, "chatter", lambda msg: None, 7, qos_overriding_options=options)
    assert node.get_parameter("qos_overrides./chatter.subscription_fast.depth").value == 7
    assert not node.has_parameter("qos_overrides./chatter.subscription_fast.lifespan")  # a sub
    assert not node.has_parameter("qos_overrides./chatter.subscription.depth")
