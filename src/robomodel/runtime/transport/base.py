"""The transport interface. Implementations: in-process (default), Zenoh (rmw_zenoh's wire) and
ROS 1 (a master, XML-RPC and TCPROS).

A transport moves messages between publishers and subscriptions, requests and replies between
service clients and servers, and answers graph queries. It never calls user code on its own
threads: deliveries and service requests are posted to the context's executor, so callbacks and
handlers run on the spinning thread, one at a time. The exception is a callback wrapped in
:class:`OnReceivingThread`, which the ROS 1 transport calls on the thread that received the
message or request (rospy's threading), and the Zenoh transport's raw subscriptions on Zenoh's
receiving thread (a bridge's hand-off of payloads).

Nodes are named by their fully qualified name (``/ns/name``); every endpoint belongs to one.
Message and service types are the classes of :mod:`robomodel.runtime.msg`; how they travel (CDR,
ROS 1 serialization, no serialization at all) is the transport's business.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.qos import QoSProfile

__all__ = [
    "Deferred",
    "Endpoint",
    "Graph",
    "MessageInfo",
    "OnReceivingThread",
    "PublisherHandle",
    "RequestId",
    "ServiceCallError",
    "ServiceHandle",
    "ServiceHandler",
    "ServiceInfo",
    "SubscriptionHandle",
    "TopicInfo",
    "Transport",
    "request_being_served",
    "request_sent",
]


@dataclass(frozen=True, slots=True)
class RequestId:
    """A service request as rmw names it: the client's GID and the client's sequence number
    (what service introspection's ``ServiceEventInfo`` carries)."""

    client_gid: bytes
    sequence_number: int


request_being_served: ContextVar[RequestId | None] = ContextVar(
    "request_being_served", default=None
)
"""While a transport calls a service handler: the request's id, on a bus that has ids."""

request_sent: ContextVar[Callable[[RequestId], None] | None] = ContextVar(
    "request_sent", default=None
)
"""Set by a caller of ``call_service``: told the id of its request as it is sent, on a bus
that has ids (the call runs on the caller's thread, so the caller's context sees it)."""


class Deferred:
    """A response that comes later: a handler returns one, and calls :meth:`resolve` (on the
    executor's thread) when it has the answer, as an action server's ``get_result`` does."""

    __slots__ = ("_callbacks", "response")

    def __init__(self) -> None:
        self.response: Message | None = None
        self._callbacks: list[Callable[[Message], None]] = []

    def resolve(self, response: Message) -> None:
        if self.response is not None:
            return
        self.response = response
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(response)

    def then(self, callback: Callable[[Message], None]) -> None:
        """Run ``callback(response)`` once resolved (now, if it already is)."""
        if self.response is not None:
            callback(self.response)
        else:
            self._callbacks.append(callback)


class OnReceivingThread:
    """A subscription callback or service handler that the ROS 1 transport calls on the thread
    that received the message (a publisher connection's reader) or the request (a client
    connection's thread, or the in-process caller's), not on the executor's: rospy's threading,
    where handlers of concurrent calls run at once. A Zenoh raw subscription's callback so
    wrapped runs on Zenoh's receiving thread as each sample arrives, with no queue between (the
    subscription's depth bounds nothing) and no thread switch. It must be thread-safe, and a
    subscription's must return quickly (its connection reads nothing meanwhile). Other
    transports call it on the executor's thread, as any callback."""

    __slots__ = ("callback",)

    def __init__(self, callback: Callable[..., Any]) -> None:
        self.callback = callback

    def __call__(self, *args: Any) -> Any:
        return self.callback(*args)


ServiceHandler = Callable[[Any], Any]
"""A service's handler: the request (its type's ``Request`` message) in, the ``Response``
message (or a :class:`Deferred` of it) out, on the executor's thread."""


class ServiceCallError(RobomodelError):
    """A service call that got no answer, or an error instead of a response."""


@dataclass(frozen=True, slots=True)
class Endpoint:
    """A publisher or subscription (or a service server or client) as seen in the graph."""

    node: str
    topic: str
    type_name: str
    qos: QoSProfile = QoSProfile()
    type_hash: str = ""  # RIHS01, where the bus says it (rmw_zenoh's liveliness tokens)


@dataclass(frozen=True, slots=True)
class MessageInfo:
    """What a raw subscription learns about a sample besides its payload (rclpy's
    ``MessageInfo``): when it was published and received, and by whom.

    ``source_timestamp_ns`` is the publisher's clock at publication (rmw_zenoh's attachment
    carries it) and ``received_timestamp_ns`` this process's clock when the sample arrived,
    both nanoseconds since the Unix epoch.
    """

    source_timestamp_ns: int
    received_timestamp_ns: int
    publication_sequence_number: int = 0
    publisher_gid: bytes = b""


@dataclass
class TopicInfo:
    name: str
    types: set[str] = field(default_factory=set)
    publishers: list[Endpoint] = field(default_factory=list)
    subscribers: list[Endpoint] = field(default_factory=list)


@dataclass
class ServiceInfo:
    name: str
    types: set[str] = field(default_factory=set)
    servers: list[Endpoint] = field(default_factory=list)
    clients: list[Endpoint] = field(default_factory=list)


@dataclass
class Graph:
    """A snapshot of the nodes, topics and services a transport can see.

    ``complete`` is False when the transport knows that entities are missing (the graph could
    not be read in full, or a bound left some out): a listing of it must not look complete.
    """

    nodes: set[str] = field(default_factory=set)
    topics: dict[str, TopicInfo] = field(default_factory=dict)
    services: dict[str, ServiceInfo] = field(default_factory=dict)
    unreadable: str = ""  # why the graph could not be read (it is then empty), else ""
    complete: bool = True  # False: entries are missing (a bound cut the listing short)

    def add(self, kind: str, endpoint: Endpoint) -> None:
        """Record an endpoint; ``kind`` is ``pub``, ``sub``, ``srv`` or ``cli``."""
        self.nodes.add(endpoint.node)
        if kind in ("srv", "cli"):
            service = self.services.setdefault(endpoint.topic, ServiceInfo(endpoint.topic))
            service.types.add(endpoint.type_name)
            (service.servers if kind == "srv" else service.clients).append(endpoint)
            return
        info = self.topics.setdefault(endpoint.topic, TopicInfo(endpoint.topic))
        info.types.add(endpoint.type_name)
        (info.publishers if kind == "pub" else info.subscribers).append(endpoint)


class PublisherHandle(ABC):
    @abstractmethod
    def publish(self, msg: Message) -> None: ...

    @abstractmethod
    def destroy(self) -> None: ...

    @abstractmethod
    def subscription_count(self) -> int:
        """Subscriptions this publisher reaches now, as rclpy's
        ``Publisher.get_subscription_count()`` (rospy: ``get_num_connections()``). Cheap
        enough to ask at every physics step: no graph round trip."""


class SubscriptionHandle(ABC):
    @abstractmethod
    def destroy(self) -> None: ...

    def messages_lost(self) -> int:
        """Messages lost so far between the publishers and this subscription, by their
        sequence numbers (rmw_zenoh's MESSAGE_LOST); 0 on a bus that does not number them."""
        return 0


class ServiceHandle(ABC):
    @abstractmethod
    def destroy(self) -> None: ...


class Transport(ABC):
    """What a context needs from a transport."""

    name: str = ""

    def describe(self) -> str:
        """The graph this transport joined, for a command's first lines: the master, the domain,
        the router (shared machine-wide unless chosen otherwise)."""
        return f"bus: {self.name} (this process only)"

    @abstractmethod
    def register_node(self, node: str) -> Callable[[], None]:
        """Make node ``node`` (``/ns/name``) visible in the graph; returns an unregister function."""

    @abstractmethod
    def create_publisher(
        self, node: str, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> PublisherHandle: ...

    @abstractmethod
    def create_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[Message], None],
    ) -> SubscriptionHandle: ...

    @abstractmethod
    def create_service(
        self, node: str, name: str, srv_type: type[Service], handler: ServiceHandler
    ) -> ServiceHandle:
        """Answer requests to service ``name`` with ``handler`` (run on the executor's thread).

        A handler that raises answers the call with an error (the client's ServiceCallError
        says why) and the server goes on.
        """

    @abstractmethod
    def call_service(
        self,
        name: str,
        srv_type: type[Service],
        request: Message,
        timeout_s: float = 2.0,
        *,
        node: str | None = None,
    ) -> Message:
        """Call service ``name`` and return its response; ServiceCallError if none comes.

        Any thread may call, the executor's own included (a handler of this process is then
        run in place). ``node``, when given, is the calling node (for the graph).
        """

    @abstractmethod
    def graph(self, timeout_s: float = 1.0) -> Graph: ...

    @abstractmethod
    def close(self) -> None: ...
