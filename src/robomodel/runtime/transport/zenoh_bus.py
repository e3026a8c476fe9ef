"""The Zenoh transport: robomodel processes on one machine or several, peer to peer.

Discovery needs no configuration and no router, and never leaves loopback unless asked:
multicast scouting is off; the first process of a domain also listens on a well-known loopback
port (``17470 + domain_id``), later ones connect to it, and Zenoh's gossip then links every
peer directly, so the group survives the first process exiting. ``connect`` endpoints (or
``ROBOMODEL_CONNECT=tcp/host:port``) join processes on other machines; ``listen`` endpoints
(``ROBOMODEL_LISTEN``) accept them.

Key expressions, under ``rm/<domain>``: ``t/<topic>`` carries CDR payloads with an attachment
``type|publisher id|sequence``; liveliness tokens ``@g/<pub|sub|node>/...`` describe the graph;
``@l/<topic>/<publisher id>`` serves the history of transient-local publishers to late
subscribers; ``@p/<node>`` answers parameter calls (JSON).
"""

from __future__ import annotations

import collections
import json
import logging
import os
import threading
import uuid
from collections.abc import Callable, Sequence
from typing import Any

from robomodel.errors import MissingDependencyError, RobomodelError
from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import CDRError, Message, deserialize, serialize
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.transport.base import (
    Endpoint,
    Graph,
    ParameterHandler,
    PublisherHandle,
    SubscriptionHandle,
    Transport,
)

__all__ = ["ANCHOR_BASE_PORT", "ZenohTransport", "domain_id_from_env"]

log = logging.getLogger("robomodel.runtime")
ANCHOR_BASE_PORT = 17470


def domain_id_from_env() -> int:
    """``ROBOMODEL_DOMAIN_ID``, else ``ROS_DOMAIN_ID``, else 0."""
    text = os.environ.get("ROBOMODEL_DOMAIN_ID") or os.environ.get("ROS_DOMAIN_ID") or "0"
    try:
        value = int(text)
    except ValueError:
        raise RobomodelError(f"domain id must be an integer 0..232, got '{text}'") from None
    if not 0 <= value <= 232:
        raise RobomodelError(f"domain id must be in 0..232, got {value}")
    return value


def _mangle(name: str) -> str:
    return name.replace("/", "%") or "%"


def _unmangle(text: str) -> str:
    return text.replace("%", "/")


def _import_zenoh() -> Any:
    try:
        import zenoh
    except ImportError:
        raise MissingDependencyError("eclipse-zenoh", "bus", "the zenoh bus") from None
    return zenoh


def _config(zenoh: Any, listen: Sequence[str], connect: Sequence[str]) -> Any:
    conf = zenoh.Config()
    conf.insert_json5("mode", '"peer"')
    conf.insert_json5("scouting/multicast/enabled", "false")
    conf.insert_json5("scouting/gossip/enabled", "true")
    conf.insert_json5("listen/endpoints", json.dumps(list(listen)))
    conf.insert_json5("listen/exit_on_failure", "true")
    conf.insert_json5("connect/endpoints", json.dumps(list(connect)))
    return conf


def _env_list(name: str) -> list[str]:
    return [p.strip() for p in os.environ.get(name, "").split(",") if p.strip()]


