"""Per-frame transform storage: tf2's ``TimeCache`` and ``StaticCache``.

A cache belongs to a *child* frame and holds its pose in its parent over time. The dynamic
cache keeps samples newest first, drops exact duplicates, refuses data older than the newest
minus the cache time and prunes what falls behind it (``tf2/src/cache.cpp``). The static cache
keeps one sample that answers for any time (``tf2/src/static_cache.cpp``).
"""

from __future__ import annotations

from collections import deque
from typing import NamedTuple

import numpy as np

from robomodel.kinematics.se3 import slerp_xyzw
from robomodel.tf.exceptions import (
    BackwardExtrapolationError,
    ExtrapolationError,
    ForwardExtrapolationError,
    NoDataForExtrapolationError,
)
from robomodel.tf.message import display_time

__all__ = ["StaticCache", "Storage", "TimeCache"]


class Storage(NamedTuple):
    """One sample: the child's pose in ``parent`` at ``stamp_ns``.

    A named tuple rather than a dataclass: one is created per transform received (a /tf
    listener stores thousands a second), and tuple construction is several times cheaper.
    """

    stamp_ns: int
    parent: str
    translation: tuple[float, float, float]
    rotation_xyzw: tuple[float, float, float, float]


def _interpolate(older: Storage, newer: Storage, time_ns: int) -> Storage:
    if newer.stamp_ns == older.stamp_ns:
        return newer
    ratio = (time_ns - older.stamp_ns) / (newer.stamp_ns - older.stamp_ns)
    t0, t1 = np.array(older.translation), np.array(newer.translation)
    t = t0 + ratio * (t1 - t0)
    q = slerp_xyzw(older.rotation_xyzw, newer.rotation_xyzw, ratio)
    return Storage(
        time_ns,
        older.parent,
        (float(t[0]), float(t[1]), float(t[2])),
        (float(q[0]), float(q[1]), float(q[2]), float(q[3])),
    )


class TimeCache:
    """Samples of one frame over the last ``cache_time_ns``."""

    is_static = False

    def __init__(self, cache_time_ns: int) -> None:
        self.cache_time_ns = cache_time_ns
        self._samples: deque[Storage] = deque()  # newest first: new data goes in at the left

    def insert(self, sample: Storage) -> bool:
        """Add a sample; False if it is older than the newest minus the cache time."""
        s = self._samples
        if s and s[0].stamp_ns >= sample.stamp_ns:  # not newer than the newest: find its place
            if s[0].stamp_ns > sample.stamp_ns + self.cache_time_ns:
                return False
            k = 0
            while k < len(s) and s[k].stamp_ns > sample.stamp_ns:
                k += 1
            if k < len(s) and s[k].stamp_ns == sample.stamp_ns:
                return True  # exact duplicate time: tf2 keeps the first one
            s.insert(k, sample)
            return True  # the newest is unchanged, so nothing falls out of the cache time
        s.appendleft(sample)  # the usual case: newer than all, O(1) at the left
        latest = sample.stamp_ns
        while s[-1].stamp_ns + self.cache_time_ns < latest:
            s.pop()
        return True

    def get(self, time_ns: int) -> Storage:
        """The sample at ``time_ns`` (0: the latest), interpolated between neighbours.

        Raises:
            ExtrapolationError: (a subclass) with tf2's message.
        """
        s = self._samples
        if not s:
            raise NoDataForExtrapolationError("Lookup would require extrapolation: no data")
        if time_ns == 0:
            return s[0]
        if len(s) == 1:
            if s[0].stamp_ns == time_ns:
                return s[0]
            raise NoDataForExtrapolationError(
                f"Lookup would require extrapolation at time {display_time(time_ns)}, "
                f"but only time {display_time(s[0].stamp_ns)} is in the buffer"
            )
        latest, earliest = s[0].stamp_ns, s[-1].stamp_ns
        if time_ns == latest:
            return s[0]
        if time_ns == earliest:
            return s[-1]
        if time_ns > latest:
            raise ForwardExtrapolationError(
                "Lookup would require extrapolation into the future.  Requested time "
                f"{display_time(time_ns)} but the latest data is at time {display_time(latest)}"
            )
        if time_ns < earliest:
            raise BackwardExtrapolationError(
                "Lookup would require extrapolation into the past.  Requested time "
                f"{display_time(time_ns)} but the earliest data is at time "
                f"{display_time(earliest)}"
            )
        k = 0
        while s[k].stamp_ns > time_ns:
            k += 1
        older, newer = s[k], s[k - 1]
        if older.parent != newer.parent:
            return older  # no interpolation across a parent change (tf2)
        return _interpolate(older, newer, time_ns)

    def latest(self) -> tuple[int, str | None]:
        """Newest stamp and parent (``(0, None)`` when empty)."""
        if not self._samples:
            return 0, None
        return self._samples[0].stamp_ns, self._samples[0].parent

    @property
    def oldest_ns(self) -> int:
        return self._samples[-1].stamp_ns if self._samples else 0

    @property
    def latest_ns(self) -> int:
        return self._samples[0].stamp_ns if self._samples else 0

    def __len__(self) -> int:
        return len(self._samples)

    def clear(self) -> None:
        self._samples.clear()


class StaticCache:
    """One sample valid at every time; its stamps count as 0 (never limit lookups)."""

    is_static = True

    def __init__(self) -> None:
        self._sample: Storage | None = None

    def insert(self, sample: Storage) -> bool:
        self._sample = sample
        return True

    def get(self, time_ns: int) -> Storage:
        if self._sample is None:
            raise ExtrapolationError("Lookup would require extrapolation: no data")
        return self._sample._replace(stamp_ns=time_ns)

    def latest(self) -> tuple[int, str | None]:
        return 0, None if self._sample is None else self._sample.parent

    @property
    def oldest_ns(self) -> int:
        return 0

    @property
    def latest_ns(self) -> int:
        return 0

    def __len__(self) -> int:
        return 1

    def clear(self) -> None:
        """Nothing: tf2's ``StaticCache::clearList`` keeps static data."""
