"""The in-process transport: deterministic, no serialization, no threads."""

from __future__ import annotations

import collections
import functools
import logging
import queue
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TypeVar

from robomodel.errors import RobomodelError
from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport.base import (
    Deferred,
    Endpoint,
    Graph,
    PublisherHandle,
    ServiceCallError,
    ServiceHandle,
    ServiceHandler,
    SubscriptionHandle,
    Transport,
)

__all__ = ["InprocTransport"]

log = logging.getLogger("robomodel.runtime")

_M = TypeVar("_M", bound=Message)


@dataclass(eq=False)
class _Sub(SubscriptionHandle):
    transport: InprocTransport
    endpoint: Endpoint
    msg_type: type[Message]
    deliver: Callable[[Message], None]

    def destroy(self) -> None:
        subs = self.transport._subs.get(self.endpoint.topic, [])
        if self in subs:
            subs.remove(self)


@dataclass(eq=False)
class _Pub(PublisherHandle):
    transport: InprocTransport
    endpoint: Endpoint
    msg_type: type[Message]
    history: collections.deque[Message] = field(default_factory=collections.deque)

    def publish(self, msg: Message) -> None:
        if not isinstance(msg, self.msg_type):
            raise RobomodelError(
                f"publisher on {self.endpoint.topic} has type {self.msg_type.__typename__}, "
                f"got {type(msg).__typename__ or type(msg).__name__}"
            )
        if self.endpoint.qos.durability is Durability.TRANSIENT_LOCAL:
            self.history.append(msg)
            while len(self.history) > max(1, self.endpoint.qos.depth):
                self.history.popleft()
        self.transport._dispatch(self, msg)

    def subscription_count(self) -> int:
        """The subscriptions that :meth:`publish` delivers to (those of a compatible type)."""
        subs = self.transport._subs.get(self.endpoint.topic, ())
        return sum(self.transport._compatible(self.msg_type, s, self.endpoint.topic) for s in subs)

    def destroy(self) -> None:
        pubs = self.transport._pubs.get(self.endpoint.topic, [])
        if self in pubs:
            pubs.remove(self)


@dataclass(eq=False)
class _Srv(ServiceHandle):
    transport: InprocTransport
    endpoint: Endpoint
    srv_type: type[Service]
    handler: ServiceHandler

    def destroy(self) -> None:
        if self.transport._services.get(self.endpoint.topic) is self:
            del self.transport._services[self.endpoint.topic]


