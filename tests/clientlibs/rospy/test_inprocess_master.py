"""A rospy node on robomodel's master in this process (messages over TCPROS on loopback).

Where its callbacks run, as rospy's: each topic has a callback thread (a slow callback on one
topic does not delay another, a Timer ticks meanwhile), a topic's messages come in order to
every Subscriber of it over one connection, ``queue_size`` drops the oldest, service handlers
of concurrent calls run at once, and the threads are bounded and counted. Also what
ros_tutorials' programs needed: ``header.seq`` as sent, and ``SubscribeListener``."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest

import robomodel.clientlibs.rospy as rospy
from robomodel.clientlibs.rospy import dispatch, timer
from robomodel.runtime.transport.ros1.ros1_types import ros1_service_type
from robomodel.runtime.transport.ros1.services import call_service
from tests.clientlibs.rospy.inprocess_node import rospy_node
from tests.timing import scaled, wait_until


@pytest.fixture(scope="module")
def node() -> Iterator[str]:
    """A rospy node of this process on a master of its own; yields the master's URI."""
    from std_msgs.msg import Int32  # noqa: F401  (the genpy faces, as a rospy script has them)

    with rospy_node("threads") as uri:
        yield uri


def _connected(publisher: Any, count: int = 1) -> None:
    wait_until(
        lambda: publisher.get_num_connections() == count,
        scaled(10),
        what=f"{count} subscriber connection(s) to {publisher.resolved_name}",
    )


def test_a_slow_callback_on_one_topic_delays_neither_another_topic_nor_a_timer(
    node: str,
) -> None:
    from std_msgs.msg import String

    release = threading.Event()
    slow_threads: list[threading.Thread] = []
    heard: list[tuple[str, threading.Thread]] = []
    ticks: list[Any] = []

    def slow(msg: Any) -> None:
        slow_threads.append(threading.current_thread())
        release.wait(scaled(20))

    slow_sub = rospy.Subscriber("/slow", String, slow)
    fast_sub = rospy.Subscriber(
        "/fast", String, lambda m: heard.append((m.data, threading.current_thread()))
    )
    slow_pub = rospy.Publisher("/slow", String, queue_size=10)
    fast_pub = rospy.Publisher("/fast", String, queue_size=10)
    _connected(slow_pub)
    _connected(fast_pub)
    slow_pub.publish("take your time")
    wait_until(lambda: slow_threads, scaled(10), what="the slow callback to start")
    ticker = rospy.Timer(rospy.Duration(0.02), ticks.append)
    try:
        for n in range(5):
            fast_pub.publish(f"quick {n}")
        wait_until(lambda: len(heard) == 5, scaled(10), what="/fast while /slow's callback runs")
        wait_until(lambda: len(ticks) >= 3, scaled(10), what="the timer while /slow's runs")
        assert [data for data, _ in heard] == [f"quick {n}" for n in range(5)]
        threads = {slow_threads[0], heard[0][1], threading.main_thread()}
        assert len(threads) == 3  # each topic its own thread, neither the caller's
    finally:
        release.set()
        ticker.shutdown()
        slow_sub.unregister()
        fast_sub.unregister()
        slow_pub.unregister()
        fast_pub.unregister()


def test_one_topic_in_order_to_its_subscribers_over_one_connection(node: str) -> None:
    from std_msgs.msg import Int32

    first: list[tuple[int, int]] = []
    second: list[tuple[int, int]] = []
    subs = [
        rospy.Subscriber("/count", Int32, lambda m: first.append((m.data, threading.get_ident()))),
        rospy.Subscriber(
            "/count", Int32, lambda m, tag: second.append((m.data, tag)), callback_args=7
        ),
    ]
    pub = rospy.Publisher("/count", Int32, queue_size=500)
    try:
        _connected(pub)  # one connection for both Subscribers, as rospy's
        for n in range(300):
            pub.publish(n)
        wait_until(lambda: len(second) == 300, scaled(20), what="300 messages on /count")
        assert [n for n, _ in first] == list(range(300))
        assert second == [(n, 7) for n in range(300)]
        assert len({ident for _, ident in first}) == 1
        assert pub.get_num_connections() == 1
    finally:
        for sub in subs:
            sub.unregister()
        pub.unregister()


