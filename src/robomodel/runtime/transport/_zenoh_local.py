"""Samples from a session's own publishers, handed straight to its on-arrival subscriptions.

A raw subscription whose callback runs on the receiving thread (:class:`OnReceivingThread`:
a bridge forwarding payloads to its clients) gets the samples of publishers in its own
Zenoh session from the publisher itself, right after ``put`` sent them to other processes:
the CDR payload that was just encoded, with no trip through Zenoh's routing and no copy out
of a Zenoh buffer. Its Zenoh subscriber then takes remote samples only (``allowed_origin``
remote), and drops what Zenoh still brings of the session's own publishers (the history a
transient-local subscriber queries), so each sample comes once. This is rclcpp's
intra-process communication for the case robomodel has: nodes of one process on one bus, such
as ``robomodel launch``'s simulation and foxglove_bridge; unlike rclcpp's, the sample goes to
other processes first, so a subscription in the publisher's process never delays them.

A transient-local subscription also gets, once, what each transient-local publisher of its
session keeps (its last ``depth`` samples, the subscription's depth at most), as Zenoh's
advanced subscriber queries a remote publisher's cache; for this such a publisher keeps its
last ``depth`` payloads, besides Zenoh's cache of them. A sample published while the
subscription is made goes either into what is replayed or to the subscription live, never
both and never neither (the registry changes under the publishers' locks).
"""

from __future__ import annotations

import contextlib
import threading
from typing import Protocol, TypeVar

__all__ = ["KeptSample", "LocalDelivery", "LocalPublisher", "LocalSubscription"]

_T = TypeVar("_T")
KeptSample = tuple[bytes, int, int, bytes]  # payload, sequence number, source time [ns], GID


class LocalPublisher(Protocol):
    """A publisher as local delivery sees it."""

    @property
    def gid(self) -> bytes:
        """Its GID, as its samples' attachments carry it."""

    @property
    def lock(self) -> threading.Lock:
        """Held while it numbers, sends and keeps a sample."""

    def kept(self) -> list[KeptSample]:
        """What it keeps for late transient-local subscribers, oldest first (under ``lock``)."""


class LocalSubscription(Protocol):
    """An on-arrival raw subscription as local delivery sees it."""

    def deliver_local(self, sample: KeptSample) -> None:
        """Hand it a sample of its own session's publisher (on the publishing thread)."""


class LocalDelivery:
    """The session's local publishers and on-arrival subscriptions, by data key."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        # each value a tuple replaced whole: a publisher reads its key's without a lock
        self._subscriptions: dict[str, tuple[LocalSubscription, ...]] = {}
        self._publishers: dict[str, tuple[LocalPublisher, ...]] = {}
        self._gids: frozenset[bytes] = frozenset()  # replaced whole, read without a lock

    def subscriptions(self, key: str) -> tuple[LocalSubscription, ...]:
        """The on-arrival subscriptions on ``key`` now (read under the publisher's lock)."""
        return self._subscriptions.get(key, ())

    def is_local(self, gid: bytes) -> bool:
        """Whether ``gid`` is a publisher of this session: Zenoh's copy of its sample (the
        history a transient-local subscriber queries reaches the session's own publishers
        too) is dropped, this module delivered it."""
        return gid in self._gids

    def add_publisher(self, key: str, publisher: LocalPublisher) -> None:
        with self._lock:
            self._publishers[key] = (*self._publishers.get(key, ()), publisher)
            self._gids = self._gids | {publisher.gid}

    def remove_publisher(self, key: str, publisher: LocalPublisher) -> None:
        with self._lock:
            _remove(self._publishers, key, publisher)
            self._gids = self._gids - {publisher.gid}

    def add_subscription(
        self, key: str, subscription: LocalSubscription, *, replay_depth: int
    ) -> None:
        """Deliver to ``subscription`` from now on, first replaying up to ``replay_depth`` kept
        samples of each local publisher on ``key`` (0: none, a volatile subscription)."""
        with self._lock:
            publishers = self._publishers.get(key, ())
            with contextlib.ExitStack() as held:
                for publisher in publishers:
                    held.enter_context(publisher.lock)
                self._subscriptions[key] = (*self._subscriptions.get(key, ()), subscription)
                backlog = [
                    sample
                    for publisher in publishers
                    for sample in (publisher.kept()[-replay_depth:] if replay_depth else ())
                ]
        for sample in backlog:  # outside every lock: the callback may publish or subscribe
            subscription.deliver_local(sample)

    def remove_subscription(self, key: str, subscription: LocalSubscription) -> None:
        with self._lock:
            _remove(self._subscriptions, key, subscription)


def _remove(table: dict[str, tuple[_T, ...]], key: str, item: _T) -> None:
    rest = tuple(x for x in table.get(key, ()) if x is not item)
    if rest:
        table[key] = rest
    else:
        table.pop(key, None)
