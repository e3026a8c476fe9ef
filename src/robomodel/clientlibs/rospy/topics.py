"""rospy's ``Publisher`` and ``Subscriber`` on the node's robomodel publishers and
subscriptions (TCPROS, registered with the master), and ``wait_for_message``."""

from __future__ import annotations

import threading
import warnings
from collections.abc import Callable
from typing import Any, ClassVar

from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.dispatch import TopicDispatch
from robomodel.clientlibs.rospy.exceptions import (
    ROSException,
    ROSInterruptException,
    ROSSerializationException,
)
from robomodel.runtime.msg import Message
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.transport.base import OnReceivingThread

__all__ = ["Publisher", "SubscribeListener", "Subscriber", "wait_for_message"]

# rospy publishes synchronously when queue_size is None; robomodel's queues are bounded: this
# stands for "no bound" (a subscriber's is dispatch.UNBOUNDED).
UNBOUNDED_PUBLISHER_QUEUE = 10_000


def _check_class(data_class: Any, what: str) -> type[Message]:
    if not (isinstance(data_class, type) and issubclass(data_class, Message)):
        raise ValueError(
            f"{what}: data_class must be a message class (from std_msgs.msg import String),"
            f" got {data_class!r}"
        )
    return data_class


def _unsupported(what: str, value: Any) -> None:
    if value:
        raise NotImplementedError(f"rospy {what} is not offered by robomodel's rospy")


class _Topic:
    """A topic's name and type. Made before ``init_node`` (as ros_tutorials' talker makes its
    Publisher), it is bound to the node when ``init_node`` runs, as rospy registers it then."""

    def __init__(self, name: str, data_class: Any) -> None:
        self.name = name
        self.resolved_name = name
        self.data_class = _check_class(data_class, f"topic {name}")
        self.type = _ros1_name(self.data_class)
        node_state = core.current()
        if node_state is None:
            core.defer(self._bind)
        else:
            self._bind(node_state)

    def _bind(self, node_state: core.NodeState) -> None:
        self.resolved_name = node_state.resolve(self.name)
        self._create(node_state)

    def _create(self, node_state: core.NodeState) -> None:
        raise NotImplementedError


def _ros1_name(data_class: type[Message]) -> str:
    package, _, name = data_class.__typename__.split("/")
    return f"{package}/{name}"


class SubscribeListener:
    """Told of the subscribers of a Publisher made with ``subscriber_listener=`` (rospy's):
    subclass it and override what you need. Both are called on the thread of the connection."""

    def peer_subscribe(
        self,
        topic_name: str,
        topic_publish: Callable[[Any], None],
        peer_publish: Callable[[Any], None],
    ) -> None:
        """A subscriber connected to ``topic_name``: ``topic_publish(msg)`` publishes to every
        subscriber, ``peer_publish(msg)`` to the new one only."""

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        """A subscriber left ``topic_name``; ``num_peers`` remain."""


