"""A node's TCPROS port: connections accepted and their connection headers read on one thread,
without blocking on any peer, then handed over.

One thread waits on the listening socket and every connection whose header is still coming
(``selectors``), so a peer that sends two bytes and stalls holds neither the accept path nor a
thread: a real subscriber that connects meanwhile is read and served at once. Bounds: a header
must be complete within ``HANDSHAKE_TIMEOUT_S``; at most ``MAX_HANDSHAKES`` are in progress and
their declared sizes add up to at most ``HANDSHAKE_BUDGET_BYTES``; beyond either, the oldest
pending connection is dropped to make room (a stalled one, as a live peer sends its header at
once). Dropped connections are logged once per server with a warning, then at debug level.
"""

from __future__ import annotations

import contextlib
import logging
import selectors
import socket
import struct
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport.ros1.tcpros import MAX_HEADER_BYTES, TcprosError, parse_header
from robomodel.runtime.transport.ros1.xmlrpc_io import log

__all__ = ["HANDSHAKE_TIMEOUT_S", "MAX_HANDSHAKES", "HandshakeServer"]

HANDSHAKE_TIMEOUT_S = 5.0
MAX_HANDSHAKES = 128
HANDSHAKE_BUDGET_BYTES = 16 << 20  # a subscriber's header is a few kB (its message definition)
_POLL_S = 0.5  # how soon a closed server's thread notices

Dispatch = Callable[[socket.socket, dict[str, str], Any], None]


@dataclass(eq=False)
class _Pending:
    sock: socket.socket
    address: Any
    deadline: float
    data: bytearray = field(default_factory=bytearray)
    size: int | None = None  # the header's declared byte count, once its prefix is in

    @property
    def charged(self) -> int:
        return self.size or 0


class HandshakeServer:
    """Accepts on ``listener`` and calls ``dispatch(sock, header, address)`` on a thread of its
    own for each connection whose header arrived whole (``sock`` blocking, with a timeout of
    ``HANDSHAKE_TIMEOUT_S`` for the reply)."""

    def __init__(self, listener: socket.socket, dispatch: Dispatch, owner: str) -> None:
        self._listener = listener
        self._dispatch = dispatch
        self._owner = owner
        self._pending: dict[socket.socket, _Pending] = {}  # in arrival order
        self._charged = 0
        self._warned = False
        self._alive = True
        listener.setblocking(False)
        self._selector = selectors.DefaultSelector()
        self._selector.register(listener, selectors.EVENT_READ)
        self._thread = threading.Thread(target=self._run, name="ros1-tcpros", daemon=True)
        self._thread.start()

    @property
    def in_progress(self) -> int:
        return len(self._pending)

    def _run(self) -> None:
        try:
            while self._alive:
                for key, _ in self._selector.select(self._wait_s()):
                    if key.fileobj is self._listener:
                        self._accept()
                    elif key.data.sock in self._pending:  # not dropped earlier in this round
                        self._read_guarded(key.data)
                self._expire()
        except (OSError, ValueError):  # the listener closed under select()
            pass
        finally:
            for pending in list(self._pending.values()):
                self._drop(pending, None)
            self._selector.close()

    def _wait_s(self) -> float:
        first = next(iter(self._pending.values()), None)
        if first is None:
            return _POLL_S
        return max(0.0, min(_POLL_S, first.deadline - time.monotonic()))

    def _accept(self) -> None:
        while True:
            try:
                sock, address = self._listener.accept()
            except (BlockingIOError, InterruptedError):
                return
            except OSError as exc:  # out of file descriptors: the others wait in the backlog
                log.debug("%s: cannot accept a TCPROS connection: %s", self._owner, exc)
                return
            sock.setblocking(False)
            while len(self._pending) >= MAX_HANDSHAKES:
                self._drop(next(iter(self._pending.values())), "too many handshakes at once")
            pending = _Pending(sock, address, time.monotonic() + HANDSHAKE_TIMEOUT_S)
            self._pending[sock] = pending
            self._selector.register(sock, selectors.EVENT_READ, pending)

    def _read_guarded(self, pending: _Pending) -> None:
        try:
            self._read(pending)
        except Exception:  # a bug with one peer must not close the port for all of them
            log_failure(log, "%s: TCPROS handshake from %s", self._owner, pending.address)
            self._drop(pending, None)

    def _read(self, pending: _Pending) -> None:
        want = 4 - len(pending.data) if pending.size is None else pending.size - len(pending.data)
        try:
            chunk = pending.sock.recv(min(want, 1 << 16))
        except (BlockingIOError, InterruptedError):
            return
        except OSError as exc:
            self._drop(pending, f"{exc}", quiet=True)
            return
        if not chunk:
            self._drop(pending, "closed by the peer", quiet=True)
            return
        pending.data += chunk
        if pending.size is None and len(pending.data) == 4:
            (size,) = struct.unpack("<I", pending.data)
            if size > MAX_HEADER_BYTES:
                self._drop(pending, f"a header of {size} bytes (at most {MAX_HEADER_BYTES})")
                return
            pending.size, pending.data = int(size), bytearray()
            self._charged += pending.size
            while self._charged > HANDSHAKE_BUDGET_BYTES:
                self._drop(next(iter(self._pending.values())), "too many header bytes at once")
        if pending.size is not None and len(pending.data) == pending.size:
            self._hand_over(pending)

    def _hand_over(self, pending: _Pending) -> None:
        self._forget(pending)
        try:
            header = parse_header(bytes(pending.data))
        except TcprosError as exc:
            log.warning("%s: dropping a TCPROS connection from %s: %s",
                        self._owner, pending.address, exc)  # fmt: skip
            pending.sock.close()
            return
        pending.sock.setblocking(True)
        pending.sock.settimeout(HANDSHAKE_TIMEOUT_S)
        try:
            threading.Thread(
                target=self._dispatch, args=(pending.sock, header, pending.address),
                name="ros1-tcpros-conn", daemon=True,
            ).start()  # fmt: skip
        except RuntimeError as exc:  # no thread left: this connection goes, the port stays
            log.warning("%s: dropping a TCPROS connection from %s: %s",
                        self._owner, pending.address, exc)  # fmt: skip
            pending.sock.close()

    def _expire(self) -> None:
        now = time.monotonic()
        for pending in list(self._pending.values()):
            if pending.deadline > now:
                break  # arrival order is deadline order
            self._drop(pending, f"no whole header within {HANDSHAKE_TIMEOUT_S} s")

    def _forget(self, pending: _Pending) -> None:
        if self._pending.pop(pending.sock, None) is not None:
            self._charged -= pending.charged
            with contextlib.suppress(KeyError, ValueError):
                self._selector.unregister(pending.sock)

    def _drop(self, pending: _Pending, reason: str | None, *, quiet: bool = False) -> None:
        self._forget(pending)
        pending.sock.close()
        if reason is None:
            return
        level = logging.DEBUG if quiet or self._warned else logging.WARNING
        if level == logging.WARNING:
            self._warned = True
            reason += " (further dropped handshakes are logged at debug level)"
        log.log(level, "%s: dropping a TCPROS connection from %s: %s",
                self._owner, pending.address, reason)  # fmt: skip

    def close(self) -> None:
        self._alive = False