def test_queue_size_keeps_the_newest_messages(node: str) -> None:
    from std_msgs.msg import Int32

    release = threading.Event()
    got: list[int] = []

    def blocking(msg: Any) -> None:
        got.append(msg.data)
        if msg.data == 0:
            release.wait(scaled(20))

    sub = rospy.Subscriber("/latest", Int32, blocking, queue_size=2)
    pub = rospy.Publisher("/latest", Int32, queue_size=100)
    try:
        _connected(pub)
        pub.publish(0)
        wait_until(lambda: got == [0], scaled(10), what="the first message's callback")
        for n in range(1, 11):
            pub.publish(n)
        waiting = sub._impl.dispatch  # type: ignore[union-attr]  # the topic's queue
        wait_until(lambda: waiting.dropped == 8, scaled(10), what="8 of 10 messages dropped")
        release.set()
        wait_until(lambda: len(got) == 3, scaled(10), what="the two newest messages")
        assert got == [0, 9, 10]
    finally:
        release.set()
        sub.unregister()
        pub.unregister()


def test_header_seq_counts_the_published_messages(node: str) -> None:
    from geometry_msgs.msg import PoseStamped

    seqs: list[int] = []
    sub = rospy.Subscriber("/stamped", PoseStamped, lambda m: seqs.append(m.header.seq))
    pub = rospy.Publisher("/stamped", PoseStamped, queue_size=10)
    try:
        _connected(pub)
        for _ in range(3):
            pub.publish(PoseStamped())
        wait_until(lambda: len(seqs) == 3, scaled(10), what="three poses")
        assert seqs == [seqs[0], seqs[0] + 1, seqs[0] + 2]
    finally:
        sub.unregister()
        pub.unregister()


def test_service_handlers_of_concurrent_calls_run_at_once(node: str) -> None:
    from std_srvs.srv import SetBool

    both_inside = threading.Barrier(2, timeout=scaled(10))
    handler_threads: set[threading.Thread] = set()

    def switch(req: Any) -> tuple[bool, str]:
        handler_threads.add(threading.current_thread())
        both_inside.wait()  # raises BrokenBarrierError unless the other call is inside too
        return req.data, "on" if req.data else "off"

    service = rospy.Service("/switch_slowly", SetBool, switch)
    kind = ros1_service_type(SetBool)
    answers: dict[str, str] = {}

    def over_the_wire() -> None:
        request = SetBool._request_class(data=True)
        answer = call_service(node, "/wire_client", "/switch_slowly", kind, request, scaled(10))
        answers["wire"] = answer.message

    try:
        caller = threading.Thread(target=over_the_wire)
        caller.start()
        answers["local"] = rospy.ServiceProxy("/switch_slowly", SetBool)(False).message
        caller.join(scaled(10))
        assert answers == {"wire": "on", "local": "off"}
        assert threading.main_thread() in handler_threads and len(handler_threads) == 2
    finally:
        service.shutdown()


def test_topic_threads_are_bounded_and_counted(node: str, monkeypatch: pytest.MonkeyPatch) -> None:
    from std_msgs.msg import Int32

    before = dispatch.topic_threads()
    monkeypatch.setattr(dispatch, "MAX_TOPIC_THREADS", before + 2)
    got: dict[str, list[int]] = {"/b0": [], "/b1": [], "/b2": []}
    subs = [rospy.Subscriber(t, Int32, got[t].append) for t in got]
    pubs = [rospy.Publisher(t, Int32, queue_size=10) for t in got]
    try:
        assert dispatch.topic_threads() == before + 2  # the third topic shares a thread
        for pub in pubs:
            _connected(pub)
            pub.publish(5)
        wait_until(
            lambda: all(len(v) == 1 for v in got.values()), scaled(10), what="all three topics"
        )
    finally:
        for sub in subs:
            sub.unregister()
        for pub in pubs:
            pub.unregister()
    assert dispatch.topic_threads() == before  # a thread ends with its last topic


