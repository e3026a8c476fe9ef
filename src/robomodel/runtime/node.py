"""Nodes: publishers, subscriptions, services, timers, a clock and parameters, as in rclpy."""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from robomodel.runtime.clock import Clock, SimClock
from robomodel.runtime.executor import Timer
from robomodel.runtime.msg import Clock as ClockMsg
from robomodel.runtime.msg import Message, Time
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.names import (
    apply_remappings,
    expand_topic_name,
    fully_qualified_node_name,
    validate_namespace,
    validate_node_name,
)
from robomodel.runtime.params import ParameterStore, SetResult
from robomodel.runtime.qos import QoSProfile, as_qos
from robomodel.runtime.transport.base import (
    PublisherHandle,
    ServiceHandle,
    ServiceHandler,
    SubscriptionHandle,
)

if TYPE_CHECKING:
    from robomodel.runtime.context import Context
    from robomodel.runtime.type_descriptions import TypeDescriptionService

__all__ = ["Client", "Node", "Publisher", "ServiceServer", "Subscription"]

M = TypeVar("M", bound=Message)


@dataclass(eq=False)
class Publisher(Generic[M]):
    """Publishes messages of one type on one (fully expanded) topic."""

    topic: str
    msg_type: type[M]
    qos: QoSProfile
    _handle: PublisherHandle
    _release: Callable[[], None] | None = None  # the node's type cache no longer counts it

    def publish(self, msg: M) -> None:
        self._handle.publish(msg)

    def get_subscription_count(self) -> int:
        """Subscriptions matched now (rclpy's name; rospy's ``get_num_connections()``): this
        process's on the in-process bus, the graph's subscription tokens of the topic and
        type on Zenoh (as rmw_zenoh counts them), the TCPROS connections on ROS 1."""
        return self._handle.subscription_count()

    def destroy(self) -> None:
        self._handle.destroy()
        if self._release is not None:
            self._release()
            self._release = None


@dataclass(eq=False)
class Subscription(Generic[M]):
    topic: str
    msg_type: type[M]
    qos: QoSProfile
    _handle: SubscriptionHandle
    _release: Callable[[], None] | None = None  # the node's type cache no longer counts it

    def get_messages_lost(self) -> int:
        """Messages lost so far, by the publishers' sequence numbers (rmw_zenoh's
        MESSAGE_LOST event counts these); 0 on a bus that does not number them."""
        return self._handle.messages_lost()

    def destroy(self) -> None:
        self._handle.destroy()
        if self._release is not None:
            self._release()
            self._release = None


@dataclass(eq=False)
class ServiceServer:
    """A service offered by a node."""

    name: str
    srv_type: type[Service]
    _handle: ServiceHandle
    _release: Callable[[], None] | None = None  # the node's type cache no longer counts it

    def destroy(self) -> None:
        self._handle.destroy()
        if self._release is not None:
            self._release()
            self._release = None


@dataclass(eq=False)
class Client:
    """Calls one service of a given type (blocking, from any thread)."""

    node: Node
    name: str
    srv_type: type[Service]

    def call(self, request: Message | None = None, timeout_s: float = 2.0) -> Any:
        """The response; ServiceCallError if none comes within ``timeout_s``."""
        return self.node.context.transport.call_service(
            self.name,
            self.srv_type,
            request if request is not None else self.srv_type.Request(),
            timeout_s,
            node=self.node.fully_qualified_name,
        )