class _ZPub(PublisherHandle):
    def __init__(self, bus: ZenohTransport, endpoint: Endpoint, msg_type: type[Message]) -> None:
        self._bus = bus
        self._type = msg_type
        self._id = uuid.uuid4().hex[:16]
        self._seq = 0
        self._lock = threading.Lock()
        session, prefix = bus.session, bus.prefix
        self._pub = session.declare_publisher(f"{prefix}/t{endpoint.topic}")
        self._token = session.liveliness().declare_token(bus.graph_key("pub", endpoint))
        self._history: collections.deque[tuple[bytes, bytes]] | None = None
        self._queryable = None
        self._history_token = None
        if endpoint.qos.durability is Durability.TRANSIENT_LOCAL:
            self._history = collections.deque(maxlen=max(1, endpoint.qos.depth))
            self._history_key = f"{prefix}/@l{endpoint.topic}/{self._id}"
            self._queryable = session.declare_queryable(self._history_key, self._serve_history)
            # Announces the history: subscribers query it whenever it becomes reachable.
            self._history_token = session.liveliness().declare_token(self._history_key)
        self._endpoint = endpoint

    def _serve_history(self, query: Any) -> None:
        with self._lock:
            history = list(self._history or ())
        # Each publisher answers on its own key: replies on the query's wildcard key would be
        # consolidated into one, and a late subscriber would get one broadcaster's /tf_static.
        for payload, attachment in history:
            query.reply(self._history_key, payload, attachment=attachment)

    def publish(self, msg: Message) -> None:
        if not isinstance(msg, self._type):
            raise RobomodelError(
                f"publisher on {self._endpoint.topic} has type {self._type.__typename__}, "
                f"got {type(msg).__name__}"
            )
        payload = serialize(msg)
        with self._lock:
            self._seq += 1
            attachment = f"{self._type.__typename__}|{self._id}|{self._seq}".encode()
            if self._history is not None:
                self._history.append((payload, attachment))
        self._pub.put(payload, attachment=attachment)

    def destroy(self) -> None:
        for handle in (self._history_token, self._queryable, self._token, self._pub):
            if handle is not None:
                try:
                    handle.undeclare()
                except Exception:  # already closed with the session
                    log.debug("undeclare failed", exc_info=True)


class _ZSub(SubscriptionHandle):
    def __init__(
        self,
        bus: ZenohTransport,
        endpoint: Endpoint,
        msg_type: type[Message],
        deliver: Callable[[Message], None],
    ) -> None:
        self._bus = bus
        self._endpoint = endpoint
        self._type = msg_type
        self._deliver = deliver
        self._last_seq: dict[str, int] = {}
        self._alive = True
        # KEEP_LAST: at most `depth` samples wait for the executor; a slow subscriber drops
        # the oldest (as DDS does) instead of falling further and further behind.
        self._pending: collections.deque[tuple[bytes, bytes]] = collections.deque(
            maxlen=max(1, endpoint.qos.depth)
        )
        self._pending_lock = threading.Lock()
        self._scheduled = False
        self.dropped = 0
        session, prefix = bus.session, bus.prefix
        self._sub = session.declare_subscriber(f"{prefix}/t{endpoint.topic}", self._on_sample)
        self._token = session.liveliness().declare_token(bus.graph_key("sub", endpoint))
        self._history_sub = None
        if endpoint.qos.durability is Durability.TRANSIENT_LOCAL:
            # As DDS on matching a writer: every latched publisher's history is queried when its
            # token becomes visible, now (history=True) or later (a publisher that starts
            # later, or a peer reached again after the process that linked us exited).
            self._history_sub = session.liveliness().declare_subscriber(
                f"{prefix}/@l{endpoint.topic}/*", self._on_history_token, history=True
            )

    def _on_sample(self, sample: Any) -> None:  # a Zenoh thread
        payload = sample.payload.to_bytes()
        attachment = sample.attachment.to_bytes() if sample.attachment is not None else b""
        with self._pending_lock:
            if len(self._pending) == self._pending.maxlen:
                self.dropped += 1
            self._pending.append((payload, attachment))
            if self._scheduled:
                return
            self._scheduled = True
        self._bus.executor.post(self._drain)

    def _drain(self) -> None:
        """On the executor: handle what is pending now; later arrivals get their own turn."""
        with self._pending_lock:
            batch = list(self._pending)
            self._pending.clear()
            self._scheduled = False
        for payload, attachment in batch:
            self._handle(payload, attachment)

    def _on_history_token(self, sample: Any) -> None:  # a Zenoh thread
        zenoh = _import_zenoh()
        if not self._alive or sample.kind != zenoh.SampleKind.PUT:
            return
        # No consolidation: the publisher's whole history (depth samples on its one key).
        self._bus.session.get(
            str(sample.key_expr),
            self._on_reply,
            consolidation=zenoh.ConsolidationMode.NONE,
            timeout=2.0,
        )

    def _on_reply(self, reply: Any) -> None:  # a Zenoh thread
        sample = reply.ok
        if sample is not None:
            self._on_sample(sample)

    def _handle(self, payload: bytes, attachment: bytes) -> None:
        if not self._alive:
            return
        type_name, pub_id, seq = "", "", 0
        parts = attachment.decode("utf-8", "replace").split("|")
        if len(parts) == 3 and parts[2].isdigit():
            type_name, pub_id, seq = parts[0], parts[1], int(parts[2])
        if type_name and type_name != self._type.__typename__:
            self._bus.warn_once(
                (self._endpoint.topic, type_name),
                "topic %s is published as %s but subscribed as %s; messages are not delivered",
                self._endpoint.topic,
                type_name,
                self._type.__typename__,
            )
            return
        if pub_id:
            if seq <= self._last_seq.get(pub_id, 0):
                return  # already delivered (history replay overlapping live data)
            self._last_seq[pub_id] = seq
        try:
            msg = deserialize(payload, self._type)
        except CDRError as exc:
            self._bus.warn_once(
                (self._endpoint.topic, "malformed", pub_id),
                "dropping a malformed %s payload on %s: %s",
                self._type.__typename__,
                self._endpoint.topic,
                exc,
            )
            return
        self._deliver(msg)

    def destroy(self) -> None:
        self._alive = False
        for handle in (self._history_sub, self._token, self._sub):
            if handle is None:
                continue
            try:
                handle.undeclare()
            except Exception:
                log.debug("undeclare failed", exc_info=True)


