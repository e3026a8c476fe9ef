"""A node's subscription to one topic over TCPROS: one connection per publisher the master (or a
``publisherUpdate``) names, each a reader thread that asks the publisher for the topic
(``requestTopic``), connects, exchanges headers and reads messages.

Messages are decoded on the reader thread and handed to the executor through a queue of
``depth`` messages (the oldest dropped when the node falls behind); a callback wrapped in
:class:`~robomodel.runtime.transport.base.OnReceivingThread` is called on the reader thread
instead (rospy's, which queues and dispatches on threads of its own), and a message whose class
has genpy's ``_connection_header`` slot gets the publisher's connection header. A publisher that drops the
connection while it is still registered is asked again after a growing pause (up to 2 s); a
malformed message is dropped with a log line, and the connection closed. A publisher no more
listed (it unregistered) is read until it closes, at most ``RETIRE_S``: what it sent last
arrives.

Bounds: at most ``MAX_PUBLISHERS`` publishers per subscription (more are ignored, with one
warning: a ``publisherUpdate`` listing 3,000 dead URIs made 3,000 threads); at most
``MAX_CONNECTING`` connection attempts at once per subscription (so dead publishers of one topic
do not delay another's), each within ``CONNECT_TIMEOUT_S`` per step (XML-RPC, connect, header);
a frame larger than the type's fixed size or than the frame budget allows is refused (see
:mod:`.tcpros`), with one warning per publisher.
"""

from __future__ import annotations

import collections
import contextlib
import logging
import socket
import threading
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from robomodel._escape import escape_name
from robomodel.runtime.msg import Message
from robomodel.runtime.transport.base import OnReceivingThread
from robomodel.runtime.transport.ros1.names import split_uri
from robomodel.runtime.transport.ros1.tcpros import (
    MAX_FRAME_BYTES,
    FrameRefused,
    TcprosError,
    read_header,
    receive_frame,
    write_header,
)
from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call, log

if TYPE_CHECKING:
    from robomodel.runtime.executor import Executor
    from robomodel.runtime.transport.ros1.ros1_types import Ros1Type

__all__ = ["Subscription"]

RETRY_MAX_S = 2.0
RETIRE_S = 2.0  # how long a connection to a publisher no more listed reads what is on its way
MAX_PUBLISHERS = 100  # per subscription; roscpp has no bound, a real graph has a handful
MAX_CONNECTING = 16  # connection attempts of one subscription at once
CONNECT_TIMEOUT_S = 5.0


class _Inbound:
    """The connection to one publisher (its slave API ``uri``)."""

    def __init__(self, subscription: Subscription, uri: str) -> None:
        self.sub = subscription
        self.uri = uri
        self.peer = uri
        self.connected = False
        self.header: dict[str, str] = {}  # the publisher's connection header
        self._alive = True
        self._retiring = False  # no more listed: read to the end, connect no more
        self._warned = False
        self._sock: socket.socket | None = None
        self._thread = threading.Thread(target=self._run, name="ros1-sub-reader", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        pause_s = 0.1
        while self._alive:
            try:
                sock = self._connect()
                if sock is not None:
                    self._read(sock)
            except FrameRefused as exc:
                self._refused(exc)
            except (OSError, TcprosError, Ros1WireError) as exc:
                if self._alive:
                    log.debug("%s from %s: %s", self.sub.topic, self.uri, exc)
            self.connected = False
            if not self._alive or self._retiring:
                return
            threading.Event().wait(pause_s)
            pause_s = min(RETRY_MAX_S, pause_s * 2)

    def _refused(self, exc: FrameRefused) -> None:
        """One warning per publisher; the next refusals (it is asked again) at debug level."""
        level = logging.DEBUG if self._warned else logging.WARNING
        self._warned = True
        log.log(level, "%s: closing the connection from %r: %s", self.sub.topic, self.peer, exc)

    def _connect(self) -> socket.socket | None:
        """Ask for the topic and connect, within one of the subscription's connection slots."""
        while not self.sub.connecting.acquire(timeout=0.5):
            if not self._alive:
                return None
        try:
            return self._handshake() if self._alive else None
        finally:
            self.sub.connecting.release()

    def _handshake(self) -> socket.socket | None:
        sub = self.sub
        answer = call(
            self.uri, "requestTopic", sub.caller_id, sub.topic, [["TCPROS"]],
            timeout_s=CONNECT_TIMEOUT_S,
        )  # fmt: skip
        if not (isinstance(answer, list) and len(answer) >= 3 and answer[0] == "TCPROS"):
            raise Ros1WireError(f"{self.uri} offers {sub.topic} over {answer!r:.60}, not TCPROS")
        host, port = str(answer[1]), int(answer[2])
        sock = socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S)
        self._sock = sock
        try:
            write_header(
                sock,
                {
                    "callerid": sub.caller_id,
                    "md5sum": sub.kind.md5sum,
                    "message_definition": sub.kind.definition,
                    "tcp_nodelay": "1",
                    "topic": sub.topic,
                    "type": sub.kind.name,
                },
            )
            header = read_header(sock)
        except BaseException:
            sock.close()
            raise
        if "error" in header:
            log.warning(  # the peer's words: control characters escaped
                "%s: publisher %s refused: %s", sub.topic, self.uri, escape_name(header["error"])
            )
            self._alive = False
            sock.close()
            return None
        self.peer = header.get("callerid", self.uri)
        self.header = header
        return sock

    def _read(self, sock: socket.socket) -> None:
        sub = self.sub
        limit = sub.kind.fixed_size or MAX_FRAME_BYTES
        try:
            sock.settimeout(None)
            self.connected = True
            while self._alive:
                with receive_frame(sock, limit) as data:
                    sub.receive(data, self)
        finally:
            sock.close()

    def retire(self) -> None:
        """The publisher is no more listed: read what it sent until it closes (as rospy, which
        keeps a connection to its end; the last messages of a publisher that shuts down are
        on their way), at most ``RETIRE_S``, and connect no more."""
        self._retiring = True
        if not self.connected:
            self.close()
            return
        closer = threading.Timer(RETIRE_S, self.close)
        closer.daemon = True
        closer.start()

    def close(self) -> None:
        self._alive = False
        if self._sock is not None:
            with contextlib.suppress(OSError):
                self._sock.shutdown(socket.SHUT_RDWR)


