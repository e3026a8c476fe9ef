"""The Zenoh transport in rmw_zenoh's wire format: real ROS 2 nodes running with
``RMW_IMPLEMENTATION=rmw_zenoh_cpp`` and robomodel processes are peers of one graph.

- Topics and services: keys ``<domain>/<name>/<DDS type>/<RIHS01 hash>``, CDR payloads and
  rmw_zenoh's attachments (see :mod:`robomodel.runtime.transport.rmw_zenoh`).
- Graph: a liveliness token per node (``NN``), publisher (``MP``), subscription (``MS``),
  service (``SS``) and client (``SC``), numbered from one counter per session as rmw_zenoh's
  context numbers them; ``graph()`` reads everyone's.
- Session: rmw_zenoh's configuration and environment (``ZENOH_SESSION_CONFIG_URI``,
  ``ZENOH_CONFIG_OVERRIDE``, ``ROS_DOMAIN_ID``), the router at ``tcp/localhost:7447``, and a
  detached ``robomodel router`` started there when none answers (see ``_zenoh_session``).
- ``ROS_DISTRO=humble`` keys types by ``TypeHashNotSupported``, as Humble's rmw_zenoh does
  (Humble has no type hashes).
"""

from __future__ import annotations

import itertools
import os
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from robomodel._escape import escape_name
from robomodel._heap import large_buffers_from_the_heap
from robomodel.errors import RobomodelError
from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.msg.typehash import dds_type_name, type_hash
from robomodel.runtime.qos import QoSProfile
from robomodel.runtime.transport._domain_id import domain_id_from_env
from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport._zenoh_common import close_session, log, undeclare_all
from robomodel.runtime.transport._zenoh_endpoints import ZenohPublisher, ZenohSubscription
from robomodel.runtime.transport._zenoh_graph import GraphCache
from robomodel.runtime.transport._zenoh_local import LocalDelivery
from robomodel.runtime.transport._zenoh_services import ServiceClient, ZenohService
from robomodel.runtime.transport._zenoh_session import open_session
from robomodel.runtime.transport.base import (
    Deferred,
    Endpoint,
    Graph,
    MessageInfo,
    PublisherHandle,
    ServiceCallError,
    ServiceHandle,
    ServiceHandler,
    SubscriptionHandle,
    Transport,
)
from robomodel.runtime.transport.rmw_zenoh import EntityKind, EntityToken, qos_to_key, topic_key

DECLARATIONS_SETTLE_S = 0.25
"""How long after opening an empty graph is asked again (see ``ZenohTransport.graph``)."""

__all__ = ["DECLARATIONS_SETTLE_S", "MAX_WARNINGS", "ZenohTransport", "domain_id_from_env"]

MAX_WARNINGS = 256
HUMBLE_TYPE_HASH = "TypeHashNotSupported"


def split_node_name(node: str) -> tuple[str, str]:
    """``/ns/name`` -> (``/ns``, ``name``); ``/name`` -> (``/``, ``name``)."""
    namespace, _, name = node.rpartition("/")
    return namespace or "/", name


@dataclass
class _NodeRecord:
    node_id: int
    token: EntityToken
    handle: object
    count: int = 1


