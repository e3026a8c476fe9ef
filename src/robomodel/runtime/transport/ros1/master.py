"""The ROS 1 master (rosmaster's master_api.py): registrations, lookups, the system state and the
parameter server with subscriptions, served over XML-RPC.

``robomodel launch`` starts one when no master answers at ``ROS_MASTER_URI``, as roslaunch starts
a roscore; ``robomodel master`` runs one on its own. Differences from rosmaster, on purpose:
``shutdown`` from a peer is refused (the master ends with the process that hosts it), and
notifications (publisherUpdate, paramUpdate) are sent from one worker thread with a bounded
queue, so a node that does not answer delays only its own updates.
"""

from __future__ import annotations

import os
import queue
import threading
from collections.abc import Callable
from typing import Any

from robomodel.runtime.transport.ros1.names import resolve, split_uri
from robomodel.runtime.transport.ros1.param_tree import ParamServerError, ParamTree, split_name
from robomodel.runtime.transport.ros1.xmlrpc_io import (
    Ros1WireError,
    XmlRpcServer,
    call_raw,
    log,
)

__all__ = ["Master", "MasterApi", "master_answers"]

MAX_PENDING_NOTIFICATIONS = 10_000
_MASTER = "/master"
Result = list[Any]


def master_answers(uri: str, timeout_s: float = 1.0) -> bool:
    """Whether a ROS 1 master answers at ``uri``."""
    try:
        call_raw(uri, "getPid", "/robomodel", timeout_s=timeout_s)
    except Ros1WireError:
        return False
    return True


class _Registrations:
    """name -> {caller_id: api}: publishers or subscribers of topics, or param subscribers."""

    def __init__(self) -> None:
        self.by_name: dict[str, dict[str, str]] = {}

    def add(self, name: str, caller_id: str, api: str) -> None:
        self.by_name.setdefault(name, {})[caller_id] = api

    def remove(self, name: str, caller_id: str, api: str) -> bool:
        entry = self.by_name.get(name, {})
        if entry.get(caller_id) != api:
            return False
        del entry[caller_id]
        if not entry:
            del self.by_name[name]
        return True

    def apis(self, name: str) -> list[str]:
        return list(self.by_name.get(name, {}).values())

    def drop_node(self, caller_id: str) -> None:
        for name in list(self.by_name):
            self.by_name[name].pop(caller_id, None)
            if not self.by_name[name]:
                del self.by_name[name]

    def state(self) -> list[list[Any]]:
        return [[name, sorted(nodes)] for name, nodes in sorted(self.by_name.items())]