class Publisher(_Topic):
    """Publishes ``data_class`` messages on ``name`` (``queue_size`` messages wait per
    subscriber, the oldest dropped first; ``latch`` gives a new subscriber the last one;
    ``subscriber_listener``, a :class:`SubscribeListener`, is told of subscribers; the
    ``headers`` dict goes into its connection header)."""

    def __init__(
        self,
        name: str,
        data_class: Any,
        subscriber_listener: Any = None,
        tcp_nodelay: bool = False,
        latch: bool = False,
        headers: Any = None,
        queue_size: int | None = None,
    ) -> None:
        if queue_size is None:
            warnings.warn(
                "The publisher should be created with an explicit keyword argument 'queue_size'.",
                SyntaxWarning,
                stacklevel=2,
            )
        depth = UNBOUNDED_PUBLISHER_QUEUE if queue_size is None else max(1, int(queue_size))
        self.latch = latch
        self._qos = QoSProfile(depth, Durability.TRANSIENT_LOCAL if latch else Durability.VOLATILE)
        self._publisher: Any = None
        self._unregistered = False
        self._listener = subscriber_listener
        self._headers = {str(k): str(v) for k, v in (headers or {}).items()}
        self._unwatch: Callable[[], None] | None = None
        super().__init__(name, data_class)

    def _create(self, node_state: core.NodeState) -> None:
        if not self._unregistered:
            self._publisher = node_state.node.create_publisher(
                self.data_class, self.resolved_name, self._qos
            )
            self._publish = self._publisher.publish
            if self._listener is not None or self._headers:
                self._extend(node_state)

    def _extend(self, node_state: core.NodeState) -> None:
        """The connection header's fields and the SubscribeListener, on the ROS 1
        publication."""
        from robomodel.runtime.transport.ros1.publication import SubscriberWatch

        found = getattr(node_state.context.transport, "publication", None)
        if found is None:
            raise NotImplementedError(
                "rospy Publisher(subscriber_listener=..., headers=...) needs the ROS 1 bus"
            )
        publication = found(node_state.node.fully_qualified_name, self._publisher.topic)
        publication.header_fields.update(self._headers)
        listener = self._listener
        if listener is None:
            return

        def connected(to_peer: Callable[[Message], None]) -> None:
            def peer_publish(*args: Any, **kwds: Any) -> None:
                to_peer(self._message(args, kwds))

            listener.peer_subscribe(self.resolved_name, self.publish, peer_publish)

        def gone(remaining: int) -> None:
            listener.peer_unsubscribe(self.resolved_name, remaining)

        watch = SubscriberWatch(connected, gone)
        publication.watches.append(watch)

        def unwatch() -> None:
            if watch in publication.watches:
                publication.watches.remove(watch)

        self._unwatch = unwatch

    def publish(self, *args: Any, **kwds: Any) -> None:
        """Publish a message, or the message that ``data_class(*args, **kwds)`` makes. As
        rospy's: in an ``on_shutdown`` hook it is still sent; once the node's topics are gone it
        does nothing."""
        if self._publisher is None:
            if self._unregistered:
                raise ROSException("publish() to an unregistered() handle")
            raise ROSException(
                "ROS node has not been initialized yet. Please call init_node() first"
            )
        self._publish(self._message(args, kwds))

    def _message(self, args: tuple[Any, ...], kwds: dict[str, Any]) -> Message:
        if len(args) == 1 and not kwds and _is_message_of(args[0], self.data_class):
            found: Message = args[0]
            return found
        try:
            made: Message = self.data_class(*args, **kwds)
        except TypeError as exc:
            raise ROSSerializationException(
                f"cannot make a {self.type} of the arguments given to publish(): {exc}"
            ) from None
        return made

    def get_num_connections(self) -> int:
        """The subscribers connected now."""
        return 0 if self._publisher is None else self._publisher.get_subscription_count()

    def unregister(self) -> None:
        """Stop publishing: the master and the subscribers forget this publisher."""
        self._unregistered = True
        if self._unwatch is not None:
            self._unwatch()
            self._unwatch = None
        if self._publisher is not None:
            self._publisher.destroy()
            self._publisher = None


def _is_message_of(value: Any, data_class: type[Message]) -> bool:
    """Whether ``value`` is a message of ``data_class``'s type, whichever face its class is."""
    kind = getattr(type(value), "__typename__", None)
    return kind == data_class.__typename__ and isinstance(value, Message)


class Subscriber(_Topic):
    """Calls ``callback(msg)`` (or ``callback(msg, callback_args)``) for every message on
    ``name``, on the topic's callback thread (:mod:`.dispatch`); ``queue_size`` messages wait,
    the oldest dropped first."""

    def __init__(
        self,
        name: str,
        data_class: Any,
        callback: Callable[..., Any] | None = None,
        callback_args: Any = None,
        queue_size: int | None = None,
        buff_size: int = 65536,
        tcp_nodelay: bool = False,
    ) -> None:
        self.callback = callback
        self.callback_args = callback_args
        self._queue_size = None if queue_size is None else max(1, int(queue_size))
        self._impl: _SubscriberImpl | None = None
        self._entry: tuple[Callable[..., Any], Any] | None = None
        self._unregistered = False
        super().__init__(name, data_class)

    def _create(self, node_state: core.NodeState) -> None:
        if self._unregistered:
            return
        self._impl = _SubscriberImpl.acquire(
            node_state, self.resolved_name, self.data_class, self._queue_size
        )
        self._entry = (self.callback or _ignore, self.callback_args)
        self._impl.dispatch.callbacks.append(self._entry)

    def get_num_connections(self) -> int:
        """The publishers of the topic that the master lists now (rospy counts the
        connections to them; they are the same once connected)."""
        if self._impl is None:
            return 0
        return len(_publishers_of(self.resolved_name))

    def unregister(self) -> None:
        """Stop receiving: the master and the publishers forget this subscriber once the
        topic's last Subscriber in this process is unregistered."""
        self._unregistered = True
        impl, self._impl = self._impl, None
        if impl is not None:
            impl.release(self._entry)


