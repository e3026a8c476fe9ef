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

import json
import os
from collections.abc import Callable, Sequence
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import Message
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.transport._zenoh_common import import_zenoh, log, mangle, unmangle
from robomodel.runtime.transport._zenoh_endpoints import ZenohPublisher, ZenohSubscription
from robomodel.runtime.transport.base import (
    Endpoint,
    Graph,
    ParameterHandler,
    PublisherHandle,
    SubscriptionHandle,
    Transport,
)

__all__ = ["ANCHOR_BASE_PORT", "MAX_WARNINGS", "ZenohTransport", "domain_id_from_env"]

ANCHOR_BASE_PORT = 17470
MAX_WARNINGS = 256


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
        zenoh = import_zenoh()
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
        self._warnings_capped = False
        self._node_handles: dict[str, tuple[Any, ...]] = {}

    def warn_once(self, key: tuple[str, ...], fmt: str, *args: object) -> None:
        """Log a warning once per ``key``. Keys come partly from other processes (type names),
        so at most ``MAX_WARNINGS`` are remembered; past that one line says the rest are
        suppressed, and memory stays bounded however many distinct names a peer sends."""
        if key in self._warned:
            return
        if len(self._warned) >= MAX_WARNINGS:
            if not self._warnings_capped:
                self._warnings_capped = True
                log.warning(
                    "more than %d distinct bus warnings; suppressing the rest", MAX_WARNINGS
                )
            return
        self._warned.add(key)
        log.warning(fmt, *args)

    def graph_key(self, kind: str, endpoint: Endpoint) -> str:
        qos = f"{endpoint.qos.depth}:{endpoint.qos.durability.value}"
        return (
            f"{self.prefix}/@g/{kind}/{mangle(endpoint.node)}/{mangle(endpoint.topic)}/"
            f"{mangle(endpoint.type_name)}/{mangle(qos)}"
        )

    def create_publisher(
        self, node: str, topic: str, msg_type: type[Message], qos: QoSProfile
    ) -> PublisherHandle:
        return ZenohPublisher(self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type)

    def create_subscription(
        self,
        node: str,
        topic: str,
        msg_type: type[Message],
        qos: QoSProfile,
        deliver: Callable[[Message], None],
    ) -> SubscriptionHandle:
        return ZenohSubscription(
            self, Endpoint(node, topic, msg_type.__typename__, qos), msg_type, deliver
        )

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
            reply = self.executor.answer(handler, request, 5.0)
            if reply is None:
                reply = {"error": f"{who} did not answer (is it spinning?)"}
            query.reply(query.key_expr, json.dumps(reply))

        return on_query

    def register_node(self, node: str, handler: ParameterHandler) -> Callable[[], None]:
        token = self.session.liveliness().declare_token(f"{self.prefix}/@g/node/{mangle(node)}")
        on_query = self._answer_on_executor(handler, f"node {node}")
        queryable = self.session.declare_queryable(f"{self.prefix}/@p/{mangle(node)}", on_query)
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
                graph.nodes.add(unmangle(parts[4]))
            elif kind == "srv":
                graph.services.add(unmangle(parts[4]))
            elif kind in ("pub", "sub") and len(parts) >= 8:
                depth, _, durability = unmangle(parts[7]).partition(":")
                qos = QoSProfile(
                    int(depth) if depth.isdigit() else 10, Durability(durability or "volatile")
                )
                graph.add(
                    kind,
                    Endpoint(unmangle(parts[4]), unmangle(parts[5]), unmangle(parts[6]), qos),
                )
        return graph

    def call_parameters(
        self, node: str, request: dict[str, Any], timeout_s: float = 2.0
    ) -> dict[str, Any]:
        replies = self.session.get(
            f"{self.prefix}/@p/{mangle(node)}", payload=json.dumps(request), timeout=timeout_s
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
        key = f"{self.prefix}/@s/{mangle(name)}"
        queryable = self.session.declare_queryable(
            key, self._answer_on_executor(handler, f"service {name}")
        )
        token = self.session.liveliness().declare_token(f"{self.prefix}/@g/srv/{mangle(name)}")
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
            f"{self.prefix}/@s/{mangle(name)}", payload=json.dumps(request), timeout=timeout_s
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
