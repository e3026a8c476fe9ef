"""The Zenoh transport's publishers and subscriptions, as rmw_zenoh's PublisherData and
SubscriptionData declare them (rmw_publisher_data.cpp, rmw_subscription_data.cpp):

- a volatile publisher is a Zenoh publisher on the topic's key; a transient-local one an
  advanced publisher with a cache of ``depth`` samples that late subscribers can query, with
  publisher detection, and (when reliable) sporadic heartbeats every 500 ms for sample-miss
  detection. Reliable maps to Zenoh's reliable reliability, best effort to best effort; the
  congestion control is DROP (BLOCK is for KEEP_ALL, which robomodel does not model).
- a volatile subscription is a Zenoh subscriber; a transient-local one an advanced subscriber
  that queries the history of every publisher, present or late-joining (and recovers missed
  samples from their heartbeats when reliable).
- every sample carries rmw_zenoh's attachment (sequence number from 1, source timestamp,
  the publisher's GID). A sample without a valid attachment is dropped with a bounded warning,
  as rmw_zenoh drops it ("Unable to obtain attachment").
- a raw subscription (``raw_deliver``, what a recorder uses) gets the CDR payload as it came
  and a :class:`MessageInfo` (source and receive timestamps, sequence number, GID) instead of
  a decoded message, as rclpy's ``raw=True`` subscriptions with message info do. One whose
  callback is wrapped in :class:`OnReceivingThread` gets them on Zenoh's receiving thread,
  without the executor's queue and its thread switch (a bridge forwarding payloads to a
  thread-safe sink); the samples of its own session's publishers come from them directly
  (:mod:`._zenoh_local`), Zenoh brings the others.
"""

from __future__ import annotations

import collections
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import CDRError, Message
from robomodel.runtime.msg.cdr import payload_decoder, payload_encoder
from robomodel.runtime.qos import Durability, History, Reliability
from robomodel.runtime.transport._attachment import SequenceTracker
from robomodel.runtime.transport._zenoh_common import (
    ZenohSessionOwner,
    direct,
    import_zenoh,
    log,
    undeclare_all,
)
from robomodel.runtime.transport._zenoh_local import KeptSample, LocalDelivery
from robomodel.runtime.transport.base import (
    Endpoint,
    MessageInfo,
    OnReceivingThread,
    PublisherHandle,
    SubscriptionHandle,
)
from robomodel.runtime.transport.rmw_zenoh import (
    EntityKind,
    encode_attachment,
    entity_gid,
    parse_attachment,
)

if TYPE_CHECKING:
    from robomodel.runtime.transport._zenoh_graph import GraphCache

__all__ = ["EndpointOwner", "ZenohPublisher", "ZenohSubscription"]

HEARTBEAT_PERIOD_S = 0.5  # SAMPLE_MISS_DETECTION_HEARTBEAT_PERIOD


class EndpointOwner(ZenohSessionOwner, Protocol):
    """The transport as its publishers see it: also the graph cache they count matches in."""

    @property
    def graph_cache(self) -> GraphCache: ...

    @property
    def local(self) -> LocalDelivery: ...


def _reliability(zenoh: Any, endpoint: Endpoint) -> Any:
    reliable = endpoint.qos.reliability is Reliability.RELIABLE
    return zenoh.Reliability.RELIABLE if reliable else zenoh.Reliability.BEST_EFFORT


