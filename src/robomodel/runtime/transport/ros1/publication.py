"""A node's publication of one topic over TCPROS: the subscribers connected to it, each with a
writer thread and a queue of ``queue_size`` messages (the oldest dropped when a subscriber falls
behind, as roscpp's publisher queue drops), and the latched message new subscribers get first.

A message is serialized once per publish, and not at all while nobody is connected and the
topic is not latched.

Bound: at most ``MAX_SUBSCRIBER_CONNECTIONS`` subscriber connections (so writer threads) at once
in one process, across its nodes and topics; past it a new subscriber is refused with an error
header and one throttled log line. A connection gives its slot back when it ends: when a write
fails, or when its subscriber closes (a writer with nothing to write looks every
``PEER_CHECK_S`` whether its peer is gone, since a subscriber sends nothing after its header).

``header_fields`` go into the connection header (rospy's ``Publisher(headers=...)``), and a
:class:`SubscriberWatch` (rospy's ``SubscribeListener``) is told of each subscriber that
connects, with a way to publish to it alone, and of each that goes, with how many remain.
"""

from __future__ import annotations

import collections
import functools
import itertools
import socket
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg import Message
from robomodel.runtime.transport.ros1.budget import ByteBudget
from robomodel.runtime.transport.ros1.tcpros import refuse, write_frame, write_header
from robomodel.runtime.transport.ros1.xmlrpc_io import log, log_throttled

if TYPE_CHECKING:
    from robomodel.runtime.transport.ros1.ros1_types import Ros1Type

__all__ = [
    "MAX_SUBSCRIBER_CONNECTIONS",
    "Publication",
    "SubscriberWatch",
    "subscriber_connections",
]

# A robomodel process publishes a few tens of topics (joint states, tf, tf_static, the robot
# description, controller and simulation topics), each read by a handful of nodes (RViz,
# rosbag, rostopic, robot_state_publisher): tens of connections. 256 is ten times that, and 256
# writer threads cost a few MiB.
MAX_SUBSCRIBER_CONNECTIONS = 256
PEER_CHECK_S = 1.0  # how soon an idle writer notices that its subscriber closed
FLUSH_S = 1.0  # how long a closing publication lets its writers write what is queued
_SLOTS = ByteBudget(MAX_SUBSCRIBER_CONNECTIONS)  # counts connections, one unit each
_connection_ids = itertools.count(1)


def subscriber_connections() -> int:
    """Subscriber connections of this process now (each with its writer thread)."""
    return _SLOTS.used


def _peer_closed(sock: socket.socket) -> bool:
    """True once the subscriber closed its end; what it sent (nothing, in TCPROS) is discarded."""
    try:
        return sock.recv(1 << 12, socket.MSG_DONTWAIT) == b""
    except (BlockingIOError, InterruptedError):
        return False
    except OSError:
        return True


class _Outbound:
    """One subscriber's connection: a writer thread draining a bounded queue. It holds one of
    the process's subscriber slots, given back (by ``on_close``) when it closes."""

    def __init__(self, sock: socket.socket, peer: str, queue_size: int, on_close: Any) -> None:
        self.sock = sock
        self.peer = peer
        self.id = next(_connection_ids)
        self._queue: collections.deque[bytes] = collections.deque(maxlen=max(1, queue_size))
        self._ready = threading.Condition()
        self._open = True
        self._finishing = False  # write what is queued, then close
        self._closed = False
        self._on_close = on_close
        self.dropped = 0
        self._thread = threading.Thread(target=self._write, name="ros1-pub-writer", daemon=True)
        self._thread.start()

    @property
    def closed(self) -> bool:
        return self._closed

    def push(self, data: bytes) -> None:
        with self._ready:
            if len(self._queue) == self._queue.maxlen:
                self.dropped += 1
            self._queue.append(data)
            self._ready.notify()

    def _write(self) -> None:
        try:
            while True:
                with self._ready:
                    while self._open and not self._queue and not self._finishing:
                        if not self._ready.wait(PEER_CHECK_S) and _peer_closed(self.sock):
                            log.debug("subscriber %r closed its connection", self.peer)
                            return
                    if not self._open or not self._queue:
                        return
                    batch = list(self._queue)
                    self._queue.clear()
                for data in batch:
                    write_frame(self.sock, data)
        except OSError as exc:
            log.debug("subscriber %s gone: %s", self.peer, exc)
        finally:
            self.close()

    def finish(self, deadline: float) -> None:
        """Write what is queued (until ``deadline``, ``time.monotonic()``), then close: the
        last messages of a publisher that goes (rospy's ``on_shutdown`` hooks publish them)."""
        with self._ready:
            self._finishing = True
            self._ready.notify()
        if self._thread is not threading.current_thread():
            self._thread.join(max(0.0, deadline - time.monotonic()))
        self.close()

    def close(self) -> None:
        with self._ready:
            if self._closed:  # on_close runs once: it gives the slot back
                return
            self._closed = True
            self._open = False
            self._ready.notify()
        try:
            self.sock.close()
        finally:
            self._on_close(self)