class MasterApi:
    """The master's XML-RPC methods. Every method takes the caller's id first and answers
    ``[code, statusMessage, value]``."""

    def __init__(self, uri: str, notify: Callable[[str, str, tuple[Any, ...]], None]) -> None:
        self.uri = uri
        self.params = ParamTree()
        self._notify = notify  # (api, method, args): sent later, off the request thread
        self._lock = threading.RLock()
        self.publishers = _Registrations()
        self.subscribers = _Registrations()
        self.param_subscribers = _Registrations()
        self.services: dict[str, tuple[str, str, str]] = {}  # name -> caller_id, url, api
        self.topic_types: dict[str, str] = {}
        self.nodes: dict[str, str] = {}

    def methods(self) -> dict[str, Callable[..., Any]]:
        names = [n for n in dir(self) if n[:1].islower() and n not in ("methods", "uri")]
        return {n: getattr(self, n) for n in names if callable(getattr(self, n))}

    # -- the master itself ------------------------------------------------------------------
    def getUri(self, caller_id: str) -> Result:
        return [1, "", self.uri]

    def getPid(self, caller_id: str) -> Result:
        return [1, "", os.getpid()]

    def shutdown(self, caller_id: str, msg: str = "") -> Result:
        log.warning("master: %s asked it to shut down (%s); refused", caller_id, msg)
        return [0, "robomodel's master ends with the process that hosts it", 0]

    # -- nodes ------------------------------------------------------------------------------
    def _node(self, caller_id: str, api: str) -> None:
        """Record ``caller_id``'s API; a new node of the same name replaces the old one, which
        is told to shut down, as rosmaster does."""
        old = self.nodes.get(caller_id)
        if old is not None and old != api:
            log.info(
                "master: new node registered with the name %s; shutting down the old", caller_id
            )
            self.publishers.drop_node(caller_id)
            self.subscribers.drop_node(caller_id)
            self.param_subscribers.drop_node(caller_id)
            for name in [s for s, v in self.services.items() if v[0] == caller_id]:
                del self.services[name]
            self._notify(old, "shutdown", (_MASTER, "new node registered with same name"))
        self.nodes[caller_id] = api

    def lookupNode(self, caller_id: str, node_name: str) -> Result:
        name = resolve(node_name, caller_id)
        with self._lock:
            api = self.nodes.get(name)
        return [1, f"node api for {name}", api] if api else [-1, f"unknown node [{name}]", ""]

    # -- topics ---------------------------------------------------------------------------------
    def registerPublisher(
        self, caller_id: str, topic: str, topic_type: str, caller_api: str
    ) -> Result:
        topic = resolve(topic, caller_id)
        with self._lock:
            self._node(caller_id, caller_api)
            self.publishers.add(topic, caller_id, caller_api)
            if topic_type != "*" or topic not in self.topic_types:
                self.topic_types[topic] = topic_type
            self._publisher_update(topic)
            subs = self.subscribers.apis(topic)
        return [1, f"Registered [{caller_id}] as publisher of [{topic}]", subs]

    def unregisterPublisher(self, caller_id: str, topic: str, caller_api: str) -> Result:
        topic = resolve(topic, caller_id)
        with self._lock:
            if not self.publishers.remove(topic, caller_id, caller_api):
                return [1, f"[{caller_id}] is not a publisher of [{topic}]", 0]
            self._publisher_update(topic)
        return [1, f"Unregistered [{caller_id}] as provider of [{topic}]", 1]

    def registerSubscriber(
        self, caller_id: str, topic: str, topic_type: str, caller_api: str
    ) -> Result:
        topic = resolve(topic, caller_id)
        with self._lock:
            self._node(caller_id, caller_api)
            self.subscribers.add(topic, caller_id, caller_api)
            if topic_type != "*" and topic not in self.topic_types:
                self.topic_types[topic] = topic_type
            pubs = self.publishers.apis(topic)
        return [1, f"Subscribed to [{topic}]", pubs]

    def unregisterSubscriber(self, caller_id: str, topic: str, caller_api: str) -> Result:
        topic = resolve(topic, caller_id)
        with self._lock:
            if not self.subscribers.remove(topic, caller_id, caller_api):
                return [1, f"[{caller_id}] is not a subscriber of [{topic}]", 0]
        return [1, f"Unsubscribed [{caller_id}] from [{topic}]", 1]

    def _publisher_update(self, topic: str) -> None:
        pubs = self.publishers.apis(topic)
        for api in self.subscribers.apis(topic):
            self._notify(api, "publisherUpdate", (_MASTER, topic, pubs))

    def getPublishedTopics(self, caller_id: str, subgraph: str) -> Result:
        prefix = resolve(subgraph, caller_id) if subgraph else "/"
        prefix = prefix if prefix.endswith("/") else prefix + "/"
        with self._lock:
            topics = [
                [t, self.topic_types.get(t, "*")]
                for t in sorted(self.publishers.by_name)
                if t.startswith(prefix) or prefix == "/"
            ]
        return [1, "current topics", topics]

    def getTopicTypes(self, caller_id: str) -> Result:
        with self._lock:
            return [1, "current topic types", [[t, k] for t, k in sorted(self.topic_types.items())]]

    def getSystemState(self, caller_id: str) -> Result:
        with self._lock:
            services = [[s, [v[0]]] for s, v in sorted(self.services.items())]
            state = [self.publishers.state(), self.subscribers.state(), services]
        return [1, "current system state", state]

    # -- services -------------------------------------------------------------------------------
    def registerService(
        self, caller_id: str, service: str, service_api: str, caller_api: str
    ) -> Result:
        service = resolve(service, caller_id)
        split_uri(service_api)
        with self._lock:
            self._node(caller_id, caller_api)
            self.services[service] = (caller_id, service_api, caller_api)
        return [1, f"Registered [{caller_id}] as provider of [{service}]", 1]

    def lookupService(self, caller_id: str, service: str) -> Result:
        service = resolve(service, caller_id)
        with self._lock:
            entry = self.services.get(service)
        if entry is None:
            return [-1, "no provider", ""]
        return [1, f"rosrpc URI: [{entry[1]}]", entry[1]]

    def unregisterService(self, caller_id: str, service: str, service_api: str) -> Result:
        service = resolve(service, caller_id)
        with self._lock:
            entry = self.services.get(service)
            if entry is None or entry[1] != service_api:
                return [1, f"[{caller_id}] is not a provider of [{service}]", 0]
            del self.services[service]
        return [1, f"Unregistered [{caller_id}] as provider of [{service}]", 1]

    # -- parameters -----------------------------------------------------------------------------
    def setParam(self, caller_id: str, key: str, value: Any) -> Result:
        key = resolve(key, caller_id)
        if not split_name(key) and not isinstance(value, dict):
            return [-1, "cannot set root of parameter tree to non-dictionary", 0]
        self.params.set(key, value)
        self._param_updates(key, caller_id)
        return [1, f"parameter {key} set", 0]

    def getParam(self, caller_id: str, key: str) -> Result:
        key = resolve(key, caller_id)
        try:
            return [1, f"Parameter [{key}]", self.params.get(key)]
        except ParamServerError:
            return [-1, f"Parameter [{key}] is not set", 0]

    def deleteParam(self, caller_id: str, key: str) -> Result:
        key = resolve(key, caller_id)
        try:
            self.params.delete(key)
        except ParamServerError:
            return [-1, f"parameter [{key}] is not set", 0]
        self._param_updates(key, caller_id)
        return [1, f"parameter {key} deleted", 0]

    def hasParam(self, caller_id: str, key: str) -> Result:
        key = resolve(key, caller_id)
        return [1, key, self.params.has(key)]

    def searchParam(self, caller_id: str, key: str) -> Result:
        if not key or key.startswith("~"):
            return [-1, "invalid key", ""]
        found = self.params.search(caller_id, key)
        if found is None:
            return [-1, f"Cannot find parameter [{key}] in an upwards search", ""]
        return [1, f"Found [{found}]", found]

    def getParamNames(self, caller_id: str) -> Result:
        return [1, "Parameter names", self.params.names()]

    def subscribeParam(self, caller_id: str, caller_api: str, key: str) -> Result:
        key = resolve(key, caller_id)
        with self._lock:
            self._node(caller_id, caller_api)
            self.param_subscribers.add(key.rstrip("/") + "/", caller_id, caller_api)
        value = self.params.get(key) if self.params.has(key) else {}
        return [1, f"Subscribed to parameter [{key}]", value]

    def unsubscribeParam(self, caller_id: str, caller_api: str, key: str) -> Result:
        key = resolve(key, caller_id).rstrip("/") + "/"
        with self._lock:
            removed = self.param_subscribers.remove(key, caller_id, caller_api)
        return [1, f"Unsubscribe to parameter [{key}]", 1 if removed else 0]

    def _param_updates(self, key: str, caller_id: str) -> None:
        """paramUpdate to every subscriber of ``key``, of a namespace above it, or of a key
        below it (rosmaster's compute_param_updates), the changing node excepted."""
        changed = key.rstrip("/") + "/"
        with self._lock:
            subscriptions = {k: dict(v) for k, v in self.param_subscribers.by_name.items()}
        for sub_key, nodes in subscriptions.items():
            if not (changed.startswith(sub_key) or sub_key.startswith(changed)):
                continue
            name = sub_key.rstrip("/") or "/"
            value = self.params.get(name) if self.params.has(name) else {}
            for node, api in nodes.items():
                if node != caller_id:
                    self._notify(api, "paramUpdate", (_MASTER, sub_key, value))


class Master:
    """A master serving on ``uri``'s port (bound to ``host``)."""

    def __init__(self, uri: str, host: str) -> None:
        _, port = split_uri(uri)
        self._queue: queue.Queue[tuple[str, str, tuple[Any, ...]] | None] = queue.Queue(
            MAX_PENDING_NOTIFICATIONS
        )
        self.api = MasterApi(uri, self._enqueue)
        self._server = XmlRpcServer(host, port, self.api.methods())
        self.uri = uri
        self._worker = threading.Thread(target=self._send, name="ros1-master-notify", daemon=True)
        self._worker.start()

    def _enqueue(self, api: str, method: str, args: tuple[Any, ...]) -> None:
        try:
            self._queue.put_nowait((api, method, args))
        except queue.Full:
            log.warning("master: notification queue full; dropping %s to %s", method, api)

    def _send(self) -> None:
        while (item := self._queue.get()) is not None:
            api, method, args = item
            try:
                call_raw(api, method, *args, timeout_s=2.0)
            except Ros1WireError as exc:
                log.debug("master: %s to %s failed: %s", method, api, exc)

    def close(self) -> None:
        self._server.close()
        self._queue.put(None)
        self._worker.join(timeout=3.0)
