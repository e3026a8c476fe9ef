"""Full QoS in rmw_zenoh's tokens and in what the Zenoh transport does with it.

Expected strings are transcribed from ros2/rmw_zenoh Jazzy 0.2.10 (``ros2-gbp/rmw_zenoh-release``
tag ``release/jazzy/rmw_zenoh_cpp/0.2.10-1``): ``qos_to_keyexpr``, ``keyexpr_to_qos`` and
``str_to_size_t`` in ``src/detail/liveliness_utils.cpp``, the defaults in ``src/detail/qos.cpp``
(keep last 42, reliable, volatile, ``RMW_DURATION_INFINITE`` = 9223372036 s 854775807 ns,
automatic liveliness), ``best_available_qos`` there (a depth of 0 is 42), the publisher's
congestion control in ``PublisherData::make`` (``src/detail/rmw_publisher_data.cpp``) and the
subscription's queue in ``SubscriptionData::add_new_message``
(``src/detail/rmw_subscription_data.cpp``). rmw's enum values are ``rmw/types.h``'s.
"""

from __future__ import annotations

import time

import pytest

from robomodel.runtime.msg import Int32
from robomodel.runtime.qos import Durability, History, Liveliness, QoSProfile, Reliability
from robomodel.runtime.transport.rmw_zenoh import EntityToken, qos_from_key, qos_to_key
from tests.conftest import unique_domain
from tests.timing import scaled

S = 10**9
FULL = QoSProfile(
    depth=5,
    durability=Durability.TRANSIENT_LOCAL,
    reliability=Reliability.BEST_EFFORT,
    history=History.KEEP_ALL,
    deadline_ns=1 * S + 500_000_000,
    lifespan_ns=2 * S,
    liveliness=Liveliness.MANUAL_BY_TOPIC,
    liveliness_lease_ns=3 * S,
)


@pytest.mark.parametrize(
    ("qos", "expected"),
    [
        # rclcpp::QoS(rclcpp::KeepAll()): depth 0, adapted to 42 and so left out
        (QoSProfile(depth=0, history=History.KEEP_ALL), "::2,:,:,:,,"),
        (QoSProfile(depth=10, deadline_ns=S + 500_000_000), "::,10:1,500000000:,:,,"),
        # 2 s: the seconds differ from infinite's, and so do the nanoseconds (0)
        (QoSProfile(depth=10, lifespan_ns=2 * S), "::,10:,:2,0:,,"),
        (
            QoSProfile(depth=10, liveliness=Liveliness.MANUAL_BY_TOPIC, liveliness_lease_ns=3 * S),
            "::,10:,:,:3,3,0",
        ),
        (FULL, "2:1:2,5:1,500000000:2,0:3,3,0"),
        # infinite's seconds with other nanoseconds: only the nanoseconds are written
        (QoSProfile(depth=10, deadline_ns=9223372036 * S + 1), "::,10:,1:,:,,"),
    ],
)
def test_qos_to_keyexpr(qos: QoSProfile, expected: str) -> None:
    assert qos_to_key(qos) == expected


def test_every_field_round_trips() -> None:
    assert qos_from_key(qos_to_key(FULL)) == FULL


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("::,10:,:,:,,:more", QoSProfile(10)),  # parts past the sixth are ignored
        ("::,10,x:,,y:,,z:,,,w", QoSProfile(10)),  # and past each field's count
        ("::, 10:,:,:,,", QoSProfile(10)),  # strtoull skips leading blanks
        ("::,+10:,:,:,,", QoSProfile(10)),
        ("::3,10:,:,:,,", QoSProfile(10)),  # history UNKNOWN: read as the default
        ("0:0:0,10:,:,:0,,", QoSProfile(10)),  # SYSTEM_DEFAULT everywhere
        ("4:4:,10:,:,:5,,", QoSProfile(10)),  # BEST_AVAILABLE
        ("::,10:9223372036,854775807:,:,,", QoSProfile(10)),  # infinite, written out
    ],
)
def test_keyexpr_to_qos_is_as_lenient_as_rmw_zenoh(text: str, expected: QoSProfile) -> None:
    assert qos_from_key(text) == expected


@pytest.mark.parametrize(
    "text",
    [
        "::,10:,:,:,",  # liveliness needs three parts
        "::,10:,:,",  # five fields
        "::,-10:,:,:,,",  # str_to_size_t refuses a leading '-'
        "::,10x:,:,:,,",  # text after the number
        "::,18446744073709551616:,:,:,,",  # past size_t
        "::,10:,:,:2,,",  # MANUAL_BY_NODE is not in str_to_qos_liveliness
        "5::,10:,:,:,,",  # no reliability 5
    ],
)
def test_keyexpr_to_qos_refuses_what_rmw_zenoh_refuses(text: str) -> None:
    assert qos_from_key(text) is None


