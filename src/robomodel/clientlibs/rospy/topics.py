"""rospy's ``Publisher`` and ``Subscriber`` on the node's robomodel publishers and
subscriptions (TCPROS, registered with the master), and ``wait_for_message``."""

from __future__ import annotations

import threading
import warnings
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.exceptions import (
    ROSException,
    ROSInterruptException,
    ROSSerializationException,
)
from robomodel.runtime.msg import Message
from robomodel.runtime.qos import Durability, QoSProfile

__all__ = ["Publisher", "Subscriber", "wait_for_message"]

# rospy publishes synchronously when queue_size is None, and queues without bound on a
# subscriber; robomodel's queues are bounded: these stand for "no bound".
UNBOUNDED_PUBLISHER_QUEUE = 10_000
UNBOUNDED_SUBSCRIBER_QUEUE = 100_000


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


class Publisher(_Topic):
    """Publishes ``data_class`` messages on ``name`` (``queue_size`` messages wait per
    subscriber, the oldest dropped first; ``latch`` gives a new subscriber the last one)."""

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
        _unsupported("Publisher(subscriber_listener=...)", subscriber_listener)
        _unsupported("Publisher(headers=...)", headers)
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
        super().__init__(name, data_class)

    def _create(self, node_state: core.NodeState) -> None:
        if not self._unregistered:
            self._publisher = node_state.node.create_publisher(
                self.data_class, self.resolved_name, self._qos
            )
            self._publish = self._publisher.publish

    def publish(self, *args: Any, **kwds: Any) -> None:
        """Publish a message, or the message that ``data_class(*args, **kwds)`` makes."""
        if self._publisher is None:
            if self._unregistered:
                raise ROSException("publish() to an unregistered() handle")
            raise ROSException(
                "ROS node has not been initialized yet. Please call init_node() first"
            )
        if core.is_shutdown():
            raise ROSException(f"publish() to {self.resolved_name} after the node shut down")
        if len(args) == 1 and not kwds and _is_message_of(args[0], self.data_class):
            msg = args[0]
        else:
            try:
                msg = self.data_class(*args, **kwds)
            except TypeError as exc:
                raise ROSSerializationException(
                    f"cannot make a {self.type} of the arguments given to publish(): {exc}"
                ) from None
        self._publish(msg)

    def get_num_connections(self) -> int:
        """The subscribers connected now."""
        return 0 if self._publisher is None else self._publisher.get_subscription_count()

    def unregister(self) -> None:
        """Stop publishing: the master and the subscribers forget this publisher."""
        self._unregistered = True
        if self._publisher is not None:
            self._publisher.destroy()
            self._publisher = None


def _is_message_of(value: Any, data_class: type[Message]) -> bool:
    """Whether ``value`` is a message of ``data_class``'s type, whichever face its class is."""
    kind = getattr(type(value), "__typename__", None)
    return kind == data_class.__typename__ and isinstance(value, Message)


class Subscriber(_Topic):
    """Calls ``callback(msg)`` (or ``callback(msg, callback_args)``) for every message on
    ``name``, on the node's callback thread; ``queue_size`` messages wait, the oldest dropped."""

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
        self._depth = UNBOUNDED_SUBSCRIBER_QUEUE if queue_size is None else max(1, int(queue_size))
        self._subscription: Any = None
        self._unregistered = False
        super().__init__(name, data_class)

    def _create(self, node_state: core.NodeState) -> None:
        if self._unregistered:
            return
        if self.callback is None:
            deliver: Callable[[Any], Any] = _ignore
        elif self.callback_args is None:
            deliver = self.callback
        else:
            deliver = _with_args(self.callback, self.callback_args)
        self._subscription = node_state.node.create_subscription(
            self.data_class, self.resolved_name, deliver, self._depth
        )

    def get_num_connections(self) -> int:
        """The publishers of the topic that the master lists now (rospy counts the
        connections to them; they are the same once connected)."""
        if self._subscription is None:
            return 0
        return len(_publishers_of(self.resolved_name))

    def unregister(self) -> None:
        """Stop receiving: the master and the publishers forget this subscriber."""
        self._unregistered = True
        if self._subscription is not None:
            self._subscription.destroy()
            self._subscription = None


def _ignore(msg: Any) -> None:
    """A Subscriber made without a callback receives and drops."""


def _with_args(callback: Callable[..., Any], args: Any) -> Callable[[Any], Any]:
    def deliver(msg: Any) -> Any:
        return callback(msg, args)

    return deliver


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

    subscriber = Subscriber(topic, topic_type, first, queue_size=1)
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