class ZenohPublisher(PublisherHandle):
    def __init__(self, bus: EndpointOwner, endpoint: Endpoint, msg_type: type[Message]) -> None:
        zenoh = import_zenoh()
        self._type = msg_type
        self._endpoint = endpoint
        self._seq = 0
        self.lock = threading.Lock()  # numbers, sends and keeps a sample at a time
        self._destroyed = False
        self._encode = payload_encoder(msg_type)  # generated now, not on the first message
        token = bus.entity_token(endpoint, EntityKind.PUBLISHER, msg_type)
        self._gid = entity_gid(token.key())
        self._graph = bus.graph_cache
        self._match = (token.name, token.dds_type)
        key = self._key = bus.data_key(endpoint.topic, msg_type)
        self._local = bus.local
        # what a transient-local subscription of this session is replayed (Zenoh's cache
        # serves those of other processes)
        self._kept: collections.deque[KeptSample] | None = None
        # rmw_publisher_data.cpp (PublisherData::make): BLOCK for RELIABLE + KEEP_ALL, so a
        # slow link holds the publisher back rather than lose messages; DROP otherwise.
        keep_all = endpoint.qos.history is History.KEEP_ALL
        reliable = endpoint.qos.reliability is Reliability.RELIABLE
        congestion = "BLOCK" if keep_all and reliable else "DROP"
        options: dict[str, Any] = {
            "congestion_control": getattr(zenoh.CongestionControl, congestion),
            "reliability": _reliability(zenoh, endpoint),
        }
        if endpoint.qos.durability is Durability.TRANSIENT_LOCAL:
            ext = zenoh.ext
            miss = None
            if endpoint.qos.reliability is Reliability.RELIABLE:
                miss = ext.MissDetectionConfig(
                    heartbeat=None, sporadic_heartbeat=HEARTBEAT_PERIOD_S
                )
            self._kept = collections.deque(maxlen=max(1, endpoint.qos.depth))
            self._pub = ext.declare_advanced_publisher(
                bus.session,
                key,
                cache=ext.CacheConfig(max(1, endpoint.qos.depth)),
                publisher_detection=True,
                sample_miss_detection=miss,
                **options,
            )
        else:
            self._pub = bus.session.declare_publisher(key, **options)
        self._token = bus.session.liveliness().declare_token(token.key())
        self._local.add_publisher(key, self)

    @property
    def gid(self) -> bytes:
        return self._gid

    def publish(self, msg: Message) -> None:
        if not isinstance(msg, self._type):
            raise RobomodelError(
                f"publisher on {self._endpoint.topic} has type {self._type.__typename__}, "
                f"got {type(msg).__name__}"
            )
        payload = self._encode(msg)
        with self.lock:
            if self._destroyed:  # a message of a node torn down by another callback: dropped
                return
            self._seq += 1
            stamp_ns = time.time_ns()
            self._pub.put(payload, attachment=encode_attachment(self._seq, stamp_ns, self._gid))
            local = self._local.subscriptions(self._key)
            if self._kept is None and not local:
                return
            sample = (payload, self._seq, stamp_ns, self._gid)
            if self._kept is not None:
                self._kept.append(sample)
        for subscription in local:  # after other processes have it, outside the lock
            subscription.deliver_local(sample)

    def kept(self) -> list[KeptSample]:
        """What a transient-local subscription of this session is replayed, oldest first."""
        return [] if self._kept is None else list(self._kept)

    def subscription_count(self) -> int:
        return 0 if self._destroyed else self._graph.subscription_count(*self._match)

    def destroy(self) -> None:
        with self.lock:
            self._destroyed = True
        self._local.remove_publisher(self._key, self)
        undeclare_all(self._token, self._pub)