class _SubscriberImpl:
    """A topic this process subscribes to (rospy's ``_SubscriberImpl``): one robomodel
    subscription and one callback thread, shared by the topic's Subscribers."""

    _topics: ClassVar[dict[str, _SubscriberImpl]] = {}
    _lock: ClassVar[threading.Lock] = threading.Lock()

    def __init__(
        self, node_state: core.NodeState, topic: str, data_class: type[Message], depth: int | None
    ) -> None:
        self.topic = topic
        self.data_class = data_class
        self.dispatch = TopicDispatch(topic, depth)
        self.subscription: Any = node_state.node.create_subscription(
            data_class, topic, OnReceivingThread(self.dispatch.put), depth or 10
        )

    @classmethod
    def acquire(
        cls, node_state: core.NodeState, topic: str, data_class: type[Message], depth: int | None
    ) -> _SubscriberImpl:
        with cls._lock:
            impl = cls._topics.get(topic)
            if impl is not None and impl.subscription is not None:
                if impl.data_class.__typename__ != data_class.__typename__:
                    raise ROSException(
                        f"cannot subscribe to {topic} as {_ros1_name(data_class)}: this process"
                        f" subscribes to it as {_ros1_name(impl.data_class)}"
                    )
                if depth is not None:  # as rospy: the last queue_size given counts
                    impl.dispatch.set_depth(depth)
                return impl
            impl = cls._topics[topic] = cls(node_state, topic, data_class, depth)
            return impl

    def release(self, entry: Any) -> None:
        """Forget one Subscriber's callback; the last one gone ends the subscription."""
        with self._lock:
            callbacks = self.dispatch.callbacks
            for index, found in enumerate(callbacks):
                if found is entry:
                    del callbacks[index]
                    break
            if callbacks:
                return
            if self._topics.get(self.topic) is self:
                del self._topics[self.topic]
            subscription, self.subscription = self.subscription, None
        if subscription is not None:
            subscription.destroy()
        self.dispatch.close()

    @classmethod
    def forget_all(cls) -> None:
        """The node shut down: its subscriptions are gone."""
        with cls._lock:
            cls._topics.clear()


core.after_teardown(_SubscriberImpl.forget_all)


def _ignore(msg: Any) -> None:
    """A Subscriber made without a callback receives and drops."""


def _publishers_of(topic: str) -> list[str]:
    from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call

    node_state = core.state()
    master = node_state.context.transport.master_uri  # type: ignore[attr-defined]
    try:
        publishers, _, _ = call(master, "getSystemState", node_state.caller_id)
    except Ros1WireError:
        return []
    for name, nodes in publishers:
        if name == topic:
            return [str(n) for n in nodes]
    return []


def wait_for_message(topic: str, topic_type: Any, timeout: float | None = None) -> Any:
    """The next message on ``topic``. ROSException when none comes within ``timeout``
    seconds, ROSInterruptException when the node shuts down first."""
    got: list[Any] = []
    arrived = threading.Event()

    def first(msg: Any) -> None:
        if not got:
            got.append(msg)
            arrived.set()

    subscriber = Subscriber(topic, topic_type, first)  # as rospy: the topic's queue_size stays
    stop = core.shutdown_event()
    try:
        import time

        end = None if timeout is None else time.monotonic() + float(timeout)
        while not arrived.is_set():
            if stop.is_set():
                raise ROSInterruptException("rospy shutdown")
            left = 0.05 if end is None else min(0.05, end - time.monotonic())
            if left <= 0:
                raise ROSException(
                    f"timeout exceeded while waiting for message on topic {subscriber.resolved_name}"
                )
            arrived.wait(left)
    finally:
        subscriber.unregister()
    return got[0]
