"""The attachment of a Zenoh sample (``type|publisher id|sequence``), parsed strictly, and the
per-publisher duplicate filter that history replays need.

Samples come from other processes, so nothing in an attachment is trusted: the three fields
must be ASCII of bounded length (``'²'.isdigit()`` is true in Python but ``int('²')`` raises),
state kept per publisher is bounded however many publisher ids a peer invents, and a forged
sequence number cannot silence the real publisher for good.
"""

from __future__ import annotations

import collections
import re
from dataclasses import dataclass

__all__ = ["Attachment", "SequenceFilter", "parse_attachment"]

_ATTACHMENT = re.compile(rb"([A-Za-z0-9_/]{1,200})\|([A-Za-z0-9_-]{1,64})\|([0-9]{1,19})")


@dataclass(frozen=True, slots=True)
class Attachment:
    """What a robomodel publisher attaches to each sample."""

    type_name: str
    publisher_id: str
    sequence: int


def parse_attachment(data: bytes) -> Attachment | None:
    """The attachment, or None when it is absent or not exactly robomodel's ASCII format."""
    match = _ATTACHMENT.fullmatch(data)
    if match is None:
        return None
    type_name, publisher_id, sequence = match.groups()
    return Attachment(type_name.decode("ascii"), publisher_id.decode("ascii"), int(sequence))


class SequenceFilter:
    """Drops samples already delivered, per publisher, with bounded memory.

    A transient-local subscriber gets a publisher's history by query while live samples keep
    coming, so the same sequence number can arrive twice: a sample is a duplicate when it is at
    most ``window`` below the last one delivered from that publisher. One far below (a
    publisher id reused after a restart, or the real publisher after a peer forged a huge
    sequence number for its id) is taken as a new start rather than dropped forever.
    Publishers are remembered least-recently-used first, at most ``max_publishers``.
    """

    def __init__(self, *, window: int = 1024, max_publishers: int = 1024) -> None:
        self._window = window
        self._max = max_publishers
        self._last: collections.OrderedDict[str, int] = collections.OrderedDict()

    def __len__(self) -> int:
        return len(self._last)

    def accept(self, publisher_id: str, sequence: int) -> bool:
        """Whether to deliver this sample (and remember it if so)."""
        last = self._last.get(publisher_id)
        if last is not None:
            self._last.move_to_end(publisher_id)
            if 0 <= last - sequence < self._window:
                return False
        self._last[publisher_id] = sequence
        if len(self._last) > self._max:
            self._last.popitem(last=False)
        return True
