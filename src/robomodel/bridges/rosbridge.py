"""rosbridge's v2 protocol over a WebSocket: rosbridge_server's ``rosbridge_websocket``.

Clients (roslibjs, roslibpy, browser dashboards) send JSON operations; the ones served are
rosbridge's: ``advertise``/``unadvertise``, ``publish``, ``subscribe`` (with ``throttle_rate``
[ms], ``queue_length`` and ``compression``)/``unsubscribe``, ``call_service`` (with
``timeout`` [s]), ``advertise_service``/``unadvertise_service``/``service_response``,
``set_level``, ``fragment`` (:mod:`.fragments`; ``fragment_size`` on any operation fragments
what the client is sent) and, on ROS 2, the action operations (:mod:`.rosbridge_actions`).
Replies and messages go back as rosbridge sends them (``publish``, ``service_response``,
``status``), the messages as its JSON (:mod:`.json_mapping`) or compressed
(:mod:`.compression`). Calls to ``/rosapi/...`` are answered by the bridge (:mod:`.rosapi`).

Everything the bus does runs on the context's spinning thread (the launch's main loop): a
client's thread hands its request over and waits, and bus callbacks only encode and queue. Each
client has a receiving thread (the WebSocket library's) and a sending one that drains its
bounded :class:`~.outbox.Outbox`; the bounds are :class:`~.limits.BridgeLimits`'.
"""

from __future__ import annotations

import contextlib
import itertools
import json
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from robomodel.bridges.compression import (
    COMPRESSIONS,
    cbor_frame,
    cbor_raw_frame,
    png_frame,
)
from robomodel.bridges.exceptions import BridgeError, ClientError
from robomodel.bridges.fragments import Reassembly, split
from robomodel.bridges.json_mapping import Dialect, message_from_json, message_to_json
from robomodel.bridges.limits import BridgeLimits
from robomodel.bridges.outbox import Frame, Outbox
from robomodel.bridges.rosapi import PREFIX, Rosapi, RosapiParams
from robomodel.bridges.rosbridge_actions import ActionOps
from robomodel.errors import MissingDependencyError, RobomodelError

__all__ = ["RosbridgeServer"]

# rosbridge's status levels, most verbose first; a client hears the ones at or above its own
_LEVELS = ("info", "warning", "error", "none")
_BUS_TIMEOUT_S = 5.0
_MAX_CALLS_IN_FLIGHT = 16  # per client: service calls waiting for their answer
_CALL_TIMEOUT_S = 10.0  # a call_service without a (positive) timeout
_MAX_CALL_TIMEOUT_S = 600.0


@dataclass
class _Subscription:
    """One client's subscription to a topic (the ids its ``subscribe`` operations gave)."""

    handle: Any  # robomodel.runtime.node.Subscription
    # id -> (throttle [ms], queue length, compression)
    options: dict[str, tuple[int, int, str]] = field(default_factory=dict)
    last_sent_s: float = 0.0
    png_refused: bool = False  # a message too large for png was said once

    @property
    def throttle_s(self) -> float:
        """rosbridge merges a client's subscriptions of one topic: the smallest throttle."""
        return min((t for t, _, _ in self.options.values()), default=0) / 1000.0

    @property
    def queue_length(self) -> int:
        """... and the largest queue (0: bounded by the send buffer alone)."""
        return max((q for _, q, _ in self.options.values()), default=0)

    @property
    def compression(self) -> str:
        """... and the last of none, png, cbor, cbor-raw that one of them asked for."""
        asked = {c for _, _, c in self.options.values()}
        return next(c for c in reversed(COMPRESSIONS) if c in asked or c == "none")


