"""foxglove_bridge: the Foxglove WebSocket protocol for Foxglove and Lichtblick, on the bus.

The protocol is the Foxglove SDK's (``foxglove-sdk`` on PyPI, the ``foxglove`` extra): its
server speaks the protocol, keeps every client's queue and sends the frames; this module is
what foxglove_bridge adds on top of it, on robomodel's bus. Using the SDK rather than writing
the protocol by hand keeps the framing, the subprotocol negotiation and the protocol's later
versions Foxglove's business, at the cost of a 55 MB wheel.

- One channel per topic of the graph (``topic_whitelist``), with its type's schema: ``cdr`` messages with a ``ros2msg`` schema on
  Zenoh, ``ros1`` messages with a ``ros1msg`` schema on ROS 1. A channel subscribes on the bus
  when its first client subscribes and unsubscribes after the last; on Zenoh the CDR payload
  goes to the clients as it came (no decoding), handed to the SDK on Zenoh's receiving thread.
  A subscription the SDK refused because it came before the SDK registered a new channel
  gets the topic advertised anew (``_RefusedSubscriptions``).
- Client publish (``clientPublish``): a client's channel on a topic of
  ``client_topic_whitelist`` becomes a publisher of its schema's type; its messages are decoded
  and published.
- Services (``services``): every service of the graph on ``service_whitelist``, called with
  the client's CDR/ROS 1 request.
- Parameters (``parameters``): the ROS 1 parameter server, or the ROS 2 nodes' parameters
  named ``/node.param`` as foxglove_bridge names them, those on ``param_whitelist``; get, set
  and subscribe. A subscription hears the nodes' ``/parameter_events`` on ROS 2 (every change,
  as it happens); the ROS 1 parameter server has no events, so its values are read once a
  second and the changed ones sent.
- The connection graph (``connectionGraph``): the graph's publishers, subscribers and services.
- Assets: ``fetchAsset`` for ``package://`` URIs on ``asset_uri_allowlist`` (by default
  foxglove_bridge's: mesh, image and description files), never with ``..`` nor outside their
  package.
- Time (``time``, offered with ``use_sim_time``): the server's time is each ``/clock``
  message's, as foxglove_bridge sends it.

The whitelists are regular expressions a whole name must match, ignoring case (foxglove_bridge's
``std::regex_match`` with ``icase``).

The graph is read once a second (``graph_period_s``). Each client's queue holds at most
``send_buffer_limit / 100 kB`` messages (the SDK bounds it by count, not bytes; between 8 and
1024): the oldest are dropped when a client reads too slowly. A client's frame over 16 MiB
closes its connection (the SDK's WebSocket bound, which it reports in one line); a client
publishing more than ``max_client_messages_per_s`` messages a second (over a burst of as many)
has the excess dropped and counted, said in one line per client.
"""

from __future__ import annotations

import logging
import re
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from robomodel._heap import large_buffers_from_the_heap
from robomodel.bridges.exceptions import BridgeError, ClientError
from robomodel.bridges.json_mapping import Dialect
from robomodel.bridges.rosapi import Ros2Params, RosapiParams
from robomodel.errors import MissingDependencyError, RobomodelError

__all__ = ["CAPABILITIES", "DEFAULT_ASSET_ALLOWLIST", "FoxgloveBridge"]

SEND_BUFFER_BYTES = 4 << 20
"""The send buffer asked for each client's socket. Linux doubles the number for its bookkeeping and
caps it at twice ``net.core.wmem_max`` (8 MiB here, 416 KiB with the kernel's default cap): what a
slow client can hold in the kernel, beside the bridge's own queue (``send_buffer_limit``)."""

CAPABILITIES = ("clientPublish", "parameters", "parametersSubscribe", "services",
                "connectionGraph", "assets")  # fmt: skip
# "time" is offered with use_sim_time, as foxglove_bridge does
# foxglove_bridge's default asset_uri_allowlist
DEFAULT_ASSET_ALLOWLIST = (
    r"^package://(?:[-\w%]+/)*[-\w%.]+\.(?:dae|fbx|glb|gltf|jpeg|jpg|mtl|obj|png|stl|tif|tiff|"
    r"urdf|webp|xacro)$",
)
_TYPICAL_MESSAGE_BYTES = 100_000
# how many times a topic is advertised anew after the SDK refused a subscription to its channel
_READVERTISE_LIMIT = 5
MAX_CLIENT_FRAME_BYTES = 16 * 1024 * 1024  # the SDK's WebSocket bound on a client's frame