class ZenohSubscription(SubscriptionHandle):
    def __init__(
        self,
        bus: EndpointOwner,
        endpoint: Endpoint,
        msg_type: type[Message],
        deliver: Callable[[Message], None] | None,
        *,
        raw_deliver: Callable[[bytes, MessageInfo], None] | None = None,
    ) -> None:
        zenoh = import_zenoh()
        self._bus = bus
        self._endpoint = endpoint
        self._type = msg_type
        self._deliver = deliver
        self._raw_deliver = raw_deliver
        self._sequences = SequenceTracker()
        # Zenoh may call from one receiving thread per link: the tracker's update is guarded
        self._sequences_lock = threading.Lock()
        self._alive = True
        self._decode = payload_decoder(msg_type)  # generated now, not on the first message
        # KEEP_LAST: at most `depth` samples wait for the executor; a slow subscriber drops
        # the oldest (rmw_zenoh's message queue) instead of falling further behind. KEEP_ALL
        # keeps every one (SubscriptionData::add_new_message, rmw_subscription_data.cpp).
        keep_all = endpoint.qos.history is History.KEEP_ALL
        # Zenoh's thread appends and the executor pops, each atomic under the GIL: no lock.
        self._pending: collections.deque[tuple[Any, int]] = collections.deque(
            maxlen=None if keep_all else max(1, endpoint.qos.depth)
        )
        self._scheduled = False
        self.dropped = 0
        token = bus.entity_token(endpoint, EntityKind.SUBSCRIPTION, msg_type)
        key = self._key = bus.data_key(endpoint.topic, msg_type)
        on_arrival = isinstance(raw_deliver, OnReceivingThread)
        on_sample = self._on_arrival if on_arrival else self._on_sample
        # on arrival, this session's samples come from its publishers (._zenoh_local)
        self._local = bus.local if on_arrival else None
        origin = {"allowed_origin": zenoh.Locality.REMOTE} if on_arrival else {}
        transient_local = endpoint.qos.durability is Durability.TRANSIENT_LOCAL
        if transient_local:
            ext = zenoh.ext
            recovery = None
            if endpoint.qos.reliability is Reliability.RELIABLE:
                recovery = ext.RecoveryConfig(periodic_queries=None, heartbeat=True)
            self._sub = ext.declare_advanced_subscriber(
                bus.session,
                key,
                direct(on_sample),
                history=ext.HistoryConfig(
                    detect_late_publishers=True, max_samples=max(1, endpoint.qos.depth)
                ),
                recovery=recovery,
                subscriber_detection=True,
                **origin,
            )
        else:
            self._sub = bus.session.declare_subscriber(key, direct(on_sample), **origin)
        self._token = bus.session.liveliness().declare_token(token.key())
        if self._local is not None:
            depth = max(1, endpoint.qos.depth) if transient_local else 0
            self._local.add_subscription(key, self, replay_depth=depth)

    def messages_lost(self) -> int:
        """Messages lost, by the publishers' sequence numbers (rmw_zenoh's MESSAGE_LOST)."""
        return self._sequences.lost

    def _on_sample(self, sample: Any) -> None:  # a Zenoh thread
        # Only queue the sample and ring: the executor's thread wakes meanwhile, and takes the
        # GIL as soon as this returns. Reading the payload and attachment here would hold it
        # back by as long (~10 us a message at 1 kHz, BENCHMARKS.md's latency section).
        pending = self._pending
        if len(pending) == pending.maxlen:  # the drain may pop one meanwhile: a count, no more
            self.dropped += 1
        pending.append((sample, time.time_ns()))
        if not self._scheduled:
            self._scheduled = True
            self._bus.executor.post(self._drain)

    def deliver_local(self, sample: KeptSample) -> None:  # the publishing thread
        payload, sequence, stamp_ns, gid = sample
        if not self._alive or self._raw_deliver is None:
            return
        with self._sequences_lock:
            self._sequences.record(gid, sequence)
        try:
            self._raw_deliver(payload, MessageInfo(stamp_ns, time.time_ns(), sequence, gid))
        except Exception:  # a bad callback never costs the publisher
            log.exception("error handling a sample on %s", self._endpoint.topic)

    def _on_arrival(self, sample: Any) -> None:  # a Zenoh thread
        try:
            self._handle(sample, time.time_ns())
        except Exception:  # one bad sample (or callback) never costs the others
            log.exception("error handling a sample on %s", self._endpoint.topic)

    def _drain(self) -> None:
        """On the executor: handle what is pending now; later arrivals get their own turn.

        The flag is lowered before the first pop: a sample appended after that schedules
        another drain (at worst one that finds nothing), one appended before it is popped here.
        """
        self._scheduled = False
        pending = self._pending
        for _ in range(len(pending)):
            sample, received_ns = pending.popleft()
            try:
                self._handle(sample, received_ns)
            except Exception:  # one bad sample (or callback) never costs the others
                log.exception("error handling a sample on %s", self._endpoint.topic)

    def _handle(self, sample: Any, received_ns: int) -> None:
        if not self._alive:
            return
        attached = sample.attachment  # each access builds a new ZBytes: read it once
        attachment = b"" if attached is None else attached.to_bytes()
        parsed = parse_attachment(attachment)
        if parsed is None:
            self._no_attachment(attachment)
            return
        sequence, stamp_ns, gid = parsed
        if self._local is not None and self._local.is_local(gid):
            return  # the publisher delivered it itself
        with self._sequences_lock:
            self._sequences.record(gid, sequence)
        payload = sample.payload.to_bytes()
        if self._raw_deliver is not None:
            self._raw_deliver(payload, MessageInfo(stamp_ns, received_ns, sequence, gid))
            return
        try:
            msg = self._decode(payload)
        except CDRError as exc:
            topic = self._endpoint.topic
            self._bus.warn_once(
                (topic, "malformed"),
                "dropping a malformed %s payload on %s: %s",
                self._type.__typename__,
                topic,
                exc,
            )
            return
        if self._deliver is not None:
            self._deliver(msg)

    def _no_attachment(self, attachment: bytes) -> None:
        topic = self._endpoint.topic
        self._bus.warn_once(
            (topic, "attachment"),
            "dropping samples on %s without a valid rmw_zenoh attachment (%r...)",
            topic,
            attachment[:40],
        )

    def destroy(self) -> None:
        self._alive = False
        if self._local is not None:
            self._local.remove_subscription(self._key, self)
        undeclare_all(self._token, self._sub)
