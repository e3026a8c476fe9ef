"""Per-publisher sequence numbers of received samples: lost-message counts and duplicates.

rmw_zenoh's subscription (``SubscriptionData::add_new_message``) remembers the last sequence
number of each publisher GID and counts ``|seq - last| - 1`` messages as lost when the jump is
larger than one. robomodel does the same, with two differences:

- memory is bounded: at most ``max_publishers`` GIDs are remembered (least recently used
  first out), however many a peer invents;
- a sample at most ``window`` below the last one delivered from the same GID is a repeat (the
  history a transient-local subscriber queries can overlap the live samples) and is dropped.
  One further below is taken as a new start, so a forged huge sequence number cannot silence
  the real publisher for good.
"""

from __future__ import annotations

import collections

__all__ = ["SequenceTracker"]


class SequenceTracker:
    """Decides which samples to deliver and counts the ones lost in between."""

    def __init__(self, *, window: int = 1024, max_publishers: int = 1024) -> None:
        self._window = window
        self._max = max_publishers
        self._last: collections.OrderedDict[bytes, int] = collections.OrderedDict()
        self.lost = 0

    def __len__(self) -> int:
        return len(self._last)

    def accept(self, gid: bytes, sequence: int) -> bool:
        """Whether to deliver this sample (and remember it if so)."""
        last = self._last.get(gid)
        if last is not None:
            self._last.move_to_end(gid)
            if 0 <= last - sequence < self._window:
                return False
            if sequence - last > 1:
                self.lost += sequence - last - 1
        self._last[gid] = sequence
        if len(self._last) > self._max:
            self._last.popitem(last=False)
        return True