def test_a_publisher_s_token_carries_its_full_qos() -> None:
    from robomodel.runtime import Context

    domain = unique_domain()
    with Context("zenoh", domain_id=int(domain)) as ctx:
        node = ctx.create_node("qos_probe")
        node.create_publisher(Int32, "/counted", FULL)
        session = ctx.transport.session  # type: ignore[attr-defined]

        def publisher_tokens() -> list[str]:
            replies = session.liveliness().get(f"@ros2_lv/{domain}/**")
            keys = [str(r.ok.key_expr) for r in replies if r.ok]
            return [k for k in keys if "/MP/" in k and "%counted" in k]

        # the token reaches the router, which answers the query, only after a moment (CI, busy)
        deadline = time.monotonic() + scaled(10.0)
        while not (found := publisher_tokens()) and time.monotonic() < deadline:
            time.sleep(0.05)
        [key] = found
        assert key.endswith("/2:1:2,5:1,500000000:2,0:3,3,0")
        token = EntityToken.parse(key)
        assert token is not None and qos_from_key(token.qos) == FULL
        [endpoint] = ctx.graph(timeout_s=scaled(10.0)).topics["/counted"].publishers
        assert endpoint.qos == FULL


def test_keep_all_keeps_every_message_and_a_reliable_one_blocks() -> None:
    """With the executor not spinning, a KEEP_LAST(5) subscription keeps the newest five of
    200 messages, a KEEP_ALL one all 200 in order; the reliable KEEP_ALL publisher declares
    BLOCK congestion control, the KEEP_LAST one DROP."""
    import zenoh

    from robomodel.runtime import Context

    domain = unique_domain()
    keep_all = QoSProfile(depth=5, history=History.KEEP_ALL)
    with Context("zenoh", domain_id=int(domain)) as ctx:
        node = ctx.create_node("queues")
        got_all: list[int] = []
        got_last: list[int] = []
        node.create_subscription(Int32, "/all", lambda m: got_all.append(m.data), keep_all)
        node.create_subscription(Int32, "/last", lambda m: got_last.append(m.data), 5)
        pub_all = node.create_publisher(Int32, "/all", keep_all)
        pub_last = node.create_publisher(Int32, "/last", 5)
        assert pub_all._handle._pub.congestion_control == zenoh.CongestionControl.BLOCK  # type: ignore[attr-defined]
        assert pub_last._handle._pub.congestion_control == zenoh.CongestionControl.DROP  # type: ignore[attr-defined]
        for n in range(200):
            pub_all.publish(Int32(n))
            pub_last.publish(Int32(n))
        ctx.spin(duration_s=scaled(30.0), until=lambda: len(got_all) == 200 and 199 in got_last)
        assert got_all == list(range(200))
        assert got_last[-1] == 199 and len(got_last) < 200


def test_a_raw_subscription_on_the_receiving_thread_has_no_queue() -> None:
    """With the executor not spinning, a raw subscription whose callback is wrapped in
    ``OnReceivingThread`` gets all 200 payloads from another session, in order, with their
    sequence numbers, on a thread other than this one; its KEEP_LAST(5) depth bounds nothing
    (there is no queue). One not so wrapped gets nothing until the executor spins, then at
    most its depth."""
    import threading

    from robomodel.runtime import Context
    from robomodel.runtime.msg import serialize
    from robomodel.runtime.transport.base import MessageInfo, OnReceivingThread
    from tests.timing import wait_until

    domain = int(unique_domain())
    keep_all = QoSProfile(depth=5, history=History.KEEP_ALL)  # a reliable publisher that blocks
    with Context("zenoh", domain_id=domain) as ctx, Context("zenoh", domain_id=domain) as other:
        node = ctx.create_node("raw")
        arrived: list[tuple[bytes, int, int]] = []
        queued: list[bytes] = []
        raw = ctx.transport.create_raw_subscription  # type: ignore[attr-defined]
        qos = QoSProfile(depth=5, history=History.KEEP_LAST)

        def on_arrival(payload: bytes, info: MessageInfo) -> None:
            arrived.append((payload, info.publication_sequence_number, threading.get_ident()))

        raw(node.fully_qualified_name, "/raw", Int32, qos, OnReceivingThread(on_arrival))
        raw(node.fully_qualified_name, "/raw", Int32, qos, lambda p, _: queued.append(p))
        publisher = other.create_node("pub").create_publisher(Int32, "/raw", keep_all)
        wait_until(lambda: publisher.get_subscription_count() == 2, 20.0,
                   what="the publisher matching both subscriptions")  # fmt: skip
        for n in range(200):
            publisher.publish(Int32(n))
        wait_until(lambda: len(arrived) >= 200, 30.0,
                   what=lambda: f"200 payloads unspun, {len(arrived)} came")  # fmt: skip
        assert [p for p, _, _ in arrived] == [serialize(Int32(n)) for n in range(200)]
        assert [s for _, s, _ in arrived] == list(range(1, 201))
        assert threading.get_ident() not in {t for _, _, t in arrived}
        assert queued == []
        ctx.spin(duration_s=scaled(10.0), until=lambda: bool(queued))
        assert 0 < len(queued) <= 5
