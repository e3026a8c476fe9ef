"""The ROS 1 transport: robomodel nodes as ROS 1 nodes of the master at ``ROS_MASTER_URI``.

Each node gets a slave API and a TCPROS server (:mod:`.ros1.node_endpoint`) and registers its
publishers, subscribers and services with the master, so that rostopic, rosnode, rosservice,
rosbag and rviz see them and real ROS 1 nodes connect to them. Messages travel in ROS 1's
serialization with the md5sums of the ROS 1 definitions (:mod:`.ros1.ros1_types`). A latched
topic is a publisher with transient-local durability. Services without a ROS 1 counterpart (the
ROS 2 parameter services every robomodel node has, lifecycle and action services) stay inside
the process. A node's ``/rosout`` publisher is its own (:mod:`robomodel.runtime.rosout`), as
in roscpp and rospy.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable
from typing import Any

from robomodel._heap import large_buffers_from_the_heap
from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.transport.base import (
    Deferred,
    Endpoint,
    Graph,
    OnReceivingThread,
    PublisherHandle,
    ServiceCallError,
    ServiceHandle,
    ServiceHandler,
    SubscriptionHandle,
    Transport,
)
from robomodel.runtime.transport.ros1.master import master_answers
from robomodel.runtime.transport.ros1.names import bind_host, http_uri, master_uri
from robomodel.runtime.transport.ros1.node_endpoint import NodeEndpoint
from robomodel.runtime.transport.ros1.publication import Publication
from robomodel.runtime.transport.ros1.ros1_types import (
    Ros1TypeError,
    robomodel_type_for,
    ros1_service_type,
    ros1_type,
)
from robomodel.runtime.transport.ros1.services import ServiceServer, call_service
from robomodel.runtime.transport.ros1.subscription import Subscription
from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call, log

__all__ = ["Ros1Transport"]


class _Handle(PublisherHandle, SubscriptionHandle, ServiceHandle):
    def __init__(
        self,
        destroy: Callable[[], None],
        publish: Callable[[Message], None] | None = None,
        count: Callable[[], int] | None = None,
    ) -> None:
        self._destroy = destroy
        self._publish = publish
        self._count = count
        self._done = False

    def publish(self, msg: Message) -> None:
        if self._publish is not None and not self._done:
            self._publish(msg)

    def subscription_count(self) -> int:
        return 0 if self._count is None or self._done else self._count()

    def destroy(self) -> None:
        if not self._done:
            self._done = True
            self._destroy()


class Ros1Transport(Transport):
    name = "ros1"

    def __init__(self, executor: Executor, *, master: str | None = None) -> None:
        self.executor = executor
        self.master_uri = master_uri(master)
        if not master_answers(self.master_uri, timeout_s=2.0):
            raise Ros1WireError(
                f"no ROS 1 master answers at {self.master_uri}; start roscore (or `robomodel "
                "master`), or set ROS_MASTER_URI to where it runs"
            )
        self._bind = bind_host()
        large_buffers_from_the_heap()  # each message is copied into and out of its connections
        self._lock = threading.Lock()
        self._nodes: dict[str, NodeEndpoint] = {}
        self._local: dict[str, tuple[type[Service], ServiceHandler]] = {}
        self._local_topics: dict[tuple[str, type[Message]], list[Callable[[Message], None]]] = {}

    # -- nodes ------------------------------------------------------------------------------
    def _endpoint(self, node: str) -> NodeEndpoint:
        with self._lock:
            endpoint = self._nodes.get(node)
            if endpoint is None:
                endpoint = self._nodes[node] = NodeEndpoint(node, self.master_uri, self._bind)
        return endpoint

    def register_node(self, node: str) -> Callable[[], None]:
        endpoint = self._endpoint(node)

        def unregister() -> None:
            with self._lock:
                if self._nodes.get(node) is not endpoint:
                    return
                del self._nodes[node]
            self._unregister_all(endpoint)
            endpoint.close()

        return unregister

    def _master(self, method: str, *args: Any) -> Any:
        return call(self.master_uri, method, *args, timeout_s=5.0)

    def _unregister_all(self, endpoint: NodeEndpoint) -> None:
        calls = [("unregisterPublisher", t, endpoint.uri) for t in endpoint.publications]
        calls += [("unregisterSubscriber", t, endpoint.uri) for t in endpoint.subscriptions]
        calls += [("unregisterService", s, self._rosrpc(endpoint)) for s in endpoint.services]
        for method, name, api in calls:
            try:
                self._master(method, endpoint.caller_id, name, api)
            except Ros1WireError as exc:
                log.debug("%s %s: %s", method, name, exc)

    def _rosrpc(self, endpoint: NodeEndpoint) -> str:
        return http_uri(endpoint.host, endpoint.tcpros_port, "rosrpc")

    # -- topics ---------------------------------------------------------------------------------
    def _advertise(
        self, endpoint: NodeEndpoint, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> Publication:
        kind = ros1_type(msg_type)
        publication = endpoint.publications.get(topic)
        if publication is None:
            latch = qos.durability is Durability.TRANSIENT_LOCAL
            publication = Publication(
                endpoint.caller_id, topic, kind, latch=latch, queue_size=qos.depth
            )
            endpoint.publications[topic] = publication
            self._master("registerPublisher", endpoint.caller_id, topic, kind.name, endpoint.uri)
        publication.refs += 1
        return publication

    def create_publisher(
        self, node: str, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> PublisherHandle:
        endpoint = self._endpoint(node)
        try:
            publication = self._advertise(endpoint, topic, msg_type, qos)
        except Ros1TypeError:
            return self._local_publisher(topic, msg_type)

        def destroy() -> None:
            publication.refs -= 1
            if publication.refs > 0 or endpoint.publications.get(topic) is not publication:
                return
            del endpoint.publications[topic]
            publication.close()
            try:
                self._master("unregisterPublisher", node, topic, endpoint.uri)
            except Ros1WireError as exc:
                log.debug("unregisterPublisher %s: %s", topic, exc)

        return _Handle(destroy, publication.publish, publication.subscriber_count)

    def create_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[Message], None],
    ) -> SubscriptionHandle:
        endpoint = self._endpoint(node)
        try:
            kind = ros1_type(msg_type)
        except Ros1TypeError:
            return self._local_subscription(topic, msg_type, deliver)
        subscription = Subscription(node, topic, kind, qos.depth, self.executor, deliver)
        endpoint.subscriptions.setdefault(topic, []).append(subscription)
        publishers = self._master("registerSubscriber", node, topic, kind.name, endpoint.uri)
        subscription.update_publishers([str(p) for p in publishers])

        def destroy() -> None:
            subscription.close()
            remaining = endpoint.subscriptions.get(topic, [])
            if subscription in remaining:
                remaining.remove(subscription)
            if not remaining:
                endpoint.subscriptions.pop(topic, None)
                try:
                    self._master("unregisterSubscriber", node, topic, endpoint.uri)
                except Ros1WireError as exc:
                    log.debug("unregisterSubscriber %s: %s", topic, exc)

        return _Handle(destroy)

    def publication(self, node: str, topic: str) -> Publication:
        """``node``'s publication of ``topic`` (made already), for what rospy adds to it: the
        fields of its connection header, a :class:`SubscriberWatch`."""
        publication = self._endpoint(node).publications.get(topic)
        if publication is None:
            raise Ros1TypeError(f"{node} publishes {topic} in this process only (no ROS 1 type)")
        return publication

    def subscriber_ids(self, node: str, topic: str) -> list[str]:
        """The caller ids of the subscribers connected now to ``node``'s publication of
        ``topic`` (actionlib's ``wait_for_server`` checks its server is among them)."""
        publication = self._endpoint(node).publications.get(topic)
        return [] if publication is None else [c.peer for c in list(publication.connections)]

    def publisher_ids(self, node: str, topic: str) -> list[str]:
        """The caller ids of the publishers that ``node``'s subscriptions of ``topic`` read
        now (connected, their headers exchanged)."""
        subscriptions = list(self._endpoint(node).subscriptions.get(topic, ()))
        return [
            inbound.peer
            for subscription in subscriptions
            for inbound in list(subscription.inbound.values())
            if inbound.connected
        ]

    # -- types without a ROS 1 counterpart: this process only -----------------------------------
    def _local_publisher(self, topic: str, msg_type: type[Message]) -> PublisherHandle:
        log.debug(
            "%s (%s) has no ROS 1 counterpart; published in this process only",
            topic,
            msg_type.__typename__,
        )

        def publish(msg: Message) -> None:
            for deliver in list(self._local_topics.get((topic, msg_type), [])):
                self.executor.post(functools.partial(deliver, msg))

        return _Handle(
            lambda: None, publish, lambda: len(self._local_topics.get((topic, msg_type), ()))
        )

    def _local_subscription(
        self, topic: str, msg_type: type[Message], deliver: Callable[[Message], None]
    ) -> SubscriptionHandle:
        subscribers = self._local_topics.setdefault((topic, msg_type), [])
        subscribers.append(deliver)
        return _Handle(lambda: subscribers.remove(deliver))

    # -- services -------------------------------------------------------------------------------
    def create_service(
        self, node: str, name: str, srv_type: type[Service], handler: ServiceHandler
    ) -> ServiceHandle:
        if name in self._local:
            raise ServiceCallError(f"service '{name}' is already offered in this process")
        self._local[name] = (srv_type, handler)
        try:
            kind = ros1_service_type(srv_type)
        except Ros1TypeError:
            log.debug(
                "%s (%s) has no ROS 1 counterpart; offered in this process only",
                name,
                srv_type.__typename__,
            )
            return _Handle(lambda: self._forget_local(name))
        endpoint = self._endpoint(node)
        endpoint.services[name] = ServiceServer(node, name, kind, handler, self.executor)
        self._master("registerService", node, name, self._rosrpc(endpoint), endpoint.uri)

        def destroy() -> None:
            self._forget_local(name)
            if endpoint.services.pop(name, None) is not None:
                try:
                    self._master("unregisterService", node, name, self._rosrpc(endpoint))
                except Ros1WireError as exc:
                    log.debug("unregisterService %s: %s", name, exc)

        return _Handle(destroy)

    def _forget_local(self, name: str) -> None:
        self._local.pop(name, None)

    def call_service(
        self,
        name: str,
        srv_type: type[Service],
        request: Message,
        timeout_s: float = 2.0,
        *,
        node: str | None = None,
    ) -> Message:
        local = self._local.get(name)
        if local is not None and local[0] is srv_type:
            return self._call_local(name, local[1], request, timeout_s)
        try:
            kind = ros1_service_type(srv_type)
        except Ros1TypeError as exc:
            raise ServiceCallError(f"service '{name}': {exc}") from None
        caller = node or "/robomodel_client"
        return call_service(self.master_uri, caller, name, kind, request, timeout_s)

    def _call_local(
        self, name: str, handler: ServiceHandler, request: Message, timeout_s: float
    ) -> Message:
        in_place = isinstance(handler, OnReceivingThread)
        if in_place or self.executor.spinner in (None, threading.get_ident()):
            answer = handler(request)
            if isinstance(answer, Deferred):
                if answer.response is None:
                    raise ServiceCallError(
                        f"service '{name}' answers later; call it from another thread"
                    )
                return answer.response
            return answer  # type: ignore[no-any-return]
        done = threading.Event()
        box: dict[str, Any] = {}

        def run() -> None:
            try:
                answer = handler(request)
            except Exception as exc:
                box["error"] = exc
                done.set()
                return
            if isinstance(answer, Deferred):
                answer.then(finish)
            else:
                finish(answer)

        def finish(response: Any) -> None:
            box["response"] = response
            done.set()

        self.executor.post(run)
        if not done.wait(timeout_s):
            raise ServiceCallError(f"service '{name}' did not answer within {timeout_s} s")
        if "error" in box:
            raise ServiceCallError(f"service '{name}' failed: {box['error']}")
        return box["response"]  # type: ignore[no-any-return]

    # -- graph and lifetime ---------------------------------------------------------------------
    def describe(self) -> str:
        return (
            f"bus: ros1, master {self.master_uri} (ROS_MASTER_URI or --master; every ROS 1 "
            "process that names it shares its graph)"
        )

    def graph(self, timeout_s: float = 1.0) -> Graph:
        try:
            state = call(
                self.master_uri, "getSystemState", "/robomodel", timeout_s=max(timeout_s, 1.0)
            )
            types = call(
                self.master_uri, "getTopicTypes", "/robomodel", timeout_s=max(timeout_s, 1.0)
            )
            return _graph_of(state, types)
        except (Ros1WireError, TypeError, ValueError) as exc:  # garbage from the master
            log.debug("cannot read the ROS 1 graph: %s", exc)
            return Graph(
                unreadable=f"cannot read the ROS 1 graph at {self.master_uri}: {exc}",
                complete=False,
            )

    def close(self) -> None:
        with self._lock:
            endpoints, self._nodes = list(self._nodes.values()), {}
        for endpoint in endpoints:
            self._unregister_all(endpoint)
            endpoint.close()


def _graph_of(state: Any, topic_types: Any) -> Graph:
    """The graph of getSystemState's and getTopicTypes' answers; TypeError or ValueError when
    they do not have the shapes rosmaster gives them."""
    graph = Graph()
    pubs, subs, services = state
    types = dict(topic_types)
    for kind, entries in (("pub", pubs), ("sub", subs)):
        for topic, nodes in entries:
            type_name = _robomodel_name(str(types.get(topic, "*")))
            for node in nodes:
                graph.add(kind, Endpoint(str(node), str(topic), type_name))
    for service, nodes in services:
        for node in nodes:
            graph.add("srv", Endpoint(str(node), str(service), ""))
    return graph


def _robomodel_name(ros1_name: str) -> str:
    """``sensor_msgs/JointState`` -> ``sensor_msgs/msg/JointState`` where robomodel has the
    type; the ROS 1 name otherwise."""
    try:
        return robomodel_type_for(ros1_name).__typename__
    except Ros1TypeError:
        return ros1_name
