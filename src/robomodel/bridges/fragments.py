"""rosbridge's ``fragment`` operation, both ways.

Outgoing: once a client gave ``fragment_size`` (on any operation, as rosbridge's protocol takes
it), each JSON frame longer than that goes as ``{"op": "fragment", "id", "data", "num",
"total"}`` frames of at most ``fragment_size`` characters of the original's text each, ``num``
from 0 and ``total`` their count (rosbridge's ``Fragmentation``; its ``total`` is a float in
Python 3, which roslibjs rounds down to this count). The id is the message's own when it has
one, else a number of the client's (from 1: roslibjs ignores a fragment whose id is falsy).
Binary (CBOR) frames are never fragmented (rosbridge cannot fragment them either).

Incoming: a client's fragments are joined when all ``total`` came and the text is handled as
one operation (rosbridge's ``Defragment``), within :class:`~.limits.BridgeLimits`' bounds: the
bytes held per client, the messages being joined at once, the fragments per message, and
``fragment_timeout_s`` after a message's last fragment (rosbridge's ``fragment_timeout``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from robomodel.bridges.exceptions import ClientError
from robomodel.bridges.limits import BridgeLimits

__all__ = ["Reassembly", "split"]


def split(text: str, size: int, message_id: Any) -> tuple[str, ...]:
    """``text`` as fragment operations of at most ``size`` characters of it each."""
    import json

    total = math.ceil(len(text) / size)
    parts = range(0, len(text), size)
    return tuple(
        json.dumps(
            {
                "op": "fragment",
                "id": message_id,
                "data": text[at : at + size],
                "num": num,
                "total": total,
            }
        )
        for num, at in enumerate(parts)
    )


@dataclass
class _Partial:
    total: int
    parts: dict[int, str] = field(default_factory=dict)
    size: int = 0
    last_s: float = 0.0


class Reassembly:
    """One client's messages in fragments (module docstring)."""

    def __init__(
        self, limits: BridgeLimits, *, clock_s: Callable[[], float] = time.monotonic
    ) -> None:
        self.limits = limits
        self._clock_s = clock_s
        self._partial: dict[str, _Partial] = {}
        self._bytes = 0

    @property
    def held_bytes(self) -> int:
        return self._bytes

    def add(self, message: dict[str, Any]) -> str | None:
        """Take one ``fragment`` operation; the joined text once its message is complete."""
        key, num, total, data = _fields(message, self.limits.max_fragments)
        now = self._clock_s()
        self._forget_stale(now)
        partial = self._partial.get(key)
        if partial is None:
            if len(self._partial) >= self.limits.max_fragmented_messages:
                raise ClientError(
                    f"fragment: {len(self._partial)} messages are being joined already "
                    "(the bridge's bound); finish one first"
                )
            partial = self._partial[key] = _Partial(total)
        if total != partial.total:
            raise ClientError(
                f"fragment {key}: total {total}, where its first fragment said {partial.total}"
            )
        if num in partial.parts:
            raise ClientError(f"fragment {key}: fragment {num} came twice")
        if self._bytes + len(data) > self.limits.max_fragment_bytes:
            self._drop(key)
            raise ClientError(
                f"fragment {key}: the fragments held would pass "
                f"{self.limits.max_fragment_bytes} bytes; the message is dropped"
            )
        partial.parts[num] = data
        partial.size += len(data)
        partial.last_s = now
        self._bytes += len(data)
        if len(partial.parts) < partial.total:
            return None
        self._drop(key)
        return "".join(partial.parts[n] for n in range(partial.total))

    def _drop(self, key: str) -> None:
        gone = self._partial.pop(key, None)
        if gone is not None:
            self._bytes -= gone.size

    def _forget_stale(self, now: float) -> None:
        stale = [
            key for key, partial in self._partial.items()
            if now - partial.last_s > self.limits.fragment_timeout_s
        ]  # fmt: skip
        for key in stale:
            self._drop(key)

    def clear(self) -> None:
        self._partial.clear()
        self._bytes = 0


def _fields(message: dict[str, Any], max_fragments: int) -> tuple[str, int, int, str]:
    """The fragment's (id, num, total, data), checked."""
    message_id, num, total, data = (message.get(k) for k in ("id", "num", "total", "data"))
    if message_id is None or isinstance(message_id, dict | list):
        raise ClientError("fragment: 'id' must be a string or a number")
    if isinstance(total, float) and math.isfinite(total):
        total = math.floor(
            total
        )  # rosbridge's own total is (n - 1) / size + 1, as roslibjs reads it
    if isinstance(num, bool) or not isinstance(num, int):
        raise ClientError(f"fragment {message_id}: 'num' must be a whole number")
    if isinstance(total, bool) or not isinstance(total, int):
        raise ClientError(f"fragment {message_id}: 'total' must be a number")
    if not 0 < total <= max_fragments:
        raise ClientError(
            f"fragment {message_id}: 'total' {total}; a message has 1 to {max_fragments} fragments"
        )
    if not 0 <= num < total:
        raise ClientError(f"fragment {message_id}: 'num' {num} is not in [0, {total})")
    if not isinstance(data, str):
        raise ClientError(f"fragment {message_id}: 'data' must be a string")
    return str(message_id), num, total, data
