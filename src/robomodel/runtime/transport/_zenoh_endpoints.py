"""The Zenoh transport's publishers and subscriptions (see ``zenoh_bus`` for the keys)."""

from __future__ import annotations

import collections
import threading
import uuid
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import CDRError, Message, deserialize, serialize
from robomodel.runtime.msg.cdr import prepare
from robomodel.runtime.qos import Durability
from robomodel.runtime.transport._attachment import SequenceFilter, parse_attachment
from robomodel.runtime.transport._zenoh_common import import_zenoh, log
from robomodel.runtime.transport.base import Endpoint, PublisherHandle, SubscriptionHandle

if TYPE_CHECKING:
    from robomodel.runtime.transport.zenoh_bus import ZenohTransport

__all__ = ["ZenohPublisher", "ZenohSubscription"]


class ZenohPublisher(PublisherHandle):
    def __init__(self, bus: ZenohTransport, endpoint: Endpoint, msg_type: type[Message]) -> None:
        self._bus = bus
        self._type = msg_type
        self._id = uuid.uuid4().hex[:16]
        self._seq = 0
        prepare(msg_type)
        self._lock = threading.Lock()
        session, prefix = bus.session, bus.prefix
        self._pub = session.declare_publisher(f"{prefix}/t{endpoint.topic}")
        self._token = session.liveliness().declare_token(bus.graph_key("pub", endpoint))
        self._history: collections.deque[tuple[bytes, bytes]] | None = None
        self._queryable = None
        self._history_token = None
        if endpoint.qos.durability is Durability.TRANSIENT_LOCAL:
            self._history = collections.deque(maxlen=max(1, endpoint.qos.depth))
            self._history_key = f"{prefix}/@l{endpoint.topic}/{self._id}"
            self._queryable = session.declare_queryable(self._history_key, self._serve_history)
            # Announces the history: subscribers query it whenever it becomes reachable.
            self._history_token = session.liveliness().declare_token(self._history_key)
        self._endpoint = endpoint

    def _serve_history(self, query: Any) -> None:
        with self._lock:
            history = list(self._history or ())
        # Each publisher answers on its own key: replies on the query's wildcard key would be
        # consolidated into one, and a late subscriber would get one broadcaster's /tf_static.
        for payload, attachment in history:
            query.reply(self._history_key, payload, attachment=attachment)

    def publish(self, msg: Message) -> None:
        if not isinstance(msg, self._type):
            raise RobomodelError(
                f"publisher on {self._endpoint.topic} has type {self._type.__typename__}, "
                f"got {type(msg).__name__}"
            )
        payload = serialize(msg)
        with self._lock:
            self._seq += 1
            attachment = f"{self._type.__typename__}|{self._id}|{self._seq}".encode()
            if self._history is not None:
                self._history.append((payload, attachment))
        self._pub.put(payload, attachment=attachment)

    def destroy(self) -> None:
        for handle in (self._history_token, self._queryable, self._token, self._pub):
            if handle is not None:
                try:
                    handle.undeclare()
                except Exception:  # already closed with the session
                    log.debug("undeclare failed", exc_info=True)


class ZenohSubscription(SubscriptionHandle):
    def __init__(
        self,
        bus: ZenohTransport,
        endpoint: Endpoint,
        msg_type: type[Message],
        deliver: Callable[[Message], None],
    ) -> None:
        self._bus = bus
        self._endpoint = endpoint
        self._type = msg_type
        self._deliver = deliver
        self._sequences = SequenceFilter()
        self._alive = True
        prepare(msg_type)
        # KEEP_LAST: at most `depth` samples wait for the executor; a slow subscriber drops
        # the oldest (as DDS does) instead of falling further and further behind.
        self._pending: collections.deque[tuple[bytes, bytes]] = collections.deque(
            maxlen=max(1, endpoint.qos.depth)
        )
        self._pending_lock = threading.Lock()
        self._scheduled = False
        self.dropped = 0
        session, prefix = bus.session, bus.prefix
        self._sub = session.declare_subscriber(f"{prefix}/t{endpoint.topic}", self._on_sample)
        self._token = session.liveliness().declare_token(bus.graph_key("sub", endpoint))
        self._history_sub = None
        if endpoint.qos.durability is Durability.TRANSIENT_LOCAL:
            # As DDS on matching a writer: every latched publisher's history is queried when its
            # token becomes visible, now (history=True) or later (a publisher that starts
            # later, or a peer reached again after the process that linked us exited).
            self._history_sub = session.liveliness().declare_subscriber(
                f"{prefix}/@l{endpoint.topic}/*", self._on_history_token, history=True
            )

    def _on_sample(self, sample: Any) -> None:  # a Zenoh thread
        payload = sample.payload.to_bytes()
        attachment = sample.attachment.to_bytes() if sample.attachment is not None else b""
        with self._pending_lock:
            if len(self._pending) == self._pending.maxlen:
                self.dropped += 1
            self._pending.append((payload, attachment))
            if self._scheduled:
                return
            self._scheduled = True
        self._bus.executor.post(self._drain)

    def _drain(self) -> None:
        """On the executor: handle what is pending now; later arrivals get their own turn."""
        with self._pending_lock:
            batch = list(self._pending)
            self._pending.clear()
            self._scheduled = False
        for payload, attachment in batch:
            try:
                self._handle(payload, attachment)
            except Exception:  # one bad sample (or callback) never costs the others
                log.exception("error handling a sample on %s", self._endpoint.topic)

    def _on_history_token(self, sample: Any) -> None:  # a Zenoh thread
        zenoh = import_zenoh()
        if not self._alive or sample.kind != zenoh.SampleKind.PUT:
            return
        # No consolidation: the publisher's whole history (depth samples on its one key).
        self._bus.session.get(
            str(sample.key_expr),
            self._on_reply,
            consolidation=zenoh.ConsolidationMode.NONE,
            timeout=2.0,
        )

    def _on_reply(self, reply: Any) -> None:  # a Zenoh thread
        sample = reply.ok
        if sample is not None:
            self._on_sample(sample)

    def _handle(self, payload: bytes, attachment: bytes) -> None:
        if not self._alive:
            return
        parsed = parse_attachment(attachment)
        if parsed is None:
            if attachment:  # a foreign or forged attachment: the sample cannot be trusted
                self._bus.warn_once(
                    (self._endpoint.topic, "attachment"),
                    "dropping samples on %s with a malformed attachment (%r...)",
                    self._endpoint.topic,
                    attachment[:40],
                )
                return
            pub_id, seq = "", 0
        else:
            if parsed.type_name != self._type.__typename__:
                self._bus.warn_once(
                    (self._endpoint.topic, parsed.type_name),
                    "topic %s is published as %s but subscribed as %s; messages are not delivered",
                    self._endpoint.topic,
                    parsed.type_name,
                    self._type.__typename__,
                )
                return
            pub_id, seq = parsed.publisher_id, parsed.sequence
        if pub_id and not self._sequences.accept(pub_id, seq):
            return  # already delivered (history replay overlapping live data)
        try:
            msg = deserialize(payload, self._type)
        except CDRError as exc:
            self._bus.warn_once(
                (self._endpoint.topic, "malformed"),
                "dropping a malformed %s payload on %s: %s",
                self._type.__typename__,
                self._endpoint.topic,
                exc,
            )
            return
        self._deliver(msg)

    def destroy(self) -> None:
        self._alive = False
        for handle in (self._history_sub, self._token, self._sub):
            if handle is None:
                continue
            try:
                handle.undeclare()
            except Exception:
                log.debug("undeclare failed", exc_info=True)