class RosbridgeServer:
    """The WebSocket server; one per ``rosbridge_websocket`` node.

    Args:
        context: The bus (a :class:`robomodel.runtime.Context` someone spins).
        params: The parameters rosapi serves (:class:`.rosapi.Ros1Params` or
            :class:`.rosapi.Ros2Params`).
        dialect: ``ros1`` or ``ros2``: the JSON's time fields and rosapi's names.
        name: The node's name; namespace: its namespace.
        address: The interface to listen on (loopback unless told otherwise).
        port: The TCP port (9090 as rosbridge's; 0 picks a free one, see :attr:`port`).
        limits: The bounds.
        log: Where the one-line reports go.
    """

    def __init__(
        self,
        context: Any,
        params: RosapiParams,
        *,
        dialect: Dialect,
        name: str = "rosbridge_websocket",
        namespace: str = "/",
        address: str = "127.0.0.1",
        port: int = 9090,
        limits: BridgeLimits | None = None,
        log: Callable[[str], None] = print,
    ) -> None:
        try:
            from websockets.sync.server import serve
        except ImportError:
            raise MissingDependencyError("websockets", "bridges", "rosbridge_server") from None
        self.context = context
        self.dialect = dialect
        self.limits = limits = limits or BridgeLimits()
        self.log = log
        self.node = context.create_node(name, namespace)
        self.rosapi = Rosapi(
            lambda: context.graph(timeout_s=0.3), params, dialect, self.node.get_clock().now_ns
        )
        self._sessions: set[_Session] = set()
        self._lock = threading.Lock()
        try:
            self._server = serve(
                self._serve_client,
                address,
                port,
                max_size=limits.max_frame_bytes,
                compression=None,
                ping_interval=None,  # roslibpy's and roslibjs's peers may not answer pings
                close_timeout=2.0,  # a refused client does not hold its thread for long
            )
        except OSError as exc:
            self.node.destroy()
            raise BridgeError(
                f"rosbridge: cannot listen on {address}:{port}: {exc.strerror}"
            ) from None
        self.address = address
        self.port = int(self._server.socket.getsockname()[1])
        # the real node's parameters, with the port it listens on (ros2 param get, rosapi)
        for key, value in (("port", self.port), ("address", address),
                           ("max_message_size", limits.max_frame_bytes),
                           ("send_buffer_limit", limits.send_buffer_bytes)):  # fmt: skip
            self.node.declare_parameter(key, value, read_only=True)
        self._thread = threading.Thread(
            target=self._server.serve_forever, name="rosbridge server", daemon=True
        )
        self._thread.start()
        log(f"Rosbridge WebSocket server started at ws://{address}:{self.port}")

    # -- running ---------------------------------------------------------------------------
    def on_bus(self, work: Callable[[], Any]) -> Any:
        """Run ``work()`` on the bus's spinning thread and return its result (ClientError with
        its message if it raised)."""
        box: dict[str, Any] = {}

        def run(_: dict[str, Any]) -> dict[str, Any]:
            box["value"] = work()
            return {}

        reply = self.context.executor.answer(run, {}, _BUS_TIMEOUT_S)
        if reply is None:
            raise ClientError("the bus did not answer in time")
        if "error" in reply:
            raise ClientError(str(reply["error"]))
        return box.get("value")

    @property
    def clients(self) -> int:
        with self._lock:
            return len(self._sessions)

    def dropped(self) -> int:
        """Messages dropped so far for the clients connected now (slow readers)."""
        with self._lock:
            return sum(s.outbox.dropped for s in self._sessions)

    def stop(self) -> None:
        self._server.shutdown()
        self._thread.join(timeout=5.0)
        with self._lock:
            sessions = list(self._sessions)
        for session in sessions:
            session.close()
        self.node.destroy()

    def _serve_client(self, connection: Any) -> None:
        host, port_number = connection.remote_address[:2]
        peer = f"{host}:{port_number}"
        with self._lock:
            full = len(self._sessions) >= self.limits.max_clients
            session = None if full else _Session(self, connection, peer)
            if session is not None:
                self._sessions.add(session)
        if session is None:
            self.log(f"rosbridge: client {peer} refused: {self.limits.max_clients} clients already")
            connection.close(1013, "too many clients")
            return
        try:
            session.run()
        finally:
            session.close()
            with self._lock:
                self._sessions.discard(session)