@dataclass
class _ClientFlow:
    """A client's published messages: a token bucket over them and what it let through."""

    tokens: float
    stamp_s: float
    received: int = 0
    dropped: int = 0


@dataclass
class _Topic:
    """A topic offered to clients: its channel and, while clients subscribe, its subscription."""

    channel: Any  # foxglove.Channel
    msg_type: type[Any]
    subscribers: set[int] = field(default_factory=set)
    subscription: Any = None


class _RefusedSubscriptions(logging.Handler):
    """Subscriptions the SDK refused to a channel it had advertised but not yet registered.

    The Foxglove SDK's server (0.30.3) sends a new channel's advertisement to a client before it
    enters the channel in that client's table: a client that subscribes at once (Foxglove does,
    for an open panel) can be answered ``Unknown channel ID: N`` and gets no data, as the SDK
    says in its log (through Python's ``logging``, logger ``foxglove``). This handler notes the
    channel ids of such lines; the bridge then advertises the topic of each one of its own anew
    (:meth:`FoxgloveBridge._update_channels`), and the client subscribes to the new channel as
    it does to any. The line comes while the channel is being made, before the bridge knows its
    id: so ids above the newest the bridge had (the SDK numbers channels upwards, one count per
    process) are noted too, at most :attr:`MAX_NOTED` between two reads of the graph. It runs
    on the SDK's thread, which holds the client's table then: it only notes the id."""

    PATTERN = re.compile(r"attempted to subscribe to unknown channel: (\d+)")
    MAX_NOTED = 1024

    def __init__(self) -> None:
        super().__init__(logging.ERROR)
        self._watched: frozenset[int] = frozenset()  # replaced whole, read without a lock
        self._newest = 0
        self._noted: set[int] = set()
        self._noted_lock = threading.Lock()

    def watch(self, channel_ids: frozenset[int]) -> None:
        """The bridge's channels now."""
        self._watched = channel_ids
        self._newest = max(channel_ids, default=self._newest)

    def emit(self, record: logging.LogRecord) -> None:
        found = self.PATTERN.search(record.getMessage())
        if found is None:
            return
        channel_id = int(found.group(1))
        if channel_id not in self._watched and channel_id <= self._newest:
            return
        with self._noted_lock:
            if len(self._noted) < self.MAX_NOTED:
                self._noted.add(channel_id)

    def take(self) -> set[int]:
        """The channel ids noted since the last call."""
        with self._noted_lock:
            taken, self._noted = self._noted, set()
        return taken


def _import_foxglove() -> Any:
    try:
        import foxglove
        import foxglove.websocket
    except ImportError:
        raise MissingDependencyError("foxglove-sdk", "foxglove", "foxglove_bridge") from None
    return foxglove


