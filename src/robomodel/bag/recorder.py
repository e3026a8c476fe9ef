"""Recording topics of a running graph into a bag, as ``ros2 bag record`` does.

The recorder is a node (``/robomodel_bag_record``) that looks at the graph every
``discovery_period_s``, subscribes to each topic it should record once a publisher shows
its type, and writes every message with its receive time and its publisher's send time. On
the Zenoh bus the CDR payload is written as it arrived (no decoding) and the send time is the
source timestamp of rmw_zenoh's attachment; on the other buses the message is serialized again
and both times are the receive time.

QoS is adapted to the publishers, as rosbag2's recorder does: a topic whose publishers are all
transient local (/tf_static, /robot_description) is subscribed transient local, so latched
messages published before the recording started are recorded too.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from robomodel.bag._writer_base import BagWriter
from robomodel.bag.exceptions import BagWriteError
from robomodel.runtime import Context
from robomodel.runtime.msg import Message, MessageTypeError, get_message_type, serialize
from robomodel.runtime.qos import Durability, QoSProfile, Reliability
from robomodel.runtime.transport.base import Endpoint, MessageInfo, TopicInfo

__all__ = ["Recorder", "RecorderStats"]

log = logging.getLogger("robomodel.bag")

QUEUE_DEPTH = 1000  # messages that may wait for the writer per topic before the oldest drop


@dataclass(frozen=True, slots=True)
class RecorderStats:
    """What the progress line shows."""

    messages: int
    size_bytes: int
    duration_s: float
    topics: int


def _subscription_qos(publishers: Sequence[Endpoint]) -> QoSProfile:
    latched = bool(publishers) and all(
        e.qos.durability is Durability.TRANSIENT_LOCAL for e in publishers
    )
    best_effort = any(e.qos.reliability is Reliability.BEST_EFFORT for e in publishers)
    return QoSProfile(
        QUEUE_DEPTH,
        Durability.TRANSIENT_LOCAL if latched else Durability.VOLATILE,
        Reliability.BEST_EFFORT if best_effort else Reliability.RELIABLE,
    )


class Recorder:
    """Records ``topics`` (None: every topic, hidden ones aside unless ``include_hidden``, as
    ros2 bag record's ``--include-hidden-topics``) of ``context``'s bus."""

    def __init__(
        self,
        context: Context,
        writer: BagWriter,
        *,
        topics: Sequence[str] | None = None,
        node_name: str = "robomodel_bag_record",
        include_hidden: bool = False,
    ) -> None:
        self.context = context
        self.writer = writer
        self.node = context.create_node(node_name)
        self._wanted = None if topics is None else {self.node.resolve_topic_name(t) for t in topics}
        self._include_hidden = include_hidden
        self._subscribed: dict[str, object] = {}
        self._skipped: set[str] = set()
        self._topic_count = 0
        self._started = time.monotonic()
        self._raw = getattr(context.transport, "create_raw_subscription", None)

    @property
    def topics(self) -> tuple[str, ...]:
        return tuple(sorted(self._subscribed))

    def stats(self) -> RecorderStats:
        return RecorderStats(
            self.writer.message_count,
            self.writer.size_bytes,
            time.monotonic() - self._started,
            self._topic_count,
        )

    def discover(self, timeout_s: float = 0.3) -> None:
        """Subscribe to the topics that appeared since the last look."""
        graph = self.context.graph(timeout_s=timeout_s)
        for name, info in sorted(graph.topics.items()):
            if name in self._subscribed or name in self._skipped or not info.publishers:
                continue
            if self._wanted is None:
                hidden = any(part.startswith("_") for part in name.split("/"))
                if hidden and not self._include_hidden:
                    continue  # hidden topics, as ros2 bag record -a leaves them
            elif name not in self._wanted:
                continue
            self._subscribe(name, info)

    def _skip(self, name: str, reason: str) -> None:
        self._skipped.add(name)
        log.warning("not recording %s: %s", name, reason)

    def _type_of(self, topic: str, info: TopicInfo) -> type[Message]:
        """The class of the topic's type; a type robomodel does not know is learned from its
        publishers (a ROS 1 publisher's definition, a ROS 2 node's type description), and
        stored in the bag as rosbag does."""
        type_name = next(iter(info.types))
        try:
            return get_message_type(type_name)
        except MessageTypeError:
            from robomodel.runtime.type_learning import learn_topic_type

            if not learn_topic_type(self.context, topic, list(info.publishers)):
                raise
        return get_message_type(type_name)

    def _subscribe(self, name: str, info: TopicInfo) -> None:
        if len(info.types) != 1:
            self._skip(name, f"published with several types ({', '.join(sorted(info.types))})")
            return
        try:
            msg_type = self._type_of(name, info)
        except MessageTypeError as exc:
            self._skip(name, str(exc))
            return
        offered = tuple(e.qos for e in info.publishers)
        try:
            self.writer.add_topic(name, msg_type, offered)
        except BagWriteError as exc:
            self._skip(name, exc.reason)
            return
        qos = _subscription_qos(info.publishers)
        if self._raw is not None:
            handle = self._raw(
                self.node.fully_qualified_name, name, msg_type, qos, self._raw_writer(name)
            )
        else:
            handle = self.node.create_subscription(msg_type, name, self._typed_writer(name), qos)
        self._subscribed[name] = handle
        self._topic_count += 1

    def _raw_writer(self, topic: str) -> Callable[[bytes, MessageInfo], None]:
        write = self.writer.write

        def on_sample(payload: bytes, info: MessageInfo) -> None:
            write(
                topic,
                payload,
                info.received_timestamp_ns,
                info.source_timestamp_ns,
                info.publication_sequence_number,
            )

        return on_sample

    def _typed_writer(self, topic: str) -> Callable[[Message], None]:
        write = self.writer.write

        def on_message(msg: Message) -> None:
            now = time.time_ns()
            write(topic, serialize(msg), now, now)

        return on_message

    def close(self) -> None:
        """Stop subscribing and finish the bag's files."""
        for handle in self._subscribed.values():
            destroy = getattr(handle, "destroy", None)
            if destroy is not None:
                destroy()
        self._subscribed.clear()
        self.writer.close()