class InprocTransport(Transport):
    """Delivers the published object itself to every subscription of its class (treat as
    read-only); a subscription of another class of the same type (a client library's flavour)
    receives a copy of its own class, as a service's server and caller do."""

    name = "inproc"

    def __init__(self, executor: Executor) -> None:
        self._executor = executor
        self._subs: dict[str, list[_Sub]] = {}
        self._pubs: dict[str, list[_Pub]] = {}
        self._nodes: dict[str, int] = {}
        self._warned: set[tuple[str, str, str]] = set()
        self._services: dict[str, _Srv] = {}

    def _compatible(self, pub_type: type[Message], sub: _Sub, topic: str) -> bool:
        from robomodel.runtime.msg.typehash import same_type

        if same_type(pub_type, sub.msg_type):
            return True
        key = (topic, pub_type.__typename__, sub.msg_type.__typename__)
        if key not in self._warned:
            self._warned.add(key)
            log.warning(
                "topic %s is published as %s but subscribed as %s by %s; messages are not delivered",
                topic,
                pub_type.__typename__,
                sub.msg_type.__typename__,
                sub.endpoint.node,
            )
        return False

    def _dispatch(self, pub: _Pub, msg: Message) -> None:
        for sub in list(self._subs.get(pub.endpoint.topic, ())):
            if self._compatible(pub.msg_type, sub, pub.endpoint.topic):
                self._executor.post(functools.partial(sub.deliver, _as(msg, sub.msg_type)))

    def create_publisher(
        self, node: str, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> PublisherHandle:
        pub = _Pub(self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type)
        self._pubs.setdefault(topic, []).append(pub)
        return pub

    def create_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[Message], None],
    ) -> SubscriptionHandle:
        sub = _Sub(self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type, deliver)
        self._subs.setdefault(topic, []).append(sub)
        if qos.durability is Durability.TRANSIENT_LOCAL:
            for pub in self._pubs.get(topic, ()):
                if pub.history and self._compatible(pub.msg_type, sub, topic):
                    for msg in list(pub.history):
                        self._executor.post(functools.partial(deliver, _as(msg, msg_type)))
        return sub

    def register_node(self, node: str) -> Callable[[], None]:
        if node in self._nodes:
            log.warning("a node named %s already exists; names should be unique", node)
        self._nodes[node] = self._nodes.get(node, 0) + 1

        def unregister() -> None:
            count = self._nodes.get(node, 0) - 1
            if count > 0:
                self._nodes[node] = count
            else:
                self._nodes.pop(node, None)

        return unregister

    def graph(self, timeout_s: float = 1.0) -> Graph:
        """The graph now. Any thread may ask (a bridge's poller does) while the executor's
        adds and removes endpoints: each table is copied before it is read, a copy that
        runs whole under the GIL."""
        graph = Graph(nodes=set(self._nodes))
        for pubs in list(self._pubs.values()):
            for pub in list(pubs):
                graph.add("pub", pub.endpoint)
        for subs in list(self._subs.values()):
            for sub in list(subs):
                graph.add("sub", sub.endpoint)
        for srv in list(self._services.values()):
            graph.add("srv", srv.endpoint)
        return graph

    def create_service(
        self, node: str, name: str, srv_type: type[Service], handler: ServiceHandler
    ) -> ServiceHandle:
        if name in self._services:
            raise RobomodelError(f"service '{name}' is already offered in this process")
        srv = _Srv(self, Endpoint(node, name, srv_type.__typename__), srv_type, handler)
        self._services[name] = srv
        return srv

    def call_service(
        self,
        name: str,
        srv_type: type[Service],
        request: Message,
        timeout_s: float = 2.0,
        *,
        node: str | None = None,
    ) -> Message:
        from robomodel.runtime.msg.typehash import same_type

        srv = self._services.get(name)
        if srv is None:
            offered = ", ".join(sorted(self._services)) or "(none)"
            raise ServiceCallError(f"service '{name}' not found; services: {offered}")
        if srv.srv_type is not srv_type and not same_type(srv.srv_type, srv_type):
            raise ServiceCallError(
                f"service '{name}' has type {srv.srv_type.__typename__}, "
                f"called as {srv_type.__typename__}"
            )
        request = _as(request, srv.srv_type.Request)  # the server's class, the caller's back
        spinner = self._executor.spinner
        if spinner is None or spinner == threading.get_ident():
            answer = _resolved(name, _run_handler(name, srv.handler, request))
            return _as(answer, srv_type.Response)
        # Another thread (a spawner, as a separate process would be): the handler runs on the
        # spinning thread, as every other callback does, and this thread waits for it.
        box: queue.SimpleQueue[Message | ServiceCallError] = queue.SimpleQueue()

        def run() -> None:
            try:
                answer = _run_handler(name, srv.handler, request)
            except ServiceCallError as exc:
                box.put(exc)
                return
            if isinstance(answer, Deferred):
                answer.then(box.put)
            else:
                box.put(answer)

        self._executor.post(run)
        try:
            reply = box.get(timeout=timeout_s)
        except queue.Empty:
            raise ServiceCallError(f"service '{name}' did not answer in {timeout_s:g} s") from None
        if isinstance(reply, ServiceCallError):
            raise reply
        return _as(reply, srv_type.Response)

    def close(self) -> None:
        self._services.clear()
        self._subs.clear()
        self._pubs.clear()
        self._nodes.clear()


def _as(msg: _M, cls: type[_M]) -> _M:
    """``msg`` as a ``cls`` message: itself when it is one (no copy), else a copy through CDR
    (another class of the same type: a flavoured face's, or one built again)."""
    if isinstance(msg, cls):
        return msg
    from robomodel.runtime.msg import cdr

    return cdr.deserialize(cdr.serialize(msg), cls)


def _run_handler(name: str, handler: ServiceHandler, request: Message) -> Message | Deferred:
    try:
        answer: Message | Deferred = handler(request)
        return answer
    except Exception as exc:  # the server goes on; the caller learns why
        log_failure(log, "service %s failed", name)
        raise ServiceCallError(f"service '{name}' failed: {exc}") from None


def _resolved(name: str, answer: Message | Deferred) -> Message:
    if isinstance(answer, Deferred):
        if answer.response is None:
            raise ServiceCallError(
                f"service '{name}' answers later; call it from another thread than the spinner"
            )
        return answer.response
    return answer