class ZenohTransport(Transport):
    """ROS 2 over Zenoh, as rmw_zenoh_cpp (see the module docstring)."""

    name = "zenoh"

    def __init__(
        self,
        executor: Executor,
        *,
        domain_id: int | None = None,
        connect: Sequence[str] = (),
        listen: Sequence[str] = (),
    ) -> None:
        self.executor = executor
        self.domain_id = domain_id_from_env() if domain_id is None else domain_id
        large_buffers_from_the_heap()  # each payload is copied into and out of Zenoh
        opened = open_session(connect, listen)
        self.session = opened.session
        self.is_router = opened.is_router
        self._opened = opened
        self.zid = str(self.session.zid())
        self._opened_at = time.monotonic()
        self.ids = itertools.count()  # rmw_zenoh: one counter per context, nodes included
        self.humble = os.environ.get("ROS_DISTRO", "") == "humble"
        self._lock = threading.Lock()
        self._nodes: dict[str, _NodeRecord] = {}
        self._services: dict[str, ZenohService] = {}
        self._variants: list[ZenohService] = []  # earlier layouts of offered services
        self._clients: dict[tuple[str, str, type[Service]], ServiceClient] = {}
        self._warned: set[tuple[str, ...]] = set()
        self._warnings_capped = False
        self._graph = GraphCache(self.session, self.domain_id)
        self.local = LocalDelivery()  # this session's samples to its on-arrival subscriptions

    # -- naming ---------------------------------------------------------------------------------
    def type_hash(self, kind: type[Message] | type[Service]) -> str:
        return HUMBLE_TYPE_HASH if self.humble else type_hash(kind)

    def data_key(self, name: str, kind: type[Message] | type[Service]) -> str:
        return topic_key(
            self.domain_id, name, dds_type_name(kind.__typename__), self.type_hash(kind)
        )

    def _node(self, node: str) -> _NodeRecord:
        record = self._nodes.get(node)
        if record is None:  # an endpoint of a node never registered: give it a token
            self.register_node(node)
            record = self._nodes[node]
        return record

    def entity_token(
        self, endpoint: Endpoint, kind: EntityKind, type_: type[Message] | type[Service]
    ) -> EntityToken:
        node = self._node(endpoint.node).token
        return EntityToken(
            self.domain_id,
            self.zid,
            node.node_id,
            next(self.ids),
            kind,
            node.namespace,
            node.node_name,
            name=endpoint.topic,
            dds_type=dds_type_name(type_.__typename__),
            type_hash=self.type_hash(type_),
            qos=qos_to_key(endpoint.qos),
        )

    def warn_once(self, key: tuple[str, ...], fmt: str, *args: object) -> None:
        """Log a warning once per ``key``. Keys come partly from other processes, so at most
        ``MAX_WARNINGS`` are remembered; past that one line says the rest are suppressed, and
        memory stays bounded however many distinct names a peer sends. Text arguments are
        printed with control characters escaped (``escape_name``): they can be a peer's."""
        if key in self._warned:
            return
        if len(self._warned) >= MAX_WARNINGS:
            if not self._warnings_capped:
                self._warnings_capped = True
                log.warning(
                    "more than %d distinct bus warnings; suppressing the rest", MAX_WARNINGS
                )
            return
        self._warned.add(key)
        log.warning(fmt, *(escape_name(a) if isinstance(a, str) else a for a in args))

    # -- nodes ----------------------------------------------------------------------------------
    def register_node(self, node: str) -> Callable[[], None]:
        with self._lock:
            record = self._nodes.get(node)
            if record is not None:
                log.warning("a node named %s already exists; names should be unique", node)
                record.count += 1
            else:
                node_id = next(self.ids)
                namespace, name = split_node_name(node)
                token = EntityToken(
                    self.domain_id, self.zid, node_id, node_id, EntityKind.NODE, namespace, name
                )
                handle = self.session.liveliness().declare_token(token.key())
                self._nodes[node] = _NodeRecord(node_id, token, handle)

        def unregister() -> None:
            with self._lock:
                current = self._nodes.get(node)
                if current is None:
                    return
                current.count -= 1
                if current.count == 0:
                    del self._nodes[node]
                    undeclare_all(current.handle)

        return unregister

    # -- topics ---------------------------------------------------------------------------------
    def create_publisher(
        self, node: str, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> PublisherHandle:
        return ZenohPublisher(self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type)

    def create_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[Message], None],
    ) -> SubscriptionHandle:
        endpoint = Endpoint(node, topic, msg_type.__typename__, qos)
        return ZenohSubscription(self, endpoint, msg_type, deliver)

    def create_raw_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[bytes, MessageInfo], None],
    ) -> SubscriptionHandle:
        """A subscription that hands over each sample's CDR payload undecoded, with its
        :class:`MessageInfo` (publish and receive time), on the executor's thread. The
        payload is not checked against ``msg_type``, which only names the topic's key.
        A ``deliver`` wrapped in :class:`OnReceivingThread` runs on Zenoh's receiving thread
        as each sample arrives, with no queue (``qos.depth`` bounds nothing): for a quick,
        thread-safe one, such as a bridge's hand-off to its clients' queues. Such a one gets
        the samples of this session's publishers from them, on the publishing thread, once
        other processes have them (:mod:`._zenoh_local`)."""
        endpoint = Endpoint(node, topic, msg_type.__typename__, qos)
        return ZenohSubscription(self, endpoint, msg_type, None, raw_deliver=deliver)

    # -- services -------------------------------------------------------------------------------
    def create_service(
        self, node: str, name: str, srv_type: type[Service], handler: ServiceHandler
    ) -> ServiceHandle:
        offered = self._services.get(name)
        variant = offered is not None and offered.srv_type.__typename__ == srv_type.__typename__
        if offered is not None and (not variant or self.data_key(name, srv_type) in self._keys()):
            raise RobomodelError(f"service '{name}' is already offered in this process")
        service = ZenohService(self, Endpoint(node, name, srv_type.__typename__), srv_type, handler)
        if variant:  # another layout of the same type (another hash, so another key)
            self._variants.append(service)
        else:
            self._services[name] = service
        return service

    def _keys(self) -> set[str]:
        return {s.key for s in [*self._services.values(), *self._variants]}

    def forget_service(self, service: ZenohService) -> None:
        if self._services.get(service.endpoint.topic) is service:
            del self._services[service.endpoint.topic]
        if service in self._variants:
            self._variants.remove(service)

    def call_service(
        self,
        name: str,
        srv_type: type[Service],
        request: Message,
        timeout_s: float = 2.0,
        *,
        node: str | None = None,
    ) -> Message:
        local = self._services.get(name)
        if (
            local is not None
            and local.srv_type is srv_type
            and self.executor.spinner in (None, threading.get_ident())
        ):
            # This thread runs the executor: a query would wait for itself. Run it in place.
            return _in_place(name, local.handler, request)
        # A caller without a node (a command line, a launch file's helper) is a node of its own
        # for the graph, as ros2cli's requester node is: its client has an SC token and a GID
        # derived from it, so ROS 2's graph tools list it.
        node = node or f"/robomodel_client_{os.getpid()}"
        key = (node, name, srv_type)  # the class: layouts of one type name differ in hash
        if node not in self._nodes:  # its token first: register_node takes the lock below
            self._node(node)
        with self._lock:
            client = self._clients.get(key)
            if client is None:
                client = self._clients[key] = ServiceClient(self, name, srv_type, node)
        return client.call(request, timeout_s)

    # -- graph and lifetime ---------------------------------------------------------------------
    def describe(self) -> str:
        opened = self._opened
        if opened.is_router:
            where = "this process is the router"
        elif opened.routers:
            how = (
                "started for this process; `robomodel router --stop` ends it"
                if (opened.started_router)
                else "running"
            )
            where = f"router {', '.join(opened.routers)} ({how})"
        else:
            where = "no router"
        return (
            f"bus: zenoh (rmw_zenoh), domain {self.domain_id} (ROS_DOMAIN_ID or --domain-id), "
            f"{where}"
        )

    def graph(self, timeout_s: float = 1.0) -> Graph:
        """Everyone's entities in this domain.

        A session that has just linked up with a router has not yet received the router's
        liveliness declarations (some milliseconds), and a query sent before then comes back
        empty at once, which made a second launch miss the first one's parameter server. While
        the session is that young and linked, an answer with none but its own nodes is asked
        again, for at most ``timeout_s``."""
        deadline = time.monotonic() + timeout_s
        graph = self._graph.graph()
        while self._stale(graph) and self.linked() and time.monotonic() < deadline:
            time.sleep(0.005)
            graph = self._graph.graph()
        return graph

    def _stale(self, graph: Graph) -> bool:
        """An answer that lacks this process's own nodes (their tokens went to a router in
        another process and the query overtook them), or only those while young."""
        own = set(self._nodes)
        return not own <= graph.nodes or (len(graph.nodes) <= len(own) and self._young())

    @property
    def graph_cache(self) -> GraphCache:
        """The domain's tokens as they come and go (what publishers count matches in)."""
        return self._graph

    def graph_quiet_s(self) -> float:
        """Seconds since the last token of the domain came or went."""
        return time.monotonic() - self._graph.changed_at

    def _young(self) -> bool:
        return time.monotonic() - self._opened_at < DECLARATIONS_SETTLE_S

    def linked(self) -> bool:
        """Whether this session is linked to a router or another peer."""
        info = self.session.info
        return bool(list(info.routers_zid()) or list(info.peers_zid()))

    def close(self) -> None:
        close_session(self.session, before=self._undeclare_everything)

    def _undeclare_everything(self) -> None:
        for service in [*self._services.values(), *self._variants]:
            service.destroy()
        for client in self._clients.values():
            client.destroy()
        self._clients.clear()
        for record in self._nodes.values():
            undeclare_all(record.handle)
        self._nodes.clear()
        self._graph.close()


def _in_place(name: str, handler: ServiceHandler, request: Message) -> Message:
    try:
        answer: Message | Deferred = handler(request)
    except Exception as exc:
        log_failure(log, "service %s failed", name)
        raise ServiceCallError(f"service '{name}' failed: {exc}") from None
    if isinstance(answer, Deferred):
        if answer.response is None:
            raise ServiceCallError(f"service '{name}' answers later; call it from another thread")
        return answer.response
    return answer
