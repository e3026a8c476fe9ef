"""Per-publisher sequence numbers of received samples: lost-message counts.

As rmw_zenoh's subscription (``SubscriptionData::add_new_message`` in
``rmw_zenoh_cpp/src/detail/rmw_subscription_data.cpp``): the last sequence number of each
publisher GID is remembered, a jump of more than one either way counts ``|seq - last| - 1``
messages as lost, and the sample is delivered all the same. A sample below the last one is a
publisher that restarted with the same GID (a fixed Zenoh id, a restarted latched
``/robot_description``), not a repeat to drop; repeats of a transient-local history are the
advanced subscriber's business, as in rmw_zenoh. The last number is always updated, so a
forged huge one cannot silence the real publisher.

One difference: memory is bounded, at most ``max_publishers`` GIDs are remembered (least
recently used first out), however many a peer invents.
"""

from __future__ import annotations

__all__ = ["SequenceTracker"]


class SequenceTracker:
    """Counts the samples lost between those received, per publisher GID."""

    def __init__(self, *, max_publishers: int = 1024) -> None:
        self._max = max_publishers
        # a plain dict in recency order: popping a GID and storing it again moves it last
        # (two dict operations a sample, where an OrderedDict took four)
        self._last: dict[bytes, int] = {}
        self.lost = 0

    def __len__(self) -> int:
        return len(self._last)

    def record(self, gid: bytes, sequence: int) -> None:
        """Record a received sample (which is delivered whatever its number, as rmw_zenoh does)."""
        seen = self._last
        last = seen.pop(gid, None)
        seen[gid] = sequence
        if last is None:
            if len(seen) > self._max:  # the least recently heard publisher is forgotten
                del seen[next(iter(seen))]
            return
        jump = abs(sequence - last)
        if jump > 1:
            self.lost += jump - 1