class ZenohTransport(Transport):
    """Peer-to-peer transport over Zenoh (see the module docstring)."""

    name = "zenoh"

    def __init__(
        self,
        executor: Executor,
        *,
        domain_id: int | None = None,
        connect: Sequence[str] = (),
        listen: Sequence[str] = (),
    ) -> None:
        zenoh = _import_zenoh()
        self.executor = executor
        self.domain_id = domain_id_from_env() if domain_id is None else domain_id
        self.prefix = f"rm/{self.domain_id}"
        connect = [*connect, *_env_list("ROBOMODEL_CONNECT")]
        listen = ["tcp/127.0.0.1:0", *listen, *_env_list("ROBOMODEL_LISTEN")]
        anchor = f"tcp/127.0.0.1:{ANCHOR_BASE_PORT + self.domain_id}"
        try:
            self.session = zenoh.open(_config(zenoh, [*listen, anchor], connect))
            self.is_anchor = True
        except Exception:  # the anchor port is taken: another process anchors this domain
            self.session = zenoh.open(_config(zenoh, listen, [*connect, anchor]))
            self.is_anchor = False
        self._warned: set[tuple[str, ...]] = set()
        self._node_handles: dict[str, tuple[Any, ...]] = {}

    def warn_once(self, key: tuple[str, ...], fmt: str, *args: object) -> None:
        if key not in self._warned:
            self._warned.add(key)
            log.warning(fmt, *args)

    def graph_key(self, kind: str, endpoint: Endpoint) -> str:
        qos = f"{endpoint.qos.depth}:{endpoint.qos.durability.value}"
        return (
            f"{self.prefix}/@g/{kind}/{_mangle(endpoint.node)}/{_mangle(endpoint.topic)}/"
            f"{_mangle(endpoint.type_name)}/{_mangle(qos)}"
        )

    def create_publisher(
        self, node: str, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> PublisherHandle:
        return _ZPub(self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type)

    def create_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[Message], None],
    ) -> SubscriptionHandle:
        return _ZSub(self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type, deliver)

    def _answer_on_executor(self, handler: ParameterHandler, who: str) -> Callable[[Any], None]:
        """A queryable callback that runs ``handler`` on the executor and replies with JSON."""

        def on_query(query: Any) -> None:  # a Zenoh thread: hand over to the executor
            try:
                request = json.loads(
                    query.payload.to_bytes() if query.payload is not None else b"{}"
                )
            except ValueError:
                query.reply(query.key_expr, json.dumps({"error": "request is not JSON"}))
                return
            done = threading.Event()
            box: dict[str, Any] = {}

            def run() -> None:
                try:
                    box["reply"] = handler(request)
                except Exception as exc:
                    box["reply"] = {"error": str(exc)}
                done.set()

            self.executor.post(run)
            if not done.wait(5.0):
                box["reply"] = {"error": f"{who} did not answer (is it spinning?)"}
            query.reply(query.key_expr, json.dumps(box["reply"]))

        return on_query

    def register_node(self, node: str, handler: ParameterHandler) -> Callable[[], None]:
        token = self.session.liveliness().declare_token(f"{self.prefix}/@g/node/{_mangle(node)}")
        on_query = self._answer_on_executor(handler, f"node {node}")
        queryable = self.session.declare_queryable(f"{self.prefix}/@p/{_mangle(node)}", on_query)
        self._node_handles[node] = (token, queryable)

        def unregister() -> None:
            for handle in self._node_handles.pop(node, ()):
                try:
                    handle.undeclare()
                except Exception:
                    log.debug("undeclare failed", exc_info=True)

        return unregister

    def graph(self, timeout_s: float = 1.0) -> Graph:
        graph = Graph()
        replies = self.session.liveliness().get(f"{self.prefix}/@g/**", timeout=timeout_s)
        for reply in replies:
            sample = reply.ok
            if sample is None:
                continue
            parts = str(sample.key_expr).split("/")
            if len(parts) < 5:
                continue
            kind = parts[3]
            if kind == "node":
                graph.nodes.add(_unmangle(parts[4]))
            elif kind == "srv":
                graph.services.add(_unmangle(parts[4]))
            elif kind in ("pub", "sub") and len(parts) >= 8:
                depth, _, durability = _unmangle(parts[7]).partition(":")
                qos = QoSProfile(
                    int(depth) if depth.isdigit() else 10, Durability(durability or "volatile")
                )
                graph.add(
                    kind,
                    Endpoint(_unmangle(parts[4]), _unmangle(parts[5]), _unmangle(parts[6]), qos),
                )
        return graph

    def call_parameters(
        self, node: str, request: dict[str, Any], timeout_s: float = 2.0
    ) -> dict[str, Any]:
        replies = self.session.get(
            f"{self.prefix}/@p/{_mangle(node)}", payload=json.dumps(request), timeout=timeout_s
        )
        for reply in replies:
            if reply.ok is not None:
                answer: dict[str, Any] = json.loads(reply.ok.payload.to_bytes())
                return answer
        nodes = sorted(self.graph(timeout_s=0.5).nodes)
        raise RobomodelError(
            f"node '{node}' did not answer; running nodes: {', '.join(nodes) or '(none found)'}"
        )

    def register_service(self, name: str, handler: ParameterHandler) -> Callable[[], None]:
        key = f"{self.prefix}/@s/{_mangle(name)}"
        queryable = self.session.declare_queryable(
            key, self._answer_on_executor(handler, f"service {name}")
        )
        token = self.session.liveliness().declare_token(f"{self.prefix}/@g/srv/{_mangle(name)}")
        self._node_handles[f"@s{name}"] = (queryable, token)

        def unregister() -> None:
            for handle in self._node_handles.pop(f"@s{name}", ()):
                try:
                    handle.undeclare()
                except Exception:
                    log.debug("undeclare failed", exc_info=True)

        return unregister

    def call_service(
        self, name: str, request: dict[str, Any], timeout_s: float = 2.0
    ) -> dict[str, Any]:
        replies = self.session.get(
            f"{self.prefix}/@s/{_mangle(name)}", payload=json.dumps(request), timeout=timeout_s
        )
        for reply in replies:
            if reply.ok is not None:
                answer: dict[str, Any] = json.loads(reply.ok.payload.to_bytes())
                return answer
        raise RobomodelError(f"service '{name}' did not answer (is its process running?)")

    def close(self) -> None:
        for node in list(self._node_handles):
            for handle in self._node_handles.pop(node):
                try:
                    handle.undeclare()
                except Exception:
                    log.debug("undeclare failed", exc_info=True)
        self.session.close()
