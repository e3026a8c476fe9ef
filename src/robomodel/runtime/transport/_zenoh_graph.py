"""The ROS graph from rmw_zenoh's liveliness tokens: robomodel's nodes and real ROS 2 ones.

As rmw_zenoh's context (``rmw_context_impl_s.cpp``: a liveliness subscriber on
``@ros2_lv/<domain>/**`` feeding its ``GraphCache``), a :class:`GraphCache` follows the tokens
of the domain as they are declared and undeclared; a subscriber with history receives those
declared before it. rmw_zenoh also asks for them once with a liveliness query, which robomodel
used to do on every graph read: with zenoh 1.10, a query matching a few hundred tokens came
back with none at all (measured: 200 tokens answered, 600 gave 0 replies while a subscriber's
history held all 600), so listings lost entries and looked complete.

Tokens that ``Entity::make`` would refuse are skipped. Memory and work are bounded: at most
``MAX_TOKENS_PER_PEER`` tokens are kept per peer (the Zenoh id a token names) and
``MAX_TOKENS`` in all; tokens past a bound are counted, one warning names the peer, and every
:class:`Graph` read while any are left out says it is not complete. Each token costs a dict
entry in and out (no scan of the others), and a graph snapshot is linear in the tokens kept.
"""

from __future__ import annotations

import collections
import threading
import time
from typing import Any

from robomodel._escape import escape_name
from robomodel.runtime.msg.typehash import ros_type_name
from robomodel.runtime.qos import QoSProfile
from robomodel.runtime.transport._zenoh_common import (
    direct,
    import_zenoh,
    log,
    release_freed_memory,
    undeclare_all,
)
from robomodel.runtime.transport.base import Endpoint, Graph
from robomodel.runtime.transport.rmw_zenoh import (
    ADMIN_SPACE,
    EntityKind,
    EntityToken,
    qos_from_key,
)

__all__ = ["MAX_TOKENS", "MAX_TOKENS_PER_PEER", "GraphCache", "add_token"]

MAX_TOKENS = 50_000
"""Tokens kept per domain, all peers together."""
TRIM_AFTER_REMOVALS = 1000
"""Tokens gone after which the process returns freed memory (``release_freed_memory``)."""
MAX_TOKENS_PER_PEER = 10_000
"""Tokens kept per peer: a process of 500 rclcpp nodes declares about 6,000 (a node, its
parameter services, /rosout and /parameter_events each)."""

_KINDS = {
    EntityKind.PUBLISHER: "pub",
    EntityKind.SUBSCRIPTION: "sub",
    EntityKind.SERVICE: "srv",
    EntityKind.CLIENT: "cli",
}


def add_token(graph: Graph, token: EntityToken) -> None:
    """Record one entity in ``graph``."""
    if token.kind is EntityKind.NODE:
        graph.nodes.add(token.node)
        return
    type_name = ros_type_name(token.dds_type) or token.dds_type
    qos = qos_from_key(token.qos)
    endpoint = Endpoint(token.node, token.name, type_name, qos or QoSProfile(), token.type_hash)
    graph.add(_KINDS[token.kind], endpoint)


