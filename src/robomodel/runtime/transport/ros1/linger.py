"""Closing a connection that was answered before its input was read, so that the peer reads
the answer instead of a reset (a "lingering close").

A TCP socket closed while input it has not read is in its buffer, or that arrives after the
close, makes the kernel answer with RST instead of FIN (RFC 1122 4.2.2.13; Linux does both). A
peer that is still sending its request then fails in ``send`` with "connection reset by peer"
and never reads the answer that was written for it. Servers that answer before they have read
a request whole (an XML-RPC 503 past the cap of requests at once, a 413 for a body too large to
read, a TCPROS error header to a client that sent frames after its header) therefore hand the
socket to :func:`close_after_answer`: it shuts down the writing side (the answer and a FIN go
out), then one thread reads and discards what the peer still sends until the peer closes, for
at most ``LINGER_S`` (Apache httpd's lingering close does the same, 2 s per read), and only
then closes.

Bounds: one thread per process, started when a connection lingers and ended when none does;
at most ``MAX_LINGERING`` connections at a time (past that a connection is closed at once, as
without lingering); one 64 KiB scratch buffer; at most ``_ROUND_BYTES`` read from one peer
before the others get their turn.
"""

from __future__ import annotations

import contextlib
import logging
import selectors
import socket
import threading
import time
from typing import cast

__all__ = ["LINGER_S", "MAX_LINGERING", "close_after_answer", "lingering"]

log = logging.getLogger("robomodel.ros1")

LINGER_S = 2.0  # a peer that has read the answer closes within milliseconds
MAX_LINGERING = 256  # connections draining at once, in one process
_POLL_S = 0.05  # how soon a connection handed over joins the ones being drained
_CHUNK_BYTES = 1 << 16
_ROUND_BYTES = 1 << 20  # read from one peer per round, so that a fast one cannot starve others


class _Lingering:
    """The connections being drained, and the one thread that drains them while any are."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._arrived: list[tuple[socket.socket, float]] = []  # (socket, deadline)
        self.count = 0  # arrived or being drained
        self._running = False

    def add(self, sock: socket.socket) -> bool:
        """Drain and close ``sock`` (its writing side shut down); False if there is no room."""
        with self._lock:
            if self.count >= MAX_LINGERING:
                return False
            self.count += 1
            self._arrived.append((sock, time.monotonic() + LINGER_S))
            if self._running:
                return True
            try:
                threading.Thread(target=self._run, name="ros1-linger", daemon=True).start()
            except RuntimeError:  # no thread left: closed at once, as without lingering
                self._arrived.pop()
                self.count -= 1
                return False
            self._running = True
            return True

    def _run(self) -> None:
        selector = selectors.DefaultSelector()
        deadlines: dict[socket.socket, float] = {}
        buffer = bytearray(_CHUNK_BYTES)
        try:
            while True:
                with self._lock:
                    arrived, self._arrived = self._arrived, []
                    if not arrived and not deadlines:
                        self._running = False
                        return
                for sock, deadline in arrived:
                    deadlines[sock] = deadline
                    selector.register(sock, selectors.EVENT_READ)
                for key, _ in selector.select(_POLL_S):
                    sock = cast(socket.socket, key.fileobj)
                    if _drained(sock, buffer):
                        self._close(sock, selector, deadlines)
                now = time.monotonic()
                for sock, deadline in list(deadlines.items()):
                    if deadline <= now:  # the peer had LINGER_S to read the answer
                        self._close(sock, selector, deadlines)
        except Exception:  # a bug here must not leave sockets open for good
            log.exception("closing lingering connections")
            with self._lock:
                self._running = False
                arrived, self._arrived = self._arrived, []
            for sock, deadline in arrived:
                deadlines[sock] = deadline
            for sock in list(deadlines):
                self._close(sock, selector, deadlines)
        finally:
            selector.close()

    def _close(
        self,
        sock: socket.socket,
        selector: selectors.BaseSelector,
        deadlines: dict[socket.socket, float],
    ) -> None:
        with contextlib.suppress(KeyError, ValueError):
            selector.unregister(sock)
        del deadlines[sock]
        sock.close()
        with self._lock:
            self.count -= 1


def _drained(sock: socket.socket, buffer: bytearray) -> bool:
    """Read and discard what ``sock`` has (up to ``_ROUND_BYTES``); True once the peer closed
    or is gone, False while it may send more."""
    read = 0
    while read < _ROUND_BYTES:
        try:
            got = sock.recv_into(buffer)
        except (BlockingIOError, InterruptedError):
            return False
        except OSError:
            return True
        if got == 0:
            return True
        read += got
    return False


_LINGERING = _Lingering()


def lingering() -> int:
    """How many connections are being drained in this process now."""
    return _LINGERING.count


def close_after_answer(sock: socket.socket) -> None:
    """Close ``sock``, whose answer is written, without losing the answer to a reset: see the
    module docstring. The socket is the caller's no longer."""
    try:
        sock.shutdown(socket.SHUT_WR)
        sock.setblocking(False)
    except OSError:  # the peer is gone already: nothing to read an answer
        sock.close()
        return
    if not _LINGERING.add(sock):
        sock.close()