def test_timers_are_bounded_and_counted(node: str, monkeypatch: pytest.MonkeyPatch) -> None:
    # a Timer an earlier test shut down may still be ending: counted now, gone at the end
    wait_until(lambda: timer.timer_threads() == 0, 10, what="the earlier tests' Timers to end")
    before = timer.timer_threads()
    monkeypatch.setattr(timer, "MAX_TIMER_THREADS", before + 1)
    ticking = rospy.Timer(rospy.Duration(0.01), lambda event: None)
    try:
        assert timer.timer_threads() == before + 1
        with pytest.raises(rospy.ROSException, match="MAX_TIMER_THREADS"):
            rospy.Timer(rospy.Duration(0.01), lambda event: None)
    finally:
        ticking.shutdown()
    ticking.join(scaled(5))
    assert timer.timer_threads() == before


def test_a_subscribe_listener_greets_each_subscriber(node: str) -> None:
    from std_msgs.msg import String

    events: list[tuple[str, object]] = []

    class Greeter(rospy.SubscribeListener):
        def peer_subscribe(self, topic_name: str, topic_publish: Any, peer_publish: Any) -> None:
            events.append(("subscribe", topic_name))
            peer_publish(String("welcome"))  # a message
            peer_publish("and hello")  # or its fields, as publish() takes them

        def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
            events.append(("unsubscribe", num_peers))

    pub = rospy.Publisher("/greetings", String, subscriber_listener=Greeter(), queue_size=10)
    heard: list[str] = []
    sub = rospy.Subscriber("/greetings", String, lambda m: heard.append(m.data))
    try:
        wait_until(lambda: len(heard) == 2, scaled(10), what="the greetings")
        assert heard == ["welcome", "and hello"]
        assert events == [("subscribe", "/greetings")]
        sub.unregister()
        wait_until(lambda: len(events) == 2, scaled(10), what="the listener told of the end")
        assert events[1] == ("unsubscribe", 0)
    finally:
        sub.unregister()
        pub.unregister()


def test_connection_headers_travel_with_messages_requests_and_responses(node: str) -> None:
    from std_msgs.msg import String
    from std_srvs.srv import SetBool

    headers: list[dict[str, str]] = []
    pub = rospy.Publisher("/snacks", String, headers={"cookies": "oreo"}, queue_size=10)
    sub = rospy.Subscriber("/snacks", String, lambda m: headers.append(m._connection_header))

    def serve(req: Any) -> tuple[bool, str]:
        return True, req._connection_header.get("cookies", "none")

    service = rospy.Service("/snack_bar", SetBool, serve)
    try:
        _connected(pub)
        pub.publish("crumbs")
        wait_until(lambda: headers, scaled(10), what="a message with its connection header")
        assert headers[0]["cookies"] == "oreo" and headers[0]["callerid"] == "/threads"
        assert headers[0]["type"] == "std_msgs/String" and headers[0]["topic"] == "/snacks"
        proxy = rospy.ServiceProxy("/snack_bar", SetBool, headers={"cookies": "peanut butter"})
        response = proxy(True)
        assert response.message == "peanut butter"
        assert response._connection_header["callerid"] == "/threads"
        assert response._connection_header["type"] == "std_srvs/SetBool"
    finally:
        service.shutdown()
        sub.unregister()
        pub.unregister()


def test_what_is_published_before_unregister_is_delivered(node: str) -> None:
    from std_msgs.msg import String

    heard: list[int] = []
    sub = rospy.Subscriber("/last_words", String, lambda m: heard.append(len(m.data)))
    pub = rospy.Publisher("/last_words", String, queue_size=100)
    try:
        _connected(pub)
        for n in range(20):  # 2 MB: more than the sockets hold, still queued at unregister
            pub.publish("x" * (100_000 + n))
        pub.unregister()  # as at shutdown, after on_shutdown hooks published
        wait_until(lambda: len(heard) == 20, scaled(10), what="all 20 messages")
        assert heard == [100_000 + n for n in range(20)]
    finally:
        sub.unregister()
        pub.unregister()