class Node:
    """A ROS-style node living in a :class:`~robomodel.runtime.context.Context`.

    Create it with ``context.create_node(name, ...)``. Every node declares ``use_sim_time``
    (default False); when true its clock follows /clock, as in ROS 2. Its log lines go to
    ``/rosout`` (:mod:`robomodel.runtime.rosout`) unless ``enable_rosout`` is False (rclpy's
    option; ROS 1's rosout node itself runs without).
    """

    def __init__(
        self,
        context: Context,
        name: str,
        namespace: str = "/",
        *,
        parameter_overrides: Mapping[str, Any] | None = None,
        remappings: Mapping[str, str] | None = None,
        allow_undeclared_parameters: bool = False,
        enable_rosout: bool = True,
    ) -> None:
        self.context = context
        self.name = validate_node_name(name)
        self.namespace = validate_namespace(namespace)
        self.fully_qualified_name = fully_qualified_node_name(self.name, self.namespace)
        self._remappings = dict(remappings or {})
        self.parameters = ParameterStore(
            self.fully_qualified_name,
            parameter_overrides,
            allow_undeclared=allow_undeclared_parameters,
        )
        self._publishers: list[Publisher[Any]] = []
        self._subscriptions: list[Subscription[Any]] = []
        self._services: list[ServiceServer] = []
        self._timers: list[Timer] = []
        self._sim_clock: SimClock | None = None
        self._clock_sub: Subscription[ClockMsg] | None = None
        self.logger = logging.getLogger(
            f"robomodel.node{self.fully_qualified_name.replace('/', '.')}"
        )
        self._unregister = context.transport.register_node(self.fully_qualified_name)
        from robomodel.runtime.param_services import ParameterServices

        self._type_cache: TypeDescriptionService | None = None
        if getattr(context, "bus", "") != "ros1":  # rcl's, not on a ROS 1 graph
            from robomodel.runtime.type_descriptions import TypeDescriptionService

            self._type_cache = TypeDescriptionService(self)
        self._parameter_services = ParameterServices(self)
        from robomodel.runtime.rosout import Rosout

        self.rosout: Rosout | None = Rosout(self) if enable_rosout else None
        use_sim_time = self.declare_parameter("use_sim_time", False)
        self._set_sim_time(bool(use_sim_time))
        self.parameters.add_post_set_callback(self._on_parameters)

    # -- names --------------------------------------------------------------------------
    def resolve_topic_name(self, topic: str) -> str:
        """Expand and remap a topic name for this node."""
        expanded = expand_topic_name(topic, self.name, self.namespace)
        return apply_remappings(expanded, self._remappings, self.name, self.namespace)

    # -- communication ------------------------------------------------------------------
    def create_publisher(
        self, msg_type: type[M], topic: str, qos: QoSProfile | int = 10
    ) -> Publisher[M]:
        profile = as_qos(qos)
        name = self.resolve_topic_name(topic)
        handle = self.context.transport.create_publisher(
            self.fully_qualified_name, name, msg_type, profile
        )
        publisher = Publisher(name, msg_type, profile, handle, self._uses(msg_type))
        self._publishers.append(publisher)
        return publisher

    def create_subscription(
        self,
        msg_type: type[M],
        topic: str,
        callback: Callable[[M], None],
        qos: QoSProfile | int = 10,
    ) -> Subscription[M]:
        profile = as_qos(qos)
        name = self.resolve_topic_name(topic)
        handle = self.context.transport.create_subscription(
            self.fully_qualified_name,
            name,
            msg_type,
            profile,
            callback,  # type: ignore[arg-type]
        )
        subscription = Subscription(name, msg_type, profile, handle, self._uses(msg_type))
        self._subscriptions.append(subscription)
        return subscription

    def create_service(
        self, srv_type: type[Service], name: str, handler: ServiceHandler
    ) -> ServiceServer:
        """Answer requests to service ``name`` (``~/x`` and relative names expand as topics do)."""
        resolved = self.resolve_topic_name(name)
        handle = self.context.transport.create_service(
            self.fully_qualified_name, resolved, srv_type, handler
        )
        server = ServiceServer(resolved, srv_type, handle, self._uses(srv_type))
        self._services.append(server)
        return server

    def create_client(self, srv_type: type[Service], name: str) -> Client:
        self._uses(srv_type)
        return Client(self, self.resolve_topic_name(name), srv_type)

    def _uses(self, kind: type[Message] | type[Service]) -> Callable[[], None] | None:
        """Enter ``kind`` in the node's type cache, which ``~/get_type_description`` answers
        from (rcl registers the type of every publisher, subscription, service and client, and
        unregisters it when the last of them is destroyed); returns the unregistering call."""
        if self._type_cache is None:
            return None
        return self._type_cache.register(kind)

    def create_timer(self, period_s: float, callback: Callable[[], None]) -> Timer:
        """Call ``callback`` every ``period_s`` seconds of this node's clock."""
        timer = self.context.executor.add_timer(period_s, callback, self.get_clock())
        self._timers.append(timer)
        return timer

    # -- time ---------------------------------------------------------------------------
    def get_clock(self) -> Clock:
        return self._sim_clock if self._sim_clock is not None else self.context.clock

    def now(self) -> Time:
        """The node's current time as a ``builtin_interfaces/Time`` message."""
        ns = self.get_clock().now_ns()
        return Time(ns // 1_000_000_000, ns % 1_000_000_000)

    def _set_sim_time(self, enabled: bool) -> None:
        if enabled and self._sim_clock is None:
            clock = SimClock()
            self._sim_clock = clock
            for timer in self._timers:
                timer.clock = clock
                timer.reset()
            self._clock_sub = self.create_subscription(
                ClockMsg, "/clock", lambda msg: clock.update(msg.clock.to_seconds()), 10
            )
        elif not enabled and self._sim_clock is not None:
            self._sim_clock = None
            if self._clock_sub is not None:
                self._clock_sub.destroy()
                self._clock_sub = None
            for timer in self._timers:
                timer.clock = self.context.clock
                timer.reset()

    # -- parameters ---------------------------------------------------------------------
    def declare_parameter(
        self, name: str, default: Any, *, description: str = "", read_only: bool = False
    ) -> Any:
        value = self.parameters.declare(name, default, description=description, read_only=read_only)
        self._parameter_services.publish_event(new={name: value})
        return value

    def get_parameter(self, name: str) -> Any:
        return self.parameters.get(name)

    def set_parameters(self, values: Mapping[str, Any]) -> SetResult:
        return self.parameters.set(values)

    def _on_parameters(self, changed: Mapping[str, Any]) -> None:
        if "use_sim_time" in changed:
            self._set_sim_time(bool(changed["use_sim_time"]))
        self._parameter_services.publish_event(changed=changed)

    # -- lifetime -------------------------------------------------------------------------
    def destroy(self) -> None:
        if self.rosout is not None:
            self.rosout.close()
            self.rosout = None
        for timer in self._timers:
            timer.cancel()
        for publisher in self._publishers:
            publisher.destroy()
        for subscription in self._subscriptions:
            subscription.destroy()
        for service in self._services:
            service.destroy()
        self._publishers.clear()
        self._subscriptions.clear()
        self._services.clear()
        self._unregister()