class Subscription:
    """One topic a node subscribes to."""

    def __init__(
        self,
        caller_id: str,
        topic: str,
        kind: Ros1Type,
        depth: int,
        executor: Executor,
        deliver: Callable[[Message], None],
    ) -> None:
        self.caller_id = caller_id
        self.topic = topic
        self.kind = kind
        self._executor = executor
        self._deliver = deliver
        self._in_place = isinstance(deliver, OnReceivingThread)
        # rospy's messages carry the publisher's connection header (genpy's slot)
        self._with_header = any(
            "_connection_header" in getattr(c, "__slots__", ()) for c in type.mro(kind.cls)
        )
        self._pending: collections.deque[Message] = collections.deque(maxlen=max(1, depth))
        self._lock = threading.Lock()
        self._scheduled = False
        self._alive = True
        self.inbound: dict[str, _Inbound] = {}
        self.dropped = 0
        self._warned_publishers = False
        self.connecting = threading.BoundedSemaphore(MAX_CONNECTING)

    def update_publishers(self, uris: Sequence[str]) -> None:
        """Connect to publishers newly listed; the ones no longer listed are retired."""
        wanted = []
        for uri in dict.fromkeys(uris):
            try:
                split_uri(str(uri))
                wanted.append(str(uri))
            except Exception:
                log.warning("%s: ignoring publisher URI %s", self.topic, escape_name(repr(uri)))
        with self._lock:
            if not self._alive:
                return
            wanted = self._within_bound(wanted)
            gone = [self.inbound.pop(u) for u in list(self.inbound) if u not in wanted]
            for uri in wanted:
                if uri not in self.inbound:
                    self.inbound[uri] = _Inbound(self, uri)
        for connection in gone:
            connection.retire()

    def _within_bound(self, wanted: list[str]) -> list[str]:
        """At most MAX_PUBLISHERS of ``wanted``: those already connected first, then in the
        order listed (the master lists publishers in the order they registered)."""
        if len(wanted) <= MAX_PUBLISHERS:
            return wanted
        if not self._warned_publishers:
            self._warned_publishers = True
            log.warning(
                "%s: %d publishers listed; reading from %d of them, the others are ignored",
                self.topic, len(wanted), MAX_PUBLISHERS,
            )  # fmt: skip
        kept = sorted(wanted, key=lambda uri: uri not in self.inbound)  # a stable sort
        return kept[:MAX_PUBLISHERS]

    def receive(self, data: bytes, connection: Any) -> None:  # a reader thread
        from robomodel.runtime.transport.ros1.ros1_types import Ros1CodecError

        try:
            msg = self.kind.decode(data)
        except Ros1CodecError as exc:
            log.warning(
                "%s: dropping a malformed message from %s: %s", self.topic, connection.peer, exc
            )
            raise TcprosError("malformed message") from None
        if self._with_header:
            msg._connection_header = connection.header  # type: ignore[attr-defined]
        if self._in_place:
            if self._alive:
                self._call(msg)
            return
        with self._lock:
            if len(self._pending) == self._pending.maxlen:
                self.dropped += 1
            self._pending.append(msg)
            if self._scheduled:
                return
            self._scheduled = True
        self._executor.post(self._drain)

    def _drain(self) -> None:
        with self._lock:
            batch = list(self._pending)
            self._pending.clear()
            self._scheduled = False
        for msg in batch:
            if not self._alive:
                return
            self._call(msg)

    def _call(self, msg: Message) -> None:
        try:
            self._deliver(msg)
        except Exception:
            log.exception("error handling a message on %s", self.topic)

    def close(self) -> None:
        with self._lock:
            self._alive = False
            connections, self.inbound = list(self.inbound.values()), {}
        for connection in connections:
            connection.close()
