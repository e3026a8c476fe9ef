"""The master's registrations as rosmaster keeps them (rosmaster/registrations.py), bounded.

Transcribed semantics:

- each kind (publishers, subscribers, services, parameter subscribers) is a multimap
  ``key -> [(caller_id, caller_api), ...]``; a service key has one provider, the last to
  register, and its ``rosrpc://`` URI (``Registrations.register``/``service_api_map``);
- ``unregister`` removes ``(caller_id, caller_api)`` only if that exact pair is registered (a
  service: ``(caller_id, service_api)``), and says how many it removed, 0 or 1; an unknown
  registration is still a success, "the intended final state is reached";
- a node is known while it has any registration (``NodeRef.is_empty``): its last unregister
  forgets it, so ``lookupNode`` and ``rosnode list`` no longer show a node that ended cleanly;
- a node that registers again under the same name with another API replaces the old one: every
  registration of that name is dropped and the old API is told to shut down.

robomodel adds bounds rosmaster has not: registrations per node and in total (each holds names
of up to ``names.MAX_NAME_BYTES``), so one peer cannot grow the master without limit.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from enum import Enum

from robomodel.errors import RobomodelError

__all__ = [
    "MAX_REGISTRATIONS",
    "MAX_REGISTRATIONS_PER_NODE",
    "Kind",
    "RegistrationBoundError",
    "Registry",
]

MAX_REGISTRATIONS_PER_NODE = 4096
MAX_REGISTRATIONS = 65536


class Kind(Enum):
    PUBLISHER = "publisher"
    SUBSCRIBER = "subscriber"
    SERVICE = "service"
    PARAM_SUBSCRIBER = "parameter subscriber"


class RegistrationBoundError(RobomodelError):
    """A registration past the per-node or total bound."""


@dataclass
class _Node:
    """rosmaster's NodeRef: the node's API and its registrations, a reference count."""

    api: str
    keys: set[tuple[Kind, str]] = field(default_factory=set)


class Registry:
    """Every registration of one master (rosmaster's RegistrationManager). Not thread-safe:
    the master calls it under its lock, as rosmaster does under ``ps_lock``."""

    def __init__(
        self,
        *,
        per_node: int = MAX_REGISTRATIONS_PER_NODE,
        total: int = MAX_REGISTRATIONS,
    ) -> None:
        self.nodes: dict[str, _Node] = {}
        self.maps: dict[Kind, dict[str, list[tuple[str, str]]]] = {kind: {} for kind in Kind}
        self.service_apis: dict[str, tuple[str, str]] = {}  # service -> (caller_id, rosrpc URI)
        self._per_node, self._total = per_node, total
        self._count = 0

    def register(
        self, kind: Kind, key: str, caller_id: str, caller_api: str, service_api: str = ""
    ) -> str | None:
        """Record the registration; the API of a node it replaced (to be told to shut down),
        or None. RegistrationBoundError past a bound, with nothing changed."""
        node = self.nodes.get(caller_id)
        replaced = node.api if node is not None and node.api != caller_api else None
        if replaced is not None:
            self._unregister_all(caller_id)
            node = None
        if node is None or (kind, key) not in node.keys:
            self._check_bounds(kind, key, caller_id, 0 if node is None else len(node.keys))
        if node is None:
            node = self.nodes[caller_id] = _Node(caller_api)
        if (kind, key) not in node.keys:
            node.keys.add((kind, key))
            self._count += 1
        providers = self.maps[kind].setdefault(key, [])
        if kind is Kind.SERVICE:
            self._drop_service_provider(key)
            providers = self.maps[kind][key] = []
            self.service_apis[key] = (caller_id, service_api)
        if (caller_id, caller_api) not in providers:
            providers.append((caller_id, caller_api))
        return replaced

    def _check_bounds(self, kind: Kind, key: str, caller_id: str, held: int) -> None:
        if held >= self._per_node:
            raise RegistrationBoundError(
                f"{caller_id} already holds {held} registrations (at most {self._per_node} "
                f"per node); {kind.value} of [{key}] refused"
            )
        if self._count >= self._total:
            raise RegistrationBoundError(
                f"the master holds {self._count} registrations (at most {self._total}); "
                f"{kind.value} of [{key}] by {caller_id} refused"
            )

    def _drop_service_provider(self, service: str) -> None:
        """A service has one provider: the previous one no longer holds it."""
        previous = self.service_apis.pop(service, None)
        if previous is not None:
            self._forget(previous[0], Kind.SERVICE, service)

    def unregister(
        self, kind: Kind, key: str, caller_id: str, caller_api: str = "", service_api: str = ""
    ) -> int:
        """Remove one registration if it is exactly the one registered: 1, else 0."""
        if caller_id not in self.nodes:
            return 0
        if kind is Kind.SERVICE:
            if self.service_apis.get(key) != (caller_id, service_api):
                return 0
            del self.service_apis[key]
            self.maps[kind].pop(key, None)
        else:
            providers = self.maps[kind].get(key, [])
            if (caller_id, caller_api) not in providers:
                return 0
            providers.remove((caller_id, caller_api))
            if not providers:
                del self.maps[kind][key]
        self._forget(caller_id, kind, key)
        return 1

    def _forget(self, caller_id: str, kind: Kind, key: str) -> None:
        node = self.nodes.get(caller_id)
        if node is None or (kind, key) not in node.keys:
            return
        node.keys.discard((kind, key))
        self._count -= 1
        if not node.keys:
            del self.nodes[caller_id]

    def _unregister_all(self, caller_id: str) -> None:
        for kind, entries in self.maps.items():
            for key in [
                k for k, providers in entries.items() if any(caller_id == p[0] for p in providers)
            ]:
                entries[key] = [p for p in entries[key] if p[0] != caller_id]
                if not entries[key]:
                    del entries[key]
                if kind is Kind.SERVICE:
                    self.service_apis.pop(key, None)
        node = self.nodes.pop(caller_id, None)
        if node is not None:
            self._count -= len(node.keys)

    def apis(self, kind: Kind, key: str) -> list[str]:
        return [api for _, api in self.maps[kind].get(key, [])]

    def providers(self, kind: Kind) -> Iterator[tuple[str, list[tuple[str, str]]]]:
        yield from self.maps[kind].items()

    def state(self, kind: Kind) -> list[list[object]]:
        """getSystemState's ``[[key, [caller_id, ...]], ...]``, sorted by key."""
        return [[k, [p[0] for p in v]] for k, v in sorted(self.maps[kind].items())]

    def has_key(self, key: str) -> bool:
        """Whether any node publishes or subscribes ``key``."""
        return key in self.maps[Kind.PUBLISHER] or key in self.maps[Kind.SUBSCRIBER]
