"""The transport interface. Implementations: in-process (default) and Zenoh.

A transport moves messages between publishers and subscriptions and answers graph and parameter
queries. It never calls user code itself: deliveries are posted to the context's executor, so
callbacks run on the spinning thread, one at a time.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from robomodel.runtime.msg import Message
from robomodel.runtime.qos import QoSProfile

__all__ = [
    "Endpoint",
    "Graph",
    "ParameterHandler",
    "PublisherHandle",
    "SubscriptionHandle",
    "TopicInfo",
    "Transport",
]

ParameterHandler = Callable[[dict[str, Any]], dict[str, Any]]


@dataclass(frozen=True, slots=True)
class Endpoint:
    """A publisher or subscription as seen in the graph."""

    node: str
    topic: str
    type_name: str
    qos: QoSProfile = QoSProfile()


@dataclass
class TopicInfo:
    name: str
    types: set[str] = field(default_factory=set)
    publishers: list[Endpoint] = field(default_factory=list)
    subscribers: list[Endpoint] = field(default_factory=list)


@dataclass
class Graph:
    """A snapshot of the nodes and topics a transport can see."""

    nodes: set[str] = field(default_factory=set)
    topics: dict[str, TopicInfo] = field(default_factory=dict)
    services: set[str] = field(default_factory=set)

    def add(self, kind: str, endpoint: Endpoint) -> None:
        self.nodes.add(endpoint.node)
        info = self.topics.setdefault(endpoint.topic, TopicInfo(endpoint.topic))
        info.types.add(endpoint.type_name)
        (info.publishers if kind == "pub" else info.subscribers).append(endpoint)


class PublisherHandle(ABC):
    @abstractmethod
    def publish(self, msg: Message) -> None: ...

    @abstractmethod
    def destroy(self) -> None: ...


class SubscriptionHandle(ABC):
    @abstractmethod
    def destroy(self) -> None: ...


class Transport(ABC):
    """What a context needs from a transport."""

    name: str = ""

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
    def register_node(self, node: str, handler: ParameterHandler) -> Callable[[], None]:
        """Make a node visible and answer its parameter calls; returns an unregister function."""

    @abstractmethod
    def graph(self, timeout_s: float = 1.0) -> Graph: ...

    @abstractmethod
    def call_parameters(
        self, node: str, request: dict[str, Any], timeout_s: float = 2.0
    ) -> dict[str, Any]: ...

    def register_service(self, name: str, handler: ParameterHandler) -> Callable[[], None]:
        """Answer JSON-like requests to service ``name``; returns an unregister function.

        The handler runs on the executor's thread, like a subscription callback.
        """
        raise NotImplementedError(f"the {self.name} transport has no services")

    def call_service(
        self, name: str, request: dict[str, Any], timeout_s: float = 2.0
    ) -> dict[str, Any]:
        """Call service ``name`` with ``request`` and return its response."""
        raise NotImplementedError(f"the {self.name} transport has no services")

    @abstractmethod
    def close(self) -> None: ...
