"""On Zenoh, an on-arrival raw subscription (a bridge's) gets its own session's samples from
the publisher, once each, after other sessions have them; a transient-local one is replayed
what the session's transient-local publishers keep; other sessions' samples come through
Zenoh as before (``robomodel.runtime.transport._zenoh_local``)."""

from __future__ import annotations

import threading
from typing import Any

from robomodel.runtime import Context
from robomodel.runtime.msg import Int32, serialize
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.transport.base import MessageInfo, OnReceivingThread
from tests.conftest import unique_domain
from tests.timing import scaled, wait_until

LATCHED = QoSProfile(depth=2, durability=Durability.TRANSIENT_LOCAL)


def _subscribe(ctx: Context, qos: QoSProfile, topic: str = "/local") -> list[tuple[Any, ...]]:
    """An on-arrival raw subscription in ``ctx``: what it gets, as (payload, sequence, GID,
    thread)."""
    got: list[tuple[Any, ...]] = []
    node = ctx.create_node(f"sub_{len(ctx.nodes)}")

    def on(payload: bytes, info: MessageInfo) -> None:
        got.append((payload, info.publication_sequence_number, info.publisher_gid,
                    threading.get_ident()))  # fmt: skip

    ctx.transport.create_raw_subscription(  # type: ignore[attr-defined]
        node.fully_qualified_name, topic, Int32, qos, OnReceivingThread(on)
    )
    return got


def test_the_publishers_own_session_gets_each_sample_once_on_the_publishing_thread() -> None:
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as ctx, Context("zenoh", domain_id=domain) as other:
        here = _subscribe(ctx, QoSProfile(depth=5))
        there = _subscribe(other, QoSProfile(depth=5))
        publisher = ctx.create_node("pub").create_publisher(Int32, "/local")
        wait_until(lambda: publisher.get_subscription_count() == 2, 20.0,
                   what="the publisher matching both subscriptions")  # fmt: skip
        for n in range(50):
            publisher.publish(Int32(n))
        wait_until(lambda: len(there) >= 50, 30.0, what=lambda: f"50 samples, {len(there)} came")
        expected = [serialize(Int32(n)) for n in range(50)]
        assert [p for p, *_ in here] == expected  # all there at once, none twice
        assert [s for _, s, _, _ in here] == list(range(1, 51))
        assert {t for *_, t in here} == {threading.get_ident()}
        assert [p for p, *_ in there] == expected
        # the publisher's GID, as the other session reads it from the attachment
        assert len({g for _, _, g, _ in here}) == 1
        assert {g for _, _, g, _ in here} == {g for _, _, g, _ in there}
        assert threading.get_ident() not in {t for *_, t in there}  # Zenoh's thread

        # a sample of another session reaches this one through Zenoh, once
        remote = other.create_node("remote").create_publisher(Int32, "/local")
        wait_until(lambda: remote.get_subscription_count() == 2, 20.0,
                   what="the other session's publisher matching both")  # fmt: skip
        remote.publish(Int32(99))
        wait_until(lambda: len(here) > 50, 20.0, what="the other session's sample")
        ctx.spin(duration_s=scaled(0.3))  # a duplicate, if one came, would be in by now
        assert [p for p, *_ in here[50:]] == [serialize(Int32(99))]


def test_a_late_transient_local_subscription_is_replayed_what_the_session_keeps() -> None:
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as ctx:
        node = ctx.create_node("pub")
        latched = node.create_publisher(Int32, "/local", LATCHED)
        volatile = node.create_publisher(Int32, "/local")
        for n in range(5):
            latched.publish(Int32(n))
        volatile.publish(Int32(100))
        late = _subscribe(ctx, LATCHED)
        # the latched publisher's last two (its depth), none of the volatile one's, once
        assert [p for p, *_ in late] == [serialize(Int32(3)), serialize(Int32(4))]
        ctx.spin(duration_s=scaled(0.5))  # Zenoh's history query, were it to answer too
        assert len(late) == 2
        latched.publish(Int32(5))
        assert [p for p, *_ in late[2:]] == [serialize(Int32(5))]
        volatile_sub = _subscribe(ctx, QoSProfile(depth=5))
        assert volatile_sub == []  # a volatile subscription is replayed nothing


def test_a_destroyed_subscription_or_publisher_is_out_of_it() -> None:
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as ctx:
        got: list[bytes] = []
        node = ctx.create_node("sub")
        handle = ctx.transport.create_raw_subscription(  # type: ignore[attr-defined]
            node.fully_qualified_name, "/local", Int32, LATCHED,
            OnReceivingThread(lambda payload, _: got.append(payload)),
        )  # fmt: skip
        publisher = ctx.create_node("pub").create_publisher(Int32, "/local", LATCHED)
        publisher.publish(Int32(1))
        assert got == [serialize(Int32(1))]
        handle.destroy()
        publisher.publish(Int32(2))
        assert got == [serialize(Int32(1))]
        publisher.destroy()
        assert _subscribe(ctx, LATCHED) == []  # a destroyed publisher is replayed to nobody
