"""The ROS 1 master (rosmaster's master_api.py): registrations, lookups, the system state and the
parameter server with subscriptions, served over XML-RPC.

``robomodel launch`` starts one when no master answers at ``ROS_MASTER_URI``, as roslaunch starts
a roscore; ``robomodel master`` runs one on its own. Differences from rosmaster, on purpose:
``shutdown`` from a peer is refused (the master ends with the process that hosts it);
notifications (publisherUpdate, paramUpdate) are sent from one worker thread with a bounded
queue, each waited for at most 2 s, and nothing a peer registers can end that thread; names,
URIs and registrations are checked and bounded (registrations.py, names.py), a refusal being
``[-1, message, 0]`` and one log line, as rosmaster's validators answer.
"""

from __future__ import annotations

import functools
import os
import queue
import threading
from collections.abc import Callable
from typing import Any

from robomodel._escape import escape_name
from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport.ros1.names import (
    MAX_NAME_BYTES,
    Ros1NameError,
    check_name,
    check_uri,
    resolve,
    split_uri,
)
from robomodel.runtime.transport.ros1.param_tree import ParamServerError, ParamTree, split_name
from robomodel.runtime.transport.ros1.registrations import (
    MAX_REGISTRATIONS,
    Kind,
    RegistrationBoundError,
    Registry,
)
from robomodel.runtime.transport.ros1.xmlrpc_io import (
    Ros1WireError,
    XmlRpcServer,
    call_raw,
    log,
    log_throttled,
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


def _checked(method: Callable[..., Result]) -> Callable[..., Result]:
    """rosmaster's apivalidate: a caller_id, name or URI that is not valid (or over the bound)
    gets ``[-1, message, 0]`` and one log line, as do registrations past their bound."""

    @functools.wraps(method)
    def checked(self: MasterApi, caller_id: Any, *args: Any) -> Result:
        try:
            if caller_id != "":  # rosmaster takes any string, the empty one too
                check_name(caller_id, "caller_id")
            return method(self, caller_id, *args)
        except (Ros1NameError, RegistrationBoundError, ParamServerError) as exc:
            log_throttled("master-refused", "master: %s refused: %s", method.__name__, exc)
            return [-1, f"ERROR: {exc}", 0]

    return checked


def _name(name: Any, caller_id: str, what: str, *, root_ok: bool = False) -> str:
    """``name`` checked as a ROS name and resolved for ``caller_id`` (rosmaster's is_topic;
    ``root_ok``: its valid_name, which takes ``/``)."""
    resolved = resolve(check_name(name, what), caller_id)
    if resolved == "/" and not root_ok:
        raise Ros1NameError(f"{what} cannot be the global namespace")
    return check_name(resolved, what)


def _type_name(topic_type: Any) -> str:
    """rosmaster's valid_type_name: ``*`` or ``package/Type``."""
    if not isinstance(topic_type, str):
        raise Ros1NameError("topic_type must be '*' or a package/Type name")
    if topic_type == "*":
        return topic_type
    if len(topic_type.split("/")) != 2:
        raise Ros1NameError("topic_type must be '*' or a package/Type name")
    for part in topic_type.split("/"):
        check_name(part, "topic_type")
    return topic_type


class MasterApi:
    """The master's XML-RPC methods. Every method takes the caller's id first and answers
    ``[code, statusMessage, value]``."""

    def __init__(self, uri: str, notify: Callable[[str, str, tuple[Any, ...]], None]) -> None:
        self.uri = uri
        self.params = ParamTree()
        self._notify = notify  # (api, method, args): sent later, off the request thread
        self._lock = threading.RLock()
        self.registry = Registry()
        self.topic_types: dict[str, str] = {}

    def methods(self) -> dict[str, Callable[..., Any]]:
        names = [n for n in dir(self) if n[:1].islower() and n not in ("methods", "uri")]
        return {n: getattr(self, n) for n in names if callable(getattr(self, n))}

    # -- the master itself ------------------------------------------------------------------
    def getUri(self, caller_id: str) -> Result:
        return [1, "", self.uri]

    def getPid(self, caller_id: str) -> Result:
        return [1, "", os.getpid()]

    def shutdown(self, caller_id: str, msg: str = "") -> Result:
        log_throttled(
            "master-shutdown",
            "master: %.200s asked it to shut down (%.200s); refused",
            caller_id,
            msg,
        )
        return [0, "robomodel's master ends with the process that hosts it", 0]

    # -- nodes ------------------------------------------------------------------------------
    def _register(
        self, kind: Kind, key: str, caller_id: str, caller_api: str, service_api: str = ""
    ) -> None:
        """Register; a new node of the same name replaces the old one, which is told to shut
        down, as rosmaster does (registrations.py, shutdown_node_task)."""
        check_uri(caller_api, "caller_api")
        old = self.registry.register(kind, key, caller_id, caller_api, service_api)
        if old is not None:
            log.info(
                "master: new node registered with the name %s; shutting down the old",
                escape_name(caller_id),
            )
            self._notify(old, "shutdown", (_MASTER, "new node registered with same name"))

    @_checked
    def lookupNode(self, caller_id: str, node_name: str) -> Result:
        name = _name(node_name, caller_id, "node", root_ok=True)
        with self._lock:
            node = self.registry.nodes.get(name)
        return [1, "node api", node.api] if node else [-1, f"unknown node [{name}]", ""]

    # -- topics ---------------------------------------------------------------------------------
    @_checked
    def registerPublisher(
        self, caller_id: str, topic: str, topic_type: str, caller_api: str
    ) -> Result:
        topic, topic_type = _name(topic, caller_id, "topic"), _type_name(topic_type)
        with self._lock:
            self._register(Kind.PUBLISHER, topic, caller_id, caller_api)
            if topic_type != "*" or topic not in self.topic_types:
                self._set_type(topic, topic_type)
            self._publisher_update(topic)
            subs = self.registry.apis(Kind.SUBSCRIBER, topic)
        return [1, f"Registered [{caller_id}] as publisher of [{topic}]", subs]

    @_checked
    def unregisterPublisher(self, caller_id: str, topic: str, caller_api: str) -> Result:
        topic = _name(topic, caller_id, "topic")
        with self._lock:
            if not self.registry.unregister(Kind.PUBLISHER, topic, caller_id, caller_api):
                return [1, f"[{caller_id}] is not a known provider of [{topic}]", 0]
            self._publisher_update(topic)
        return [1, f"Unregistered [{caller_id}] as provider of [{topic}]", 1]

    @_checked
    def registerSubscriber(
        self, caller_id: str, topic: str, topic_type: str, caller_api: str
    ) -> Result:
        topic, topic_type = _name(topic, caller_id, "topic"), _type_name(topic_type)
        with self._lock:
            self._register(Kind.SUBSCRIBER, topic, caller_id, caller_api)
            if topic_type != "*" and topic not in self.topic_types:
                self._set_type(topic, topic_type)
            pubs = self.registry.apis(Kind.PUBLISHER, topic)
        return [1, f"Subscribed to [{topic}]", pubs]

    @_checked
    def unregisterSubscriber(self, caller_id: str, topic: str, caller_api: str) -> Result:
        topic = _name(topic, caller_id, "topic")
        with self._lock:
            if not self.registry.unregister(Kind.SUBSCRIBER, topic, caller_id, caller_api):
                return [1, f"[{caller_id}] is not a known provider of [{topic}]", 0]
        return [1, f"Unregistered [{caller_id}] as provider of [{topic}]", 1]

    def _set_type(self, topic: str, topic_type: str) -> None:
        """rosmaster keeps a topic's type after its last registration ends (getTopicTypes
        still lists it); robomodel too, but drops those stale types past the bound."""
        if topic not in self.topic_types and len(self.topic_types) >= MAX_REGISTRATIONS:
            for stale in [t for t in self.topic_types if not self.registry.has_key(t)]:
                del self.topic_types[stale]
        self.topic_types[topic] = topic_type

    def _publisher_update(self, topic: str) -> None:
        pubs = self.registry.apis(Kind.PUBLISHER, topic)
        for api in self.registry.apis(Kind.SUBSCRIBER, topic):
            self._notify(api, "publisherUpdate", (_MASTER, topic, pubs))

    @_checked
    def getPublishedTopics(self, caller_id: str, subgraph: str) -> Result:
        prefix = _name(subgraph, caller_id, "subgraph", root_ok=True) if subgraph else "/"
        prefix = prefix if prefix.endswith("/") else prefix + "/"
        with self._lock:
            topics = [
                [t, self.topic_types.get(t, "*")]
                for t, _ in sorted(self.registry.providers(Kind.PUBLISHER))
                if t.startswith(prefix) or prefix == "/"
            ]
        return [1, "current topics", topics]

    def getTopicTypes(self, caller_id: str) -> Result:
        with self._lock:
            return [1, "current topic types", [[t, k] for t, k in sorted(self.topic_types.items())]]

    def getSystemState(self, caller_id: str) -> Result:
        with self._lock:
            kinds = (Kind.PUBLISHER, Kind.SUBSCRIBER, Kind.SERVICE)
            state = [self.registry.state(kind) for kind in kinds]
        return [1, "current system state", state]

    # -- services -------------------------------------------------------------------------------
    @_checked
    def registerService(
        self, caller_id: str, service: str, service_api: str, caller_api: str
    ) -> Result:
        service = _name(service, caller_id, "service")
        check_uri(service_api, "service_api")
        with self._lock:
            self._register(Kind.SERVICE, service, caller_id, caller_api, service_api)
        return [1, f"Registered [{caller_id}] as provider of [{service}]", 1]

    @_checked
    def lookupService(self, caller_id: str, service: str) -> Result:
        service = _name(service, caller_id, "service")
        with self._lock:
            entry = self.registry.service_apis.get(service)
        if entry is None:
            return [-1, "no provider", ""]
        return [1, f"rosrpc URI: [{entry[1]}]", entry[1]]

    @_checked
    def unregisterService(self, caller_id: str, service: str, service_api: str) -> Result:
        service = _name(service, caller_id, "service")
        with self._lock:
            if not self.registry.unregister(
                Kind.SERVICE, service, caller_id, service_api=str(service_api)
            ):
                return [1, f"[{caller_id}] is not a provider of [{service}]", 0]
        return [1, f"Unregistered [{caller_id}] as provider of [{service}]", 1]

    # -- parameters -----------------------------------------------------------------------------
    @_checked
    def setParam(self, caller_id: str, key: str, value: Any) -> Result:
        key = _key(key, caller_id)
        if not split_name(key) and not isinstance(value, dict):
            return [-1, "cannot set root of parameter tree to non-dictionary", 0]
        self.params.set(key, value)
        self._param_updates(key, caller_id)
        return [1, f"parameter {key} set", 0]

    @_checked
    def getParam(self, caller_id: str, key: str) -> Result:
        key = _key(key, caller_id)
        try:
            return [1, f"Parameter [{key}]", self.params.get(key)]
        except ParamServerError:
            return [-1, f"Parameter [{key}] is not set", 0]

    @_checked
    def deleteParam(self, caller_id: str, key: str) -> Result:
        key = _key(key, caller_id)
        try:
            self.params.delete(key)
        except ParamServerError:
            return [-1, f"parameter [{key}] is not set", 0]
        self._param_updates(key, caller_id)
        return [1, f"parameter {key} deleted", 0]

    @_checked
    def hasParam(self, caller_id: str, key: str) -> Result:
        key = _key(key, caller_id)
        return [1, key, self.params.has(key)]

    @_checked
    def searchParam(self, caller_id: str, key: str) -> Result:
        if not isinstance(key, str) or not key or key.startswith("~"):
            return [-1, "invalid key", ""]
        _key(key, caller_id)
        found = self.params.search(caller_id, key)
        if found is None:
            return [-1, f"Cannot find parameter [{key}] in an upwards search", ""]
        return [1, f"Found [{found}]", found]

    def getParamNames(self, caller_id: str) -> Result:
        return [1, "Parameter names", self.params.names()]

    @_checked
    def subscribeParam(self, caller_id: str, caller_api: str, key: str) -> Result:
        key = _key(key, caller_id)
        with self._lock:
            self._register(Kind.PARAM_SUBSCRIBER, key.rstrip("/") + "/", caller_id, caller_api)
        value = self.params.get(key) if self.params.has(key) else {}
        return [1, f"Subscribed to parameter [{key}]", value]

    @_checked
    def unsubscribeParam(self, caller_id: str, caller_api: str, key: str) -> Result:
        key = _key(key, caller_id).rstrip("/") + "/"
        with self._lock:
            removed = self.registry.unregister(Kind.PARAM_SUBSCRIBER, key, caller_id, caller_api)
        return [1, f"Unsubscribe to parameter [{key}]", removed]

    def _param_updates(self, key: str, caller_id: str) -> None:
        """paramUpdate to every subscriber of ``key``, of a namespace above it, or of a key
        below it (rosmaster's compute_param_updates), the changing node excepted."""
        changed = key.rstrip("/") + "/"
        with self._lock:
            subscriptions = [
                (k, list(v)) for k, v in self.registry.providers(Kind.PARAM_SUBSCRIBER)
            ]
        for sub_key, nodes in subscriptions:
            if not (changed.startswith(sub_key) or sub_key.startswith(changed)):
                continue
            name = sub_key.rstrip("/") or "/"
            value = self.params.get(name) if self.params.has(name) else {}
            for node, api in nodes:
                if node != caller_id:
                    self._notify(api, "paramUpdate", (_MASTER, sub_key, value))


def _key(key: Any, caller_id: str) -> str:
    """A parameter key resolved for ``caller_id``: any string (rosmaster's non_empty_str)
    within ``MAX_NAME_BYTES``; the tree bounds its depth."""
    if not isinstance(key, str) or len(key) > MAX_NAME_BYTES:
        raise Ros1NameError(
            f"a parameter key must be a string of at most {MAX_NAME_BYTES} characters"
        )
    resolved = resolve(key, caller_id)
    if len(resolved) > MAX_NAME_BYTES:
        raise Ros1NameError(f"parameter key {resolved[:80]!r}... is longer than {MAX_NAME_BYTES}")
    return resolved


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
            log_throttled(
                "master-queue",
                "master: notification queue full; dropping %s to %.200s",
                method,
                api,
            )

    def _send(self) -> None:
        while (item := self._queue.get()) is not None:
            api, method, args = item
            try:
                call_raw(api, method, *args, timeout_s=2.0)
            except Ros1WireError as exc:  # a node that ended, or a peer's garbage URI
                log.debug("master: %s to %s failed: %s", method, api, exc)
            except Exception:  # nothing a peer sends may end this thread: it serves everyone
                log_failure(log, "master: %s to %.200s failed", method, api)

    def close(self) -> None:
        self._server.close()
        self._queue.put(None)
        self._worker.join(timeout=3.0)