@dataclass(frozen=True, slots=True, eq=False)
class SubscriberWatch:
    """Calls about a publication's subscribers, on the thread that accepted or lost one:
    ``connected(publish_to_it)`` once a subscriber's connection is made (before a latched
    message goes to it), ``gone(remaining)`` once it ended."""

    connected: Callable[[Callable[[Message], None]], None]
    gone: Callable[[int], None]


class Publication:
    """One topic a node publishes."""

    def __init__(
        self, caller_id: str, topic: str, kind: Ros1Type, *, latch: bool, queue_size: int
    ) -> None:
        self.caller_id = caller_id
        self.topic = topic
        self.kind = kind
        self.latch = latch
        self.queue_size = queue_size
        self.refs = 0
        self._seq = 0
        self._latched: bytes | None = None
        self._lock = threading.Lock()
        self.connections: list[_Outbound] = []
        self.watches: list[SubscriberWatch] = []
        self.header_fields: dict[str, str] = {}  # rospy's Publisher(headers=...)

    def subscriber_count(self) -> int:
        """Subscriber connections now (rospy's ``get_num_connections()``): updated as they
        are accepted and as they end, so reading it costs nothing."""
        return len(self.connections)

    def publish(self, msg: Message) -> None:
        with self._lock:
            connections = list(self.connections)
            if not connections and not self.latch:
                return
            data = self.kind.encode(msg, self._seq)
            self._seq += 1
            if self.latch:
                self._latched = data
        for connection in connections:
            connection.push(data)

    def accept(self, sock: socket.socket, header: dict[str, str]) -> None:
        """A subscriber's connection whose header asked for this topic."""
        peer = header.get("callerid", "?")
        md5 = header.get("md5sum", "")
        if md5 not in ("*", self.kind.md5sum):
            reason = (
                f"Client [{peer}] wants topic [{self.topic}] to have datatype/md5sum "
                f"[{header.get('type', '')}/{md5}], but our version has "
                f"[{self.kind.name}/{self.kind.md5sum}]. Dropping connection."
            )
            log.warning("%s", reason)
            refuse(sock, reason)
            return
        if not _SLOTS.take(1):
            self._refuse_past_cap(sock, peer)
            return
        try:
            connection = self._connect(sock, header, peer)
        except BaseException:
            _SLOTS.give(1)
            raise
        with self._lock:
            if not connection.closed:  # a writer that failed at once has given its slot back
                self.connections.append(connection)
            latched = self._latched
        for watch in list(self.watches):
            self._tell(watch.connected, functools.partial(self._publish_to, connection))
        if latched is not None:
            connection.push(latched)

    def _publish_to(self, connection: _Outbound, msg: Message) -> None:
        """Send ``msg`` to one subscriber (rospy's ``peer_publish``)."""
        with self._lock:
            data = self.kind.encode(msg, self._seq)
            self._seq += 1
        connection.push(data)

    def _tell(self, call: Callable[[Any], None], value: Any) -> None:
        try:
            call(value)
        except Exception:
            log.exception("%s: a subscriber watch failed", self.topic)

    def _refuse_past_cap(self, sock: socket.socket, peer: str) -> None:
        log_throttled(
            "tcpros-subscribers",
            "TCPROS: more than %d subscriber connections at once in this process "
            "(MAX_SUBSCRIBER_CONNECTIONS); refusing %r on %s",
            MAX_SUBSCRIBER_CONNECTIONS,
            peer,
            self.topic,
        )
        refuse(
            sock,
            f"{self.caller_id} has {MAX_SUBSCRIBER_CONNECTIONS} subscriber connections "
            f"already (its process's limit); try again later",
        )

    def _connect(self, sock: socket.socket, header: dict[str, str], peer: str) -> _Outbound:
        """The reply header written and the writer started (the slot taken is the caller's
        to give back if this fails)."""
        fields = {
            "callerid": self.caller_id,
            "latching": "1" if self.latch else "0",
            "md5sum": self.kind.md5sum,
            "message_definition": self.kind.definition,
            "topic": self.topic,
            "type": self.kind.name,
        }
        write_header(sock, {**fields, **self.header_fields})  # as rospy: the user's win
        if header.get("tcp_nodelay") == "1":
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        return _Outbound(sock, peer, self.queue_size, self._forget)

    def _forget(self, connection: _Outbound) -> None:
        _SLOTS.give(1)
        with self._lock:
            if connection not in self.connections:
                return
            self.connections.remove(connection)
            remaining = len(self.connections)
        for watch in list(self.watches):
            self._tell(watch.gone, remaining)

    def close(self) -> None:
        """Close the connections, once each has written what is queued for it (within
        ``FLUSH_S`` for them all)."""
        with self._lock:
            connections, self.connections = self.connections, []
        deadline = time.monotonic() + FLUSH_S
        for connection in connections:
            connection.finish(deadline)
