"""``Publisher.get_subscription_count()`` on every transport (rclpy's name; rospy's
``get_num_connections()``): the in-process bus counts the subscriptions it delivers to, Zenoh
the graph's subscription tokens of the topic and type (rmw_zenoh's
``GraphCache::publisher_count_matched_subscriptions``), ROS 1 the publication's TCPROS
connections. Each count follows subscribers as they come and as they go."""

from __future__ import annotations

import xmlrpc.client
from collections.abc import Iterator

import pytest

from robomodel.runtime import Context
from robomodel.runtime.msg import Int32, get_message_type
from robomodel.runtime.transport.ros1.master import Master
from tests.conftest import unique_domain
from tests.ros1wire.conftest import free_port
from tests.timing import wait_until

String = get_message_type("std_msgs/msg/String")


@pytest.fixture
def master_uri() -> Iterator[str]:
    uri = f"http://127.0.0.1:{free_port()}/"
    master = Master(uri, "127.0.0.1")
    try:
        yield uri
    finally:
        master.close()


def _follows_subscribers(talker: Context, listener: Context) -> None:
    """0, then 1 per subscription of the publisher's type (another type on the topic is not
    matched), then 0 again once they are destroyed."""
    pub = talker.create_node("talker").create_publisher(Int32, "/count_me", 10)
    assert pub.get_subscription_count() == 0
    node = listener.create_node("listener")
    first = node.create_subscription(Int32, "/count_me", lambda m: None, 10)
    wait_until(
        lambda: pub.get_subscription_count() == 1,
        30,
        what="the first subscription",
        interval_s=0.01,
    )
    second = node.create_subscription(Int32, "/count_me", lambda m: None, 10)
    wait_until(
        lambda: pub.get_subscription_count() == 2,
        30,
        what="the second subscription",
        interval_s=0.01,
    )
    first.destroy()
    second.destroy()
    wait_until(
        lambda: pub.get_subscription_count() == 0,
        30,
        what="the subscriptions to go",
        interval_s=0.01,
    )


def test_inproc_counts_the_subscriptions_it_delivers_to() -> None:
    with Context() as ctx:
        _follows_subscribers(ctx, ctx)
        pub = ctx.create_node("typed").create_publisher(Int32, "/typed", 10)
        ctx.create_node("other").create_subscription(String, "/typed", lambda m: None, 10)
        assert pub.get_subscription_count() == 0  # another type: never delivered


def test_zenoh_counts_the_graph_s_subscription_tokens() -> None:
    pytest.importorskip("zenoh")
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as talker, Context("zenoh", domain_id=domain) as other:
        _follows_subscribers(talker, other)
        pub = talker.create_node("typed").create_publisher(Int32, "/typed", 10)
        other.create_node("other").create_subscription(String, "/typed", lambda m: None, 10)
        other.create_node("same").create_subscription(Int32, "/typed", lambda m: None, 10)

        def both_seen() -> bool:
            info = talker.graph().topics.get("/typed")
            return info is not None and len(info.subscribers) == 2

        wait_until(both_seen, 30, what="both subscriptions in the talker's graph", interval_s=0.01)
        assert pub.get_subscription_count() == 1


def test_ros1_counts_the_publication_s_connections(master_uri: str) -> None:
    with Context("ros1", master=master_uri) as talker, Context("ros1", master=master_uri) as other:
        _follows_subscribers(talker, other)
        # the master knows a subscriber that has not connected: it is not counted
        pub = talker.create_node("late").create_publisher(Int32, "/late", 10)
        proxy = xmlrpc.client.ServerProxy(master_uri)
        proxy.registerSubscriber("/ghost", "/late", "std_msgs/Int32", "http://127.0.0.1:1/")
        assert pub.get_subscription_count() == 0