class GraphCache:
    """The live tokens of one domain, kept up to date by a liveliness subscriber."""

    def __init__(
        self,
        session: Any,
        domain_id: int,
        *,
        max_tokens: int | None = None,
        max_per_peer: int | None = None,
    ) -> None:
        """Follow the tokens of ``domain_id``; the bounds default to ``MAX_TOKENS`` and
        ``MAX_TOKENS_PER_PEER``."""
        self._put = import_zenoh().SampleKind.PUT
        self._domain_id = domain_id
        self._max_tokens = MAX_TOKENS if max_tokens is None else max_tokens
        self._max_per_peer = MAX_TOKENS_PER_PEER if max_per_peer is None else max_per_peer
        self._removed = 0
        self._lock = threading.Lock()
        self._tokens: dict[str, EntityToken] = {}
        self._per_peer: collections.Counter[str] = collections.Counter()
        # subscriptions by (topic, DDS type name): what a publisher's matched count reads
        self._subscriptions: collections.Counter[tuple[str, str]] = collections.Counter()
        # hashes of the keys left out (so that their undeclaration is told from a stranger's),
        # then a count of those past the set's own bound
        self._left_out: set[int] = set()
        self._left_out_untracked = 0
        self._warned = False
        self.changed_at = time.monotonic()
        self._subscriber = session.liveliness().declare_subscriber(
            f"{ADMIN_SPACE}/{domain_id}/**", direct(self._on_sample), history=True
        )

    def __len__(self) -> int:
        return len(self._tokens)

    @property
    def left_out(self) -> int:
        """Live tokens not kept because of the bounds."""
        return len(self._left_out) + self._left_out_untracked

    def _on_sample(self, sample: Any) -> None:  # a Zenoh thread
        key = str(sample.key_expr)
        token = EntityToken.parse(key)
        if token is None or token.domain_id != self._domain_id:
            return
        with self._lock:
            self.changed_at = time.monotonic()
            if sample.kind == self._put:
                self._add(key, token)
                return
            self._remove(key, token)
            self._removed += 1
            trim = self._removed >= TRIM_AFTER_REMOVALS
            if trim:
                self._removed = 0
        if trim:  # a flood went away: so does the memory it took (here and in Zenoh's tables)
            release_freed_memory()

    def _remove(self, key: str, token: EntityToken) -> None:
        if key in self._tokens:
            del self._tokens[key]
            self._per_peer[token.zid] -= 1
            if not self._per_peer[token.zid]:
                del self._per_peer[token.zid]
            if token.kind is EntityKind.SUBSCRIPTION:
                topic = (token.name, token.dds_type)
                self._subscriptions[topic] -= 1
                if not self._subscriptions[topic]:
                    del self._subscriptions[topic]
        elif hash(key) in self._left_out:  # a token that was left out went away
            self._left_out.discard(hash(key))
        elif self._left_out_untracked:
            self._left_out_untracked -= 1

    def _add(self, key: str, token: EntityToken) -> None:
        # A token already kept, or already left out, is declared again when it reaches this
        # session by a second route (a direct link to its peer opening after the router's); a
        # left-out one admitted then, once room is made, would be counted twice.
        if key in self._tokens or hash(key) in self._left_out:
            return
        full = len(self._tokens) >= self._max_tokens
        if full or self._per_peer[token.zid] >= self._max_per_peer:
            if len(self._left_out) < 4 * self._max_tokens:
                self._left_out.add(hash(key))
            else:
                self._left_out_untracked += 1
            if not self._warned:
                self._warned = True
                log.warning(
                    "the ROS graph of domain %d has more entities than robomodel keeps (%s); "
                    "leaving the rest out, and listings say they are incomplete",
                    self._domain_id,
                    f"{self._max_tokens} in all"
                    if full
                    else f"{self._max_per_peer} for peer {escape_name(token.zid)}",
                )
            return
        self._tokens[key] = token
        self._per_peer[token.zid] += 1
        if token.kind is EntityKind.SUBSCRIPTION:
            self._subscriptions[(token.name, token.dds_type)] += 1

    def subscription_count(self, topic: str, dds_type: str) -> int:
        """Live subscriptions of ``topic`` with type ``dds_type``, as rmw_zenoh's
        ``GraphCache::publisher_count_matched_subscriptions`` counts a publisher's matches
        (graph_cache.cpp: the topic's subscriptions of the publisher's type whose QoS is not
        incompatible, and rmw_zenoh's ``rmw_qos_profile_check_compatible`` finds none so).
        Kept up to date as tokens come and go: reading it is a dict look-up."""
        return self._subscriptions.get((topic, dds_type), 0)

    def tokens(self) -> list[EntityToken]:
        """The tokens kept, as declared."""
        with self._lock:
            return list(self._tokens.values())

    def graph(self) -> Graph:
        """A snapshot of the entities kept; ``complete`` is False while any are left out."""
        with self._lock:
            tokens = list(self._tokens.values())
            left_out = self.left_out
        graph = Graph(complete=not left_out)
        for token in tokens:
            add_token(graph, token)
        return graph

    def close(self) -> None:
        undeclare_all(self._subscriber)
