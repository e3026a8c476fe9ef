"""Playing a bag back onto the bus, as ``ros2 bag play`` does.

Messages are published in recorded order with their recorded spacing (divided by ``rate``).
Topics their publishers offered transient local, and /tf_static and /robot_description
always, are published latched, with a history as deep as the bag has messages on them (up to
100), so a late subscriber gets every static transform, not only the last publisher's.
``clock_hz`` publishes the playback time on /clock, as ``ros2 bag play --clock``, so nodes
with ``use_sim_time`` follow the bag's time (a recorded /clock is then not played: two clocks
would make such nodes jump back and forth). Message contents (header stamps included) are
published as recorded.

What cannot be played is said once per topic: a type robomodel does not know, messages that
do not decode, and messages the bag lists but its storage does not hold (a SQLite 3 message
whose ``topic_id`` names no topic) — :meth:`Player.shortfall` after the first pass.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Collection
from dataclasses import dataclass

from robomodel.bag.model import BagMessage, TopicSummary
from robomodel.bag.reader import Bag
from robomodel.runtime import Context
from robomodel.runtime.msg import Clock, Message, MessageTypeError, Time, get_message_type
from robomodel.runtime.msg import deserialize as cdr_deserialize
from robomodel.runtime.node import Publisher
from robomodel.runtime.qos import QoSProfile, latched

__all__ = ["ALWAYS_LATCHED", "PlayOptions", "Player"]

log = logging.getLogger("robomodel.bag")

ALWAYS_LATCHED = frozenset({"/tf_static", "/robot_description"})
MAX_LATCHED_DEPTH = 100

Decoder = Callable[[bytes], Message]


@dataclass(frozen=True, slots=True)
class PlayOptions:
    rate: float = 1.0
    loop: bool = False
    topics: Collection[str] | None = None
    clock_hz: float | None = None


def _decoder(topic: TopicSummary) -> tuple[type[Message], Decoder]:
    """The robomodel class of a topic and how to turn its stored bytes into a message."""
    if topic.definition:  # a type robomodel does not know decodes by the bag's definition
        from robomodel.runtime.msg._resolver import learn_definition

        learn_definition(topic.type, topic.definition)
    if topic.serialization_format == "ros1":
        from robomodel.runtime.transport.ros1.ros1_types import Ros1TypeError, ros1_type_named

        package, _, name = topic.type.rpartition("/")
        try:
            kind = ros1_type_named(f"{package.split('/')[0]}/{name}")
        except Ros1TypeError as exc:
            raise MessageTypeError(str(exc)) from None
        return kind.cls, kind.decode
    if topic.serialization_format != "cdr":
        raise MessageTypeError(f"serialization format '{topic.serialization_format}'")
    cls = get_message_type(topic.type)
    return cls, lambda data: cdr_deserialize(data, cls)


class Player:
    """Publishes the messages of ``bag`` from a node of ``context``."""

    def __init__(self, context: Context, bag: Bag, options: PlayOptions = PlayOptions()) -> None:
        if not options.rate > 0:
            raise ValueError(f"rate must be positive, got {options.rate}")
        self.context = context
        self.bag = bag
        self.options = options
        self.node = context.create_node("robomodel_bag_play")
        self.published = 0
        self._read: dict[str, int] = {}  # messages read per topic in the first pass
        self._undecodable: set[str] = set()
        self._passes = 0
        self._publishers: dict[str, tuple[Publisher[Message], Decoder]] = {}
        self._clock: Publisher[Clock] | None = None
        self._clock_ns = 0
        if options.clock_hz:
            self._clock = self.node.create_publisher(Clock, "/clock")
        self.summary = bag.summary()
        for topic in self.summary.topics:
            if options.clock_hz and topic.name == "/clock":
                log.warning("not playing the recorded /clock: --clock publishes the bag's time")
            elif options.topics is None or topic.name in options.topics:
                self._add(topic)

    def _add(self, topic: TopicSummary) -> None:
        try:
            cls, decode = _decoder(topic)
        except MessageTypeError as exc:
            log.warning("not playing %s (%s): %s", topic.name, topic.type, exc)
            return
        qos: QoSProfile | int = 10
        if topic.latched or topic.name in ALWAYS_LATCHED:
            qos = latched(max(1, min(topic.count, MAX_LATCHED_DEPTH)))
        publisher = self.node.create_publisher(cls, topic.name, qos)
        self._publishers[topic.name] = (publisher, decode)

    @property
    def topics(self) -> tuple[str, ...]:
        return tuple(self._publishers)

    def play(self, stop: Callable[[], bool] = lambda: False) -> int:
        """Publish the bag (again and again with ``loop``) until done or ``stop()``; returns
        the number of messages published."""
        while self._publishers:
            self._play_once(stop)
            self._passes += 1
            if self._passes == 1 and not stop():
                for line in self.shortfall():
                    log.warning("%s", line)
            if not self.options.loop or stop():
                break
        return self.published

    def shortfall(self) -> list[str]:
        """One line per topic played whose messages the first pass read fewer of than the bag
        lists."""
        listed = {t.name: t.count for t in self.summary.topics}
        return [
            f"{topic}: the bag lists {listed[topic]} messages, its storage holds "
            f"{self._read.get(topic, 0)} of them"
            for topic in self._publishers
            if self._read.get(topic, 0) < listed.get(topic, 0)
        ]

    def _play_once(self, stop: Callable[[], bool]) -> None:
        """One pass over the bag. Message times are ``log_time`` (receive time); with a clock,
        /clock is published every ``1 / clock_hz`` s with the bag time of that moment."""
        first: int | None = None
        start = time.monotonic()
        period = 1.0 / self.options.clock_hz if self.options.clock_hz else None
        next_tick = start
        self._clock_ns = 0
        for message in self.bag.messages(self._publishers):
            if first is None:
                first = message.log_time_ns
            due = start + (message.log_time_ns - first) / 1e9 / self.options.rate
            while not stop():
                now = time.monotonic()
                if period is not None and now >= next_tick:
                    bag_now = first + round((now - start) * self.options.rate * 1e9)
                    self._tick_clock(min(bag_now, message.log_time_ns))
                    next_tick += period
                    next_tick = next_tick if next_tick > now else now + period
                if now >= due:
                    break
                wake = min(due, next_tick) if period is not None else due
                self.context.spin(duration_s=min(wake - now, 0.1))
            if stop():
                return
            if not self._passes:
                self._read[message.topic] = self._read.get(message.topic, 0) + 1
            self._publish(message)
        self.context.spin(duration_s=0.05)  # let the last messages leave

    def _tick_clock(self, stamp_ns: int) -> None:
        """Publish ``stamp_ns`` on /clock, never going back within a pass."""
        if self._clock is not None:
            stamp_ns = self._clock_ns = max(self._clock_ns, stamp_ns)
            self._clock.publish(Clock(Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)))

    def _publish(self, message: BagMessage) -> None:
        publisher, decode = self._publishers[message.topic]
        try:
            msg = decode(message.data)
        except (MessageTypeError, ValueError) as exc:
            level = logging.DEBUG if message.topic in self._undecodable else logging.WARNING
            self._undecodable.add(message.topic)
            log.log(level, "skipping %s messages that do not decode (the first: %s)",
                    message.topic, exc)  # fmt: skip
            return
        publisher.publish(msg)
        self.published += 1