class _Session:
    """One connected client: its endpoints on the bus and its outgoing queue."""

    def __init__(self, server: RosbridgeServer, connection: Any, peer: str) -> None:
        self.server = server
        self.connection = connection
        self.peer = peer
        self.outbox = Outbox(server.limits.send_buffer_bytes)
        self.level = "error"
        self.subscriptions: dict[str, _Subscription] = {}
        self.publishers: dict[str, Any] = {}
        self.services: dict[str, Any] = {}
        self.pending: dict[str, tuple[Any, Any]] = {}  # call id -> (Deferred, service type)
        self.actions = ActionOps(self)
        self.reassembly = Reassembly(server.limits)
        self.fragment_size: int | None = None  # rosbridge's: set by any operation that gives it
        self._fragmented_ids = itertools.count(1)  # next() is atomic: bus and client threads
        self._calls = threading.BoundedSemaphore(_MAX_CALLS_IN_FLIGHT)
        self._next_call = 0
        self._tokens = server.limits.max_ops_per_s
        self._refilled_s = time.monotonic()
        self.closed = threading.Event()
        self._sender = threading.Thread(
            target=self._send_loop, name=f"rosbridge to {peer}", daemon=True
        )
        self._sender.start()
        self._ops: dict[str, Callable[[dict[str, Any]], None]] = {
            "advertise": self.advertise,
            "unadvertise": self.unadvertise,
            "publish": self.publish,
            "subscribe": self.subscribe,
            "unsubscribe": self.unsubscribe,
            "call_service": self.call_service,
            "advertise_service": self.advertise_service,
            "unadvertise_service": self.unadvertise_service,
            "service_response": self.service_response,
            "set_level": self.set_level,
            "fragment": self.fragment,
            "send_action_goal": self.actions.send_action_goal,
            "cancel_action_goal": self.actions.cancel_action_goal,
            "advertise_action": self.actions.advertise_action,
            "unadvertise_action": self.actions.unadvertise_action,
            "action_feedback": self.actions.action_feedback,
            "action_result": self.actions.action_result,
        }

    # -- the connection --------------------------------------------------------------------
    def run(self) -> None:
        from websockets.exceptions import ConnectionClosed

        try:
            for frame in self.connection:
                if not self._admit():
                    self.server.log(
                        f"rosbridge: client {self.peer} sent more than "
                        f"{self.server.limits.max_ops_per_s:g} operations a second: closed"
                    )
                    self.connection.close(1008, "too many operations a second")
                    return
                self.handle(frame)
        except ConnectionClosed as exc:
            if exc.sent is not None and exc.sent.code == 1009:
                self.server.log(
                    f"rosbridge: client {self.peer} sent a frame over "
                    f"{self.server.limits.max_frame_bytes} bytes: closed"
                )

    def _admit(self) -> bool:
        """A token bucket: ``max_ops_per_s`` a second, as many in a burst."""
        rate = self.server.limits.max_ops_per_s
        now = time.monotonic()
        self._tokens = min(rate, self._tokens + (now - self._refilled_s) * rate)
        self._refilled_s = now
        if self._tokens < 1.0:
            return False
        self._tokens -= 1.0
        return True

    def _send_loop(self) -> None:
        while not self.closed.is_set():
            frame = self.outbox.take(0.2)
            if frame is None:
                continue
            try:
                for part in frame if isinstance(frame, tuple) else (frame,):
                    self.connection.send(part)
            except Exception:  # the client went away: the receiving side ends the session
                return

    def send(
        self, message: dict[str, Any], *, key: str | None = None, queue_length: int = 0
    ) -> None:
        text = json.dumps(message, allow_nan=False)
        self.outbox.put(self.text_frame(text, message.get("id")), key=key,
                        queue_length=queue_length)  # fmt: skip

    def text_frame(self, text: str, message_id: Any) -> Frame:
        """``text`` as it goes to the client: in fragments when it is longer than the
        client's ``fragment_size``."""
        size = self.fragment_size
        if size is None or len(text) <= size:
            return text
        if message_id is None:
            message_id = next(self._fragmented_ids)
        return split(text, size, message_id)

    def status(self, level: str, text: str, op_id: Any = None) -> None:
        """A ``status`` line, if the client's level lets it through (rosbridge's default:
        errors only)."""
        if _LEVELS.index(level) < _LEVELS.index(self.level):
            return
        message: dict[str, Any] = {"op": "status", "level": level, "msg": text}
        if op_id is not None:
            message["id"] = op_id
        self.send(message)

    def close(self) -> None:
        if self.closed.is_set():
            return
        self.closed.set()
        self.outbox.close()
        self.reassembly.clear()
        work = [s.handle.destroy for s in self.subscriptions.values()]
        work += [e.destroy for e in [*self.publishers.values(), *self.services.values()]]
        work += self.actions.close()
        self.subscriptions.clear()
        self.publishers.clear()
        self.services.clear()
        if work:
            # a bus that is gone (shutdown) took its endpoints with it
            with contextlib.suppress(ClientError):
                self.server.on_bus(lambda: [w() for w in work])
        self.connection.close()

    # -- operations ------------------------------------------------------------------------
    def handle(self, frame: str | bytes, *, joined: bool = False) -> None:
        """One operation; ``joined``: the text of a message that came in fragments."""
        op_id = None
        try:
            try:
                message = json.loads(frame)
            except ValueError:
                raise ClientError(f"not JSON: {str(frame)[:60]!r}") from None
            except RecursionError:
                raise ClientError("JSON nested deeper than the bridge reads") from None
            if not isinstance(message, dict):
                raise ClientError("an operation must be a JSON object")
            op_id = message.get("id")
            op = message.get("op")
            handler = self._ops.get(op) if isinstance(op, str) else None
            if handler is None:
                raise ClientError(f"unknown op {op!r}; the ops are: {', '.join(sorted(self._ops))}")
            if joined and op == "fragment":
                raise ClientError("fragment: a message in fragments may not be a fragment")
            if "fragment_size" in message:
                self._set_fragment_size(message["fragment_size"])
            handler(message)
        except ClientError as exc:
            self.status("error", str(exc), op_id)

    def _set_fragment_size(self, value: Any) -> None:
        low = self.server.limits.min_fragment_bytes
        if value is not None and (
            isinstance(value, bool) or not isinstance(value, int) or value < low
        ):
            raise ClientError(f"fragment_size must be a whole number >= {low}, got {value!r}")
        self.fragment_size = value

    def fragment(self, message: dict[str, Any]) -> None:
        text = self.reassembly.add(message)
        if text is not None:
            self.handle(text, joined=True)

    def name_of(self, message: dict[str, Any], key: str) -> str:
        """A topic or service name from the client, valid as a ROS name (``/`` prefixed)."""
        from robomodel.runtime.names import expand_topic_name

        name = message.get(key)
        if not isinstance(name, str) or not name:
            raise ClientError(f"{message.get('op')}: '{key}' must be a non-empty name")
        try:
            return expand_topic_name(name, "rosbridge", "/")
        except RobomodelError as exc:
            raise ClientError(f"{message.get('op')}: {exc}") from None

    def count_endpoints(self) -> None:
        count = len(self.subscriptions) + len(self.publishers) + len(self.services)
        count += self.actions.endpoints()
        if count >= self.server.limits.max_endpoints:
            raise ClientError(
                f"this client has {count} topics and services already (the bridge's bound)"
            )

    def _message_type(self, topic: str, given: Any) -> type[Any]:
        from robomodel.runtime.msg import get_message_type

        name = given if isinstance(given, str) and given else None
        info = None
        if name is None:
            info = self.server.context.graph(timeout_s=0.3).topics.get(topic)
            if info is None or not info.types:
                raise ClientError(
                    f"cannot infer the type of {topic}: it has no publisher yet; give 'type'"
                )
            name = sorted(info.types)[0]
        try:
            return get_message_type(name)
        except RobomodelError as exc:
            if info is None:
                info = self.server.context.graph(timeout_s=0.3).topics.get(topic)
            if info is not None and info.publishers:
                from robomodel.runtime.type_learning import learn_topic_type

                if learn_topic_type(self.server.context, topic, list(info.publishers)):
                    return get_message_type(name)
            raise ClientError(f"{topic}: {exc}") from None

    def advertise(self, message: dict[str, Any]) -> None:
        topic = self.name_of(message, "topic")
        msg_type = self._message_type(topic, message.get("type") or "")
        existing = self.publishers.get(topic)
        if existing is not None:
            if existing.msg_type is not msg_type:
                raise ClientError(
                    f"advertise: {topic} is advertised as {existing.msg_type.__typename__} already"
                )
            return
        self.count_endpoints()
        from robomodel.runtime.qos import Durability, QoSProfile

        depth = message.get("queue_size", 100)
        depth = depth if isinstance(depth, int) and 0 < depth <= 10_000 else 100
        latch = message.get("latch") is True
        qos = QoSProfile(depth, Durability.TRANSIENT_LOCAL if latch else Durability.VOLATILE)
        node = self.server.node
        self.publishers[topic] = self.server.on_bus(
            lambda: node.create_publisher(msg_type, topic, qos)
        )

    def unadvertise(self, message: dict[str, Any]) -> None:
        topic = self.name_of(message, "topic")
        publisher = self.publishers.pop(topic, None)
        if publisher is None:
            raise ClientError(f"unadvertise: {topic} is not advertised by this client")
        self.server.on_bus(publisher.destroy)

    def publish(self, message: dict[str, Any]) -> None:
        topic = self.name_of(message, "topic")
        publisher = self.publishers.get(topic)
        if publisher is None:  # rosbridge advertises on a first publish, with the graph's type
            self.advertise({"op": "advertise", "topic": topic, "latch": message.get("latch")})
            publisher = self.publishers[topic]
        msg = message_from_json(publisher.msg_type, message.get("msg"), self.server.dialect)
        self.server.context.executor.post(lambda: publisher.publish(msg))

    def subscribe(self, message: dict[str, Any]) -> None:
        topic = self.name_of(message, "topic")
        throttle = _whole(message, "throttle_rate")
        queue_length = _whole(message, "queue_length")
        sub_id = str(message.get("id", f"subscribe:{topic}"))
        compression = message.get("compression") or "none"
        if compression not in COMPRESSIONS:
            raise ClientError(f"subscribe {topic}: compression {compression!r}; "
                              f"the compressions are: {', '.join(COMPRESSIONS)}")  # fmt: skip
        found = self.subscriptions.get(topic)
        if found is not None:
            found.options[sub_id] = (throttle, queue_length, compression)
            return
        self.count_endpoints()
        msg_type = self._message_type(topic, message.get("type"))
        entry = _Subscription(handle=None, options={sub_id: (throttle, queue_length, compression)})
        encode = _bus_encoder(msg_type, self.server.dialect)

        def deliver(msg: Any) -> None:
            now = time.monotonic()
            if entry.throttle_s and now - entry.last_sent_s < entry.throttle_s:
                return
            entry.last_sent_s = now
            self.outbox.put(
                self._published(topic, msg, entry, encode), key=topic,
                queue_length=entry.queue_length,
            )  # fmt: skip

        from robomodel.runtime.qos import Durability, QoSProfile

        qos = QoSProfile(max(queue_length, 10), Durability.TRANSIENT_LOCAL)
        node = self.server.node
        self.subscriptions[topic] = entry
        try:
            entry.handle = self.server.on_bus(
                lambda: node.create_subscription(msg_type, topic, deliver, qos)
            )
        except ClientError:
            del self.subscriptions[topic]
            raise

    def _published(
        self, topic: str, msg: Any, entry: _Subscription, encode: Callable[[Any], bytes]
    ) -> Frame:
        """The ``publish`` operation of ``msg`` as the subscription's compression has it."""
        dialect = self.server.dialect
        compression = entry.compression
        if compression == "cbor":
            return cbor_frame(topic, msg, dialect)
        if compression == "cbor-raw":
            return cbor_raw_frame(topic, encode(msg), self.server.node.get_clock().now_ns())
        body = {"op": "publish", "topic": topic, "msg": message_to_json(msg, dialect)}
        text = json.dumps(body, allow_nan=False)
        if compression == "png":
            bound = self.server.limits.max_png_bytes
            if len(text) <= bound:
                text = png_frame(text)
            elif not entry.png_refused:
                entry.png_refused = True
                self.status("warning", f"subscribe {topic}: a message of {len(text)} bytes is "
                            f"over png's {bound}; such messages go as JSON")  # fmt: skip
        return self.text_frame(text, None)

    def unsubscribe(self, message: dict[str, Any]) -> None:
        topic = self.name_of(message, "topic")
        entry = self.subscriptions.get(topic)
        if entry is None:
            raise ClientError(f"unsubscribe: this client is not subscribed to {topic}")
        sub_id = message.get("id")
        if sub_id is not None and len(entry.options) > 1:
            entry.options.pop(str(sub_id), None)
            return
        del self.subscriptions[topic]
        self.server.on_bus(entry.handle.destroy)

    def call_service(self, message: dict[str, Any]) -> None:
        service = self.name_of(message, "service")
        args = message.get("args") or {}
        if isinstance(args, list):  # rosbridge takes the request's fields in order too
            args = {"__values__": args}
        if not isinstance(args, dict):
            raise ClientError(f"call_service {service}: 'args' must be a JSON object")
        timeout_s = message.get("timeout")
        if timeout_s is not None and (
            isinstance(timeout_s, bool) or not isinstance(timeout_s, int | float)
        ):
            raise ClientError(
                f"call_service {service}: 'timeout' must be a number of seconds, got {timeout_s!r}"
            )
        if timeout_s is None or not timeout_s > 0:  # roslibjs: none or <= 0 is no timeout
            timeout_s = _CALL_TIMEOUT_S if timeout_s is None else _MAX_CALL_TIMEOUT_S
        if not self._calls.acquire(blocking=False):
            raise ClientError(
                f"call_service {service}: {_MAX_CALLS_IN_FLIGHT} calls of this client wait "
                "for their answers already"
            )
        op_id = message.get("id")
        given_type = message.get("type")
        threading.Thread(
            target=self._call,
            args=(service, args, op_id, given_type, float(min(timeout_s, _MAX_CALL_TIMEOUT_S))),
            name=f"rosbridge call {service}", daemon=True,
        ).start()  # fmt: skip

    def _call(
        self, service: str, args: dict[str, Any], op_id: Any, given: Any, timeout_s: float
    ) -> None:
        reply: dict[str, Any] = {"op": "service_response", "service": service}
        if op_id is not None:
            reply["id"] = op_id
        try:
            if service.startswith(PREFIX):
                values = self.server.rosapi.answer(service, args)
            else:
                values = self._call_bus(service, args, given, timeout_s)
            reply.update(values=values, result=True)
        except RobomodelError as exc:
            reply.update(values=str(exc), result=False)
        finally:
            self._calls.release()
        self.send(reply)

    def _call_bus(
        self, service: str, args: dict[str, Any], given: Any, timeout_s: float
    ) -> dict[str, Any]:
        from robomodel.runtime.msg.schema import get_service_type

        name = given if isinstance(given, str) and given else None
        if name is None:
            info = self.server.context.graph(timeout_s=0.3).services.get(service)
            if info is None or not info.types:
                raise ClientError(f"Service {service} does not exist")
            name = sorted(info.types)[0]
        srv_type = get_service_type(name)
        if "__values__" in args:
            values = args["__values__"]
            names = [n for n, _ in srv_type.Request.__fields__]
            args = dict(zip(names, values, strict=False))
        request = message_from_json(srv_type.Request, args, self.server.dialect)
        response = self.server.context.call_service(service, srv_type, request, timeout_s)
        return message_to_json(response, self.server.dialect)

    def advertise_service(self, message: dict[str, Any]) -> None:
        from robomodel.runtime.msg.schema import get_service_type
        from robomodel.runtime.transport.base import Deferred

        service = self.name_of(message, "service")
        type_name = message.get("type")
        if not isinstance(type_name, str) or not type_name:
            raise ClientError(f"advertise_service {service}: 'type' must name a service type")
        try:
            srv_type = get_service_type(type_name)
        except RobomodelError as exc:
            raise ClientError(f"advertise_service {service}: {exc}") from None
        if service in self.services:
            raise ClientError(f"advertise_service: {service} is advertised by this client already")
        self.count_endpoints()
        dialect = self.server.dialect

        def handler(request: Any) -> Deferred:
            self._next_call += 1
            call_id = f"service_request:{service}:{self._next_call}"
            deferred = Deferred()
            self.pending[call_id] = (deferred, srv_type)
            self.send({"op": "call_service", "id": call_id, "service": service,
                       "args": message_to_json(request, dialect)})  # fmt: skip
            return deferred

        node = self.server.node
        self.services[service] = self.server.on_bus(
            lambda: node.create_service(srv_type, service, handler)
        )

    def unadvertise_service(self, message: dict[str, Any]) -> None:
        service = self.name_of(message, "service")
        server = self.services.pop(service, None)
        if server is None:
            raise ClientError(f"unadvertise_service: {service} is not advertised by this client")
        self.server.on_bus(server.destroy)

    def service_response(self, message: dict[str, Any]) -> None:
        call_id = message.get("id")
        waiting = self.pending.pop(str(call_id), None) if call_id is not None else None
        if waiting is None:
            raise ClientError(f"service_response: no call with id {call_id!r} waits for one")
        deferred, srv_type = waiting
        if message.get("result") is False:
            # the caller hears no answer (rosbridge's caller gets an exception)
            self.server.log(
                f"rosbridge: client {self.peer} failed a call of {message.get('service')}"
            )
            return
        response = message_from_json(srv_type.Response, message.get("values"), self.server.dialect)
        self.server.context.executor.post(lambda: deferred.resolve(response))

    def set_level(self, message: dict[str, Any]) -> None:
        level = message.get("level")
        if level not in _LEVELS:
            raise ClientError(f"set_level: level {level!r}; the levels are: {', '.join(_LEVELS)}")
        self.level = level


def _bus_encoder(msg_type: type[Any], dialect: Dialect) -> Callable[[Any], bytes]:
    """The serialisation of ``msg_type`` on the bus (``cbor-raw``'s bytes): CDR on ROS 2,
    ROS 1's on ROS 1."""
    if dialect == "ros2":
        from robomodel.runtime.msg.cdr import payload_encoder

        return payload_encoder(msg_type)
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    return ros1_type(msg_type).encode


def _whole(message: dict[str, Any], key: str) -> int:
    """A non-negative whole-number option (0 when absent)."""
    value = message.get(key, 0)
    if value is None:
        return 0
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise ClientError(
            f"{message.get('op')}: '{key}' must be a whole number >= 0, got {value!r}"
        )
    return value
