"""A client's outgoing messages: a queue bounded in bytes, and per topic in count.

The bus's thread puts (never blocks); the client's sender thread takes. When the bytes waiting
would pass the bound, the oldest messages are dropped (a slow client sees the newest data, as
foxglove_bridge's ``send_buffer_limit`` and rosbridge's ``queue_length`` give it); a topic's
``queue_length`` (rosbridge's subscribe option) keeps at most that many of its messages waiting.
Replies and status lines (key ``None``) are never dropped for a topic's sake, only for bytes.
A message sent in fragments is one item (a tuple of frames), kept or dropped whole.
"""

from __future__ import annotations

import threading
from collections import deque

__all__ = ["Frame", "Outbox"]

Frame = str | bytes | tuple[str, ...]  # text, binary, or one message's fragments


def _size(frame: Frame) -> int:
    return sum(len(part) for part in frame) if isinstance(frame, tuple) else len(frame)


class Outbox:
    """Bounded FIFO of encoded frames (``str`` for text, ``bytes`` for binary, a tuple of
    texts for a message's fragments)."""

    def __init__(self, limit_bytes: int) -> None:
        self.limit_bytes = limit_bytes
        self._items: deque[tuple[str | None, Frame]] = deque()
        self._per_key: dict[str, int] = {}
        self._bytes = 0
        self._closed = False
        self._ready = threading.Condition()
        self.dropped = 0  # messages dropped so far (bytes over the bound, or a topic's queue)

    @property
    def waiting_bytes(self) -> int:
        with self._ready:
            return self._bytes

    def put(self, frame: Frame, *, key: str | None = None, queue_length: int = 0) -> None:
        """Queue ``frame``; ``key`` groups a topic's frames for its ``queue_length`` (0: no
        count bound). A frame larger than the whole bound is dropped at once."""
        size = _size(frame)
        with self._ready:
            if self._closed:
                return
            if size > self.limit_bytes:
                self.dropped += 1
                return
            if key is not None and queue_length > 0:
                while self._per_key.get(key, 0) >= queue_length:
                    self._drop_oldest(key)
            while self._bytes + size > self.limit_bytes and self._items:
                self._drop_oldest(None)
            self._items.append((key, frame))
            self._bytes += size
            if key is not None:
                self._per_key[key] = self._per_key.get(key, 0) + 1
            self._ready.notify()

    def _drop_oldest(self, key: str | None) -> None:
        """Drop the oldest frame of ``key`` (any frame when None)."""
        for index, (item_key, frame) in enumerate(self._items):
            if key is None or item_key == key:
                del self._items[index]
                self._forget(item_key, frame)
                self.dropped += 1
                return

    def _forget(self, key: str | None, frame: Frame) -> None:
        self._bytes -= _size(frame)
        if key is not None:
            left = self._per_key[key] - 1
            if left:
                self._per_key[key] = left
            else:
                del self._per_key[key]

    def take(self, timeout_s: float) -> Frame | None:
        """The oldest frame, waiting up to ``timeout_s``; None if none came or it is closed."""
        with self._ready:
            if not self._items and not self._closed:
                self._ready.wait(timeout_s)
            if not self._items:
                return None
            key, frame = self._items.popleft()
            self._forget(key, frame)
            return frame

    def close(self) -> None:
        with self._ready:
            self._closed = True
            self._items.clear()
            self._per_key.clear()
            self._bytes = 0
            self._ready.notify_all()