class FoxgloveBridge:
    """A running foxglove_bridge (see the module docstring).

    Args:
        context: The bus (a :class:`robomodel.runtime.Context` someone spins).
        params: The parameters clients get and set (:mod:`.rosapi`'s).
        dialect: ``ros1`` or ``ros2``: the message encoding and the parameters' names.
        package_index: Where ``package://`` assets are found.
        name, namespace: The node's.
        address: The interface to listen on (loopback unless told otherwise).
        port: The TCP port (8765, foxglove_bridge's; 0 picks a free one).
        topic_whitelist: Regular expressions; a topic matching one is offered.
        param_whitelist, service_whitelist, client_topic_whitelist: The same for parameters
            (as clients name them), services and the topics clients may publish on.
        asset_uri_allowlist: The same for the URIs ``fetchAsset`` serves.
        use_sim_time: Offer the ``time`` capability with ``/clock``'s time.
        send_buffer_limit: [bytes] sets the per-client message bound (module docstring).
        max_qos_depth: The bus subscriptions' queue depth at most.
        max_client_messages_per_s: A client's published messages a second (as many in a
            burst); the excess is dropped.
        capabilities: The protocol capabilities offered (:data:`CAPABILITIES`).
        graph_period_s: [s] How often the graph (and the ROS 1 parameters watched) are read.
        log: Where the one-line reports go.
    """

    def __init__(
        self,
        context: Any,
        params: RosapiParams,
        *,
        dialect: Dialect,
        package_index: Any,
        name: str = "foxglove_bridge",
        namespace: str = "/",
        address: str = "127.0.0.1",
        port: int = 8765,
        topic_whitelist: Sequence[str] = (".*",),
        param_whitelist: Sequence[str] = (".*",),
        service_whitelist: Sequence[str] = (".*",),
        client_topic_whitelist: Sequence[str] = (".*",),
        asset_uri_allowlist: Sequence[str] = DEFAULT_ASSET_ALLOWLIST,
        use_sim_time: bool = False,
        send_buffer_limit: int = 10_000_000,
        max_qos_depth: int = 25,
        max_client_messages_per_s: float = 5_000.0,
        capabilities: Sequence[str] = CAPABILITIES,
        graph_period_s: float = 1.0,
        log: Callable[[str], None] = print,
    ) -> None:
        foxglove = _import_foxglove()
        from foxglove.websocket import Capability

        unknown = sorted(set(capabilities) - set(CAPABILITIES))
        if unknown:
            raise BridgeError(
                f"foxglove_bridge: unknown capabilities {', '.join(unknown)}; "
                f"they are: {', '.join(CAPABILITIES)}"
            )
        self._whitelist = _patterns("topic_whitelist", topic_whitelist)
        self._param_whitelist = _patterns("param_whitelist", param_whitelist)
        self._service_whitelist = _patterns("service_whitelist", service_whitelist)
        self._client_topics = _patterns("client_topic_whitelist", client_topic_whitelist)
        self._assets = _patterns("asset_uri_allowlist", asset_uri_allowlist)
        self.use_sim_time = use_sim_time
        self.context = context
        self.params = params
        self.dialect = dialect
        self.package_index = package_index
        self.capabilities = tuple(capabilities)
        self.max_qos_depth = max_qos_depth
        self.graph_period_s = graph_period_s
        if not max_client_messages_per_s > 0:
            raise BridgeError(
                "foxglove_bridge: max_client_messages_per_s must be positive, "
                f"got {max_client_messages_per_s!r}"
            )
        self.max_client_messages_per_s = float(max_client_messages_per_s)
        self._flows: dict[int, _ClientFlow] = {}  # client id -> its published messages
        self.log = log
        self.node = context.create_node(name, namespace)
        self._topics: dict[str, _Topic] = {}
        self._refusals = _RefusedSubscriptions()
        self._readvertised: dict[str, int] = {}  # topic -> times advertised anew
        self._refused: set[tuple[str, str]] = set()  # (topic, type) that cannot be offered
        self._services: dict[str, str] = {}  # name -> type offered to clients
        # (client, channel) -> (publisher, decoder of the wire format)
        self._client_channels: dict[tuple[int, int], tuple[Any, Callable[[bytes], Any]]] = {}
        self._watched_params: dict[str, Any] = {}
        self._events = dialect == "ros2" and isinstance(params, Ros2Params)
        self._events_subscription: Any = None
        self._clock_subscription: Any = None
        self._graph_wanted = False
        self._lock = threading.RLock()
        self._stopping = threading.Event()
        self._fox = foxglove.Context()
        wanted = {
            "clientPublish": Capability.ClientPublish,
            "parameters": Capability.Parameters,
            "services": Capability.Services,
            "connectionGraph": Capability.ConnectionGraph,
        }
        offered = [wanted[c] for c in dict.fromkeys(capabilities) if c in wanted]
        if use_sim_time:
            offered.append(Capability.Time)
        encoding = "cdr" if dialect == "ros2" else "ros1"
        try:
            self.server = foxglove.start_server(
                name=name,
                host=address,
                port=port,
                capabilities=offered,
                server_listener=self,
                supported_encodings=[encoding],
                asset_handler=self._asset if "assets" in capabilities else None,
                context=self._fox,
                message_backlog_size=min(1024, max(8, send_buffer_limit // _TYPICAL_MESSAGE_BYTES)),
            )
        except Exception as exc:  # the SDK raises its own errors for a port in use
            self.node.destroy()
            raise BridgeError(
                f"foxglove_bridge: cannot listen on {address}:{port}: {exc}"
            ) from None
        self.port = int(self.server.port)
        self._tune_sockets()
        large_buffers_from_the_heap()  # the SDK's frames, as the transport's payloads
        logging.getLogger("foxglove").addHandler(self._refusals)
        for key, value in (("port", self.port), ("address", address),
                           ("send_buffer_limit", send_buffer_limit),
                           ("max_qos_depth", max_qos_depth)):  # fmt: skip
            self.node.declare_parameter(key, value, read_only=True)
        if use_sim_time:
            self.node.set_parameters({"use_sim_time": True})  # its clock is /clock's, as ROS's
            self._clock_subscription = self._on_bus(self._follow_clock)
        self._poller = threading.Thread(
            target=self._poll, name="foxglove_bridge graph", daemon=True
        )
        self._poller.start()
        log(f"foxglove_bridge listening at ws://{address}:{self.port}")

    # -- lifetime --------------------------------------------------------------------------
    def stop(self) -> None:
        self._stopping.set()
        self._poller.join(timeout=5.0)
        self.server.stop()
        logging.getLogger("foxglove").removeHandler(self._refusals)
        with self._lock:
            endpoints = [t.subscription for t in self._topics.values() if t.subscription]
            endpoints += [publisher for publisher, _ in self._client_channels.values()]
            endpoints += [e for e in (self._events_subscription, self._clock_subscription) if e]
            self._events_subscription = self._clock_subscription = None
            self._topics.clear()
            self._client_channels.clear()
        if endpoints:
            self._on_bus(lambda: [e.destroy() for e in endpoints])
        self.node.destroy()

    def _tune_sockets(self) -> None:
        """TCP_NODELAY and a send buffer of ``SEND_BUFFER_BYTES`` on the server's listening
        socket, whose connections inherit both (Linux). Nagle's algorithm off, as
        foxglove_bridge 0.x set it on every client socket: the SDK's server leaves it on, and its
        small frames then wait for the client's delayed acknowledgements (16 ms more p50 at
        1 kHz, bench/bench_bridges.py). The send buffer: with one that holds a whole 0.92 MB
        image frame, the image's hop through the bridge measured 1.2 ms p50, against 1.65 with
        the kernel's autotuned one, which starts at 16 KiB (bench/bench_bridges.py). Linux
        only (``/proc/self/fd``); elsewhere nothing is done."""
        import os
        import socket

        try:
            names = os.listdir("/proc/self/fd")
        except OSError:
            return
        for name in names:
            try:
                if not os.readlink(f"/proc/self/fd/{name}").startswith("socket:"):
                    continue
                found = socket.socket(fileno=os.dup(int(name)))
            except (OSError, ValueError):
                continue
            with found:
                try:
                    if found.type == socket.SOCK_STREAM and found.getsockname()[1] == self.port:
                        found.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                        found.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SEND_BUFFER_BYTES)
                except (OSError, IndexError, TypeError):
                    continue

    def _on_bus(self, work: Callable[[], Any]) -> Any:
        box: dict[str, Any] = {}

        def run(_: dict[str, Any]) -> dict[str, Any]:
            box["value"] = work()
            return {}

        reply = self.context.executor.answer(run, {}, 5.0)
        if reply is None:
            raise ClientError("the bus did not answer in time")
        if "error" in reply:
            raise ClientError(str(reply["error"]))
        return box.get("value")

    # -- the graph -------------------------------------------------------------------------
    def _poll(self) -> None:
        trouble = ""  # the last failure said, so that a master down is said once, not per poll
        while not self._stopping.is_set():
            try:
                graph = self.context.graph(timeout_s=0.3)
                if graph.unreadable:  # a master that did not answer in time: nothing went
                    raise RobomodelError(graph.unreadable)
                self._update_channels(graph)
                if "services" in self.capabilities:
                    self._update_services(graph)
                if self._graph_wanted:
                    self.server.publish_connection_graph(self._connection_graph(graph))
                if not self._events:
                    self._publish_watched()
                trouble = ""
            except RobomodelError as exc:
                if str(exc) != trouble:
                    trouble = str(exc)
                    self.log(f"foxglove_bridge: reading the graph failed: {exc}")
            self._stopping.wait(self.graph_period_s)

    def _offered(self, topic: str) -> bool:
        return _listed(topic, self._whitelist)

    def _update_channels(self, graph: Any) -> None:
        foxglove = _import_foxglove()
        own = self.node.fully_qualified_name
        present = {
            name: info for name, info in graph.topics.items()
            if len(info.types) == 1 and self._offered(name)
            and any(e.node != own for e in info.publishers)
        }  # fmt: skip
        with self._lock:
            # A channel goes when its topic left a complete graph; a graph read in part (a
            # bound left entities out) only adds, or a client's subscription would be dropped
            # while its topic is still published.
            gone_names = [n for n in self._topics if n not in present] if graph.complete else []
            gone_names += self._to_advertise_again(present)
            for name in gone_names:
                gone = self._topics.pop(name)
                gone.channel.close()
                if gone.subscription is not None:
                    self._on_bus(gone.subscription.destroy)
            for name, info in present.items():
                type_name = next(iter(info.types))
                if name in self._topics or (name, type_name) in self._refused:
                    continue
                try:
                    msg_type = self._message_type(name, type_name, info)
                    schema = self._schema(msg_type)
                except RobomodelError as exc:
                    self._refused.add((name, type_name))  # said once
                    self.log(f"foxglove_bridge: not offering {name}: {exc}")
                    continue
                channel = foxglove.Channel(
                    name, schema=schema, message_encoding=self._encoding(), context=self._fox
                )
                self._topics[name] = _Topic(channel, msg_type)
            self._refusals.watch(frozenset(t.channel.id() for t in self._topics.values()))
            for name, topic in self._topics.items():  # those the bus did not make in time
                if topic.subscribers and topic.subscription is None:
                    self._subscribe_on_bus(name, topic)

    def _subscribe_on_bus(self, name: str, topic: _Topic) -> None:
        """The bus subscription of a topic with clients; when the bus does not make it in time
        (it is busy), one line, and it is tried again at the next read of the graph."""
        try:
            topic.subscription = self._subscribe(name, topic)
        except ClientError as exc:
            self.log(
                f"foxglove_bridge: subscribing to {name} on the bus failed: {exc}; "
                "trying again at the next read of the graph"
            )

    def _to_advertise_again(self, present: dict[str, Any]) -> list[str]:
        """The topics whose channel a client could not subscribe to (:class:`_RefusedSubscriptions`)
        and that are still published: closed here, they are advertised anew in the same pass."""
        refused = self._refusals.take()
        again = []
        for name, topic in self._topics.items():
            times = self._readvertised.get(name, 0)
            if topic.channel.id() in refused and name in present and times < _READVERTISE_LIMIT:
                self._readvertised[name] = times + 1
                again.append(name)
                self.log(
                    f"foxglove_bridge: advertising {name} again: a client subscribed to it "
                    "before the Foxglove SDK had registered its channel"
                )
        return again

    def _message_type(self, topic: str, type_name: str, info: Any) -> type[Any]:
        from robomodel.runtime.msg import MessageTypeError, get_message_type

        try:
            return get_message_type(type_name)
        except MessageTypeError:
            from robomodel.runtime.type_learning import learn_topic_type

            if not learn_topic_type(self.context, topic, list(info.publishers)):
                raise
        return get_message_type(type_name)

    def _encoding(self) -> str:
        return "cdr" if self.dialect == "ros2" else "ros1"

    def _schema(self, msg_type: type[Any]) -> Any:
        """The channel's schema: the ``ros2msg`` text (fields, then each nested type's) or
        ROS 1's full ``message_definition`` (``ros1msg``)."""
        foxglove = _import_foxglove()
        if self.dialect == "ros2":
            from robomodel.bag.typedefs import ros2msg_definition

            return foxglove.Schema(
                name=msg_type.__typename__, encoding="ros2msg",
                data=ros2msg_definition(msg_type).encode(),
            )  # fmt: skip
        from robomodel.runtime.transport.ros1.ros1_types import ros1_type

        found = ros1_type(msg_type)
        return foxglove.Schema(name=found.name, encoding="ros1msg", data=found.definition.encode())

    def _update_services(self, graph: Any) -> None:
        own = self.node.fully_qualified_name
        present = {
            name: next(iter(info.types)) for name, info in graph.services.items()
            if len(info.types) == 1 and any(e.node != own for e in info.servers)
            and _listed(name, self._service_whitelist)
        }  # fmt: skip
        gone = [n for n in self._services if n not in present] if graph.complete else []
        if gone:
            self.server.remove_services(gone)
            for name in gone:
                del self._services[name]
        added = []
        for name, type_name in sorted(present.items()):
            if name in self._services:
                continue
            try:
                added.append(self._service(name, type_name))
            except RobomodelError as exc:
                self._services[name] = type_name  # said once
                self.log(f"foxglove_bridge: not offering service {name}: {exc}")
                continue
            self._services[name] = type_name
        if added:
            self.server.add_services(added)

    def _service(self, name: str, type_name: str) -> Any:
        foxglove = _import_foxglove()
        from robomodel.runtime.msg.schema import get_service_type

        srv_type = get_service_type(type_name)
        encoding = self._encoding()
        schema = foxglove.ServiceSchema(
            srv_type.__typename__,
            request=foxglove.MessageSchema(encoding=encoding, schema=self._schema(srv_type.Request)),
            response=foxglove.MessageSchema(encoding=encoding, schema=self._schema(srv_type.Response)),
        )  # fmt: skip
        decode, _ = self._codec(srv_type.Request)
        _, encode = self._codec(srv_type.Response)

        def handler(request: Any) -> bytes:
            try:
                message = decode(request.payload)
            except Exception as exc:
                raise ValueError(
                    f"{name}: the request does not decode as {type_name}: {exc}"
                ) from None
            response = self.context.call_service(name, srv_type, message, 10.0)
            return bytes(encode(response))

        return foxglove.Service(name, schema=schema, handler=handler)

    def _codec(self, msg_type: type[Any]) -> tuple[Callable[[bytes], Any], Callable[[Any], bytes]]:
        """Decoder and encoder of the bus's wire format for ``msg_type``."""
        if self.dialect == "ros2":
            from robomodel.runtime.msg.cdr import payload_decoder, payload_encoder

            return payload_decoder(msg_type), payload_encoder(msg_type)
        from robomodel.runtime.transport.ros1.ros1_types import ros1_type

        found = ros1_type(msg_type)
        return found.decode, found.encode

    def _connection_graph(self, graph: Any) -> Any:
        foxglove = _import_foxglove()
        found = foxglove.ConnectionGraph()
        for name, info in graph.topics.items():
            if info.publishers:
                found.set_published_topic(name, sorted({e.node for e in info.publishers}))
            if info.subscribers:
                found.set_subscribed_topic(name, sorted({e.node for e in info.subscribers}))
        for name, info in graph.services.items():
            found.set_advertised_service(name, sorted({e.node for e in info.servers}))
        return found

    # -- subscriptions (the SDK's listener) -------------------------------------------------
    def on_subscribe(self, client: Any, channel: Any) -> None:
        with self._lock:
            topic = self._topics.get(channel.topic)
            if topic is None:
                return
            topic.subscribers.add(client.id)
            if topic.subscription is not None:
                return
            self._subscribe_on_bus(channel.topic, topic)

    def _subscribe(self, name: str, topic: _Topic) -> Any:
        from robomodel.runtime.qos import Durability, QoSProfile

        depth = max(1, min(self.max_qos_depth, 1000))
        qos = QoSProfile(depth, Durability.TRANSIENT_LOCAL)
        channel = topic.channel
        raw = getattr(self.context.transport, "create_raw_subscription", None)
        node = self.node.fully_qualified_name
        if self.dialect == "ros2" and raw is not None:
            from robomodel.runtime.transport.base import OnReceivingThread

            def forward_raw(payload: bytes, info: Any) -> None:
                channel.log(payload, log_time=info.received_timestamp_ns)

            # on Zenoh's thread: the SDK's queues are thread-safe and bounded per client
            on_arrival = OnReceivingThread(forward_raw)
            return self._on_bus(lambda: raw(node, name, topic.msg_type, qos, on_arrival))
        _, encode = self._codec(topic.msg_type)

        def forward(msg: Any) -> None:
            channel.log(bytes(encode(msg)), log_time=time.time_ns())

        return self._on_bus(
            lambda: self.node.create_subscription(topic.msg_type, name, forward, qos)
        )

    def on_unsubscribe(self, client: Any, channel: Any) -> None:
        with self._lock:
            topic = self._topics.get(channel.topic)
            if topic is None:
                return
            topic.subscribers.discard(client.id)
            if topic.subscribers or topic.subscription is None:
                return
            subscription, topic.subscription = topic.subscription, None
        self._on_bus(subscription.destroy)

    # -- client publish ----------------------------------------------------------------------
    def on_client_advertise(self, client: Any, channel: Any) -> None:
        from robomodel.runtime.msg import get_message_type
        from robomodel.runtime.names import expand_topic_name

        try:
            if channel.encoding != self._encoding():
                raise ClientError(
                    f"encoding {channel.encoding!r}; this bridge takes {self._encoding()!r}"
                )
            topic = expand_topic_name(channel.topic, "foxglove_bridge", "/")
            if not _listed(topic, self._client_topics):
                raise ClientError("not on client_topic_whitelist")
            msg_type = get_message_type(channel.schema_name)
            decode, _ = self._codec(msg_type)
            publisher = self._on_bus(lambda: self.node.create_publisher(msg_type, topic, 10))
        except RobomodelError as exc:
            self.log(
                f"foxglove_bridge: client {client.id} cannot publish on {channel.topic}: {exc}"
            )
            return
        with self._lock:
            self._client_channels[(client.id, channel.id)] = (publisher, decode)

    def on_client_unadvertise(self, client: Any, client_channel_id: int) -> None:
        with self._lock:
            entry = self._client_channels.pop((client.id, client_channel_id), None)
            if not any(key[0] == client.id for key in self._client_channels):
                self._flows.pop(client.id, None)  # its last channel (or the client) went
        if entry is not None:
            self._on_bus(entry[0].destroy)

    def client_flow(self, client_id: int) -> tuple[int, int]:
        """(received, dropped) of the messages client ``client_id`` published."""
        with self._lock:
            flow = self._flows.get(client_id)
            return (flow.received, flow.dropped) if flow else (0, 0)

    def _admit(self, client_id: int) -> bool:
        """A token of the client's bucket (``max_client_messages_per_s``), or False: the
        message is dropped, said once per client."""
        rate = self.max_client_messages_per_s
        now = time.monotonic()
        with self._lock:
            flow = self._flows.get(client_id)
            if flow is None:
                flow = self._flows[client_id] = _ClientFlow(tokens=rate, stamp_s=now)
            flow.received += 1
            flow.tokens = min(rate, flow.tokens + (now - flow.stamp_s) * rate)
            flow.stamp_s = now
            if flow.tokens >= 1.0:
                flow.tokens -= 1.0
                return True
            flow.dropped += 1
            first = flow.dropped == 1
        if first:
            self.log(f"foxglove_bridge: client {client_id} publishes more than {rate:g} "
                     "messages a second: the excess is dropped")  # fmt: skip
        return False

    def on_message_data(self, client: Any, client_channel_id: int, data: bytes) -> None:
        with self._lock:
            entry = self._client_channels.get((client.id, client_channel_id))
        if entry is None or not self._admit(client.id):
            return
        publisher, decode = entry
        try:
            msg = decode(data)
        except Exception as exc:
            self.log(f"foxglove_bridge: client {client.id} sent a message that does not decode "
                     f"as {publisher.msg_type.__typename__}: {exc}")  # fmt: skip
            return
        self.context.executor.post(lambda: publisher.publish(msg))

    # -- parameters ----------------------------------------------------------------------------
    def _param_name(self, name: str) -> str:
        """foxglove_bridge's ``/node.param`` as rosapi's ``/node:param`` (ROS 2)."""
        if self.dialect == "ros1":
            return name
        node, sep, param = name.partition(".")
        return f"{node}:{param}" if sep else name

    def _client_name(self, name: str) -> str:
        return name if self.dialect == "ros1" else name.replace(":", ".", 1)

    def _parameter(self, name: str, value: Any) -> Any:
        return _import_foxglove().Parameter(self._client_name(name), value=value)

    def _param_listed(self, name: str) -> bool:
        """Whether ``name`` (robomodel's form) is on ``param_whitelist`` (the clients' form)."""
        return _listed(self._client_name(name), self._param_whitelist)

    def on_get_parameters(
        self, client: Any, param_names: list[str], request_id: str | None = None
    ) -> list[Any]:
        names = [self._param_name(n) for n in param_names] or self.params.names()
        found = []
        for name in filter(self._param_listed, names):
            try:
                found.append(self._parameter(name, self.params.get(name)))
            except (KeyError, RobomodelError):
                continue
        return found

    def on_set_parameters(
        self, client: Any, parameters: list[Any], request_id: str | None = None
    ) -> list[Any]:
        result = []
        for parameter in parameters:
            name = self._param_name(parameter.name)
            if not self._param_listed(name):
                self.log(f"foxglove_bridge: client {client.id} may not set {parameter.name}: "
                         "not on param_whitelist")  # fmt: skip
                continue
            try:
                self.params.set(name, parameter.get_value())
                result.append(self._parameter(name, self.params.get(name)))
            except (KeyError, RobomodelError) as exc:
                self.log(f"foxglove_bridge: setting {parameter.name} failed: {exc}")
        return result

    def on_parameters_subscribe(self, param_names: list[str]) -> None:
        with self._lock:
            for name in filter(self._param_listed, map(self._param_name, param_names)):
                self._watched_params.setdefault(name, object())
            start = self._events and self._watched_params and self._events_subscription is None
        if start:
            subscription = self._on_bus(self._follow_parameter_events)
            with self._lock:
                self._events_subscription = subscription

    def on_parameters_unsubscribe(self, param_names: list[str]) -> None:
        with self._lock:
            for name in param_names:
                self._watched_params.pop(self._param_name(name), None)
            subscription = None
            if not self._watched_params:
                subscription, self._events_subscription = self._events_subscription, None
        if subscription is not None:
            self._on_bus(subscription.destroy)

    def _follow_parameter_events(self) -> Any:
        """On the bus's thread: a subscription to ``/parameter_events`` that sends the watched
        parameters' changes (foxglove_bridge's ``on_parameter_event``, changed ones only)."""
        from robomodel.runtime.msg.types.rcl_interfaces import ParameterEvent
        from robomodel.runtime.param_services import PARAMETER_EVENTS_QOS
        from robomodel.runtime.param_values import from_parameter_value

        def heard(event: Any) -> None:
            node = "/" + event.node.strip("/")
            with self._lock:
                watched = [p for p in event.changed_parameters
                           if f"{node}:{p.name}" in self._watched_params]  # fmt: skip
            if watched:
                self.server.publish_parameter_values([
                    self._parameter(f"{node}:{p.name}", from_parameter_value(p.value))
                    for p in watched
                ])  # fmt: skip

        return self.node.create_subscription(
            ParameterEvent, "/parameter_events", heard, PARAMETER_EVENTS_QOS
        )

    def _follow_clock(self) -> Any:
        """On the bus's thread: a ``/clock`` subscription that sends each time to the clients
        (foxglove_bridge's ``broadcastTime``)."""
        from robomodel.runtime.msg import get_message_type

        clock = get_message_type("rosgraph_msgs/msg/Clock")

        def heard(msg: Any) -> None:
            self.server.broadcast_time(int(msg.clock.sec) * 1_000_000_000 + int(msg.clock.nanosec))

        return self.node.create_subscription(clock, "/clock", heard, 1)

    def _publish_watched(self) -> None:
        with self._lock:
            watched = dict(self._watched_params)
        changed = []
        for name, last in watched.items():
            try:
                value = self.params.get(name)
            except (KeyError, RobomodelError):
                continue
            if value != last:
                changed.append(self._parameter(name, value))
                with self._lock:
                    if name in self._watched_params:
                        self._watched_params[name] = value
        if changed:
            self.server.publish_parameter_values(changed)

    # -- the rest of the listener ---------------------------------------------------------------
    def on_connection_graph_subscribe(self) -> None:
        self._graph_wanted = True

    def on_connection_graph_unsubscribe(self) -> None:
        self._graph_wanted = False

    def on_playback_control_request(self, playback_control_request: Any) -> None:
        return None

    def _asset(self, uri: str) -> bytes | None:
        """A ``package://`` file the allowlist admits, inside its package; None otherwise."""
        if ".." in uri or not _listed(uri, self._assets):
            return None
        try:
            path = self.package_index.resolve(uri)
            return bytes(path.read_bytes())
        except (RobomodelError, OSError):
            return None


def _patterns(name: str, patterns: Sequence[str]) -> list[re.Pattern[str]]:
    """A whitelist's regular expressions, ignoring case as foxglove_bridge's do."""
    try:
        return [re.compile(p, re.IGNORECASE) for p in patterns]
    except re.error as exc:
        raise BridgeError(f"foxglove_bridge: {name}: {exc}") from None


def _listed(name: str, patterns: Sequence[re.Pattern[str]]) -> bool:
    """Whether the whole of ``name`` matches one of ``patterns``."""
    return any(p.fullmatch(name) for p in patterns)
