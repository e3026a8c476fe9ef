"""The Zenoh transport's service servers and clients, as rmw_zenoh's ServiceData and ClientData
(rmw_service_data.cpp, rmw_client_data.cpp):

- a server is a *complete* queryable on the service's key (``<domain>/<name>/<DDS service
  type>/<service type hash>``) and an ``SS`` liveliness token;
- a request is a ``get`` on that key with target ALL_COMPLETE and no consolidation, the CDR
  request as payload and an attachment (the client's sequence number from 1, a timestamp, the
  client's GID); the server replies on its key with the CDR response and an attachment that
  carries the request's sequence number and client GID back.

A handler runs on the executor's thread; the Zenoh thread that received the query only hands
it over. A request that cannot be decoded, or a handler that raises, is answered with a Zenoh
error reply saying why (rmw_zenoh clients log it; robomodel's raise ServiceCallError).
"""

from __future__ import annotations

import itertools
import threading
import time
from typing import Any, Protocol

from robomodel.runtime.msg import CDRError, Message, deserialize, serialize
from robomodel.runtime.msg.cdr import prepare
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport._zenoh_common import (
    ZenohSessionOwner,
    direct,
    import_zenoh,
    log,
    undeclare_all,
)
from robomodel.runtime.transport.base import (
    Deferred,
    Endpoint,
    RequestId,
    ServiceCallError,
    ServiceHandle,
    ServiceHandler,
    request_being_served,
    request_sent,
)
from robomodel.runtime.transport.rmw_zenoh import (
    EntityKind,
    encode_attachment,
    entity_gid,
    parse_attachment,
)

__all__ = ["ServiceClient", "ServiceOwner", "ZenohService"]

ZENOH_QUERY_TIMEOUT = "Timeout"
"""The error Zenoh itself gives a query that outlived its timeout (seen from no replier, and on a
loaded machine with a replier id too, source not traced). robomodel's servers' errors name the
service and the cause; rmw_zenoh's servers send none: an error of this bare text is no answer."""


class ServiceOwner(ZenohSessionOwner, Protocol):
    """The transport as its services see it: also told when a service is destroyed."""

    def forget_service(self, service: ZenohService) -> None: ...


class ZenohService(ServiceHandle):
    def __init__(
        self,
        bus: ServiceOwner,
        endpoint: Endpoint,
        srv_type: type[Service],
        handler: ServiceHandler,
    ) -> None:
        self._bus = bus
        self.endpoint = endpoint
        self.srv_type = srv_type
        self.handler = handler
        prepare(srv_type.Request)
        prepare(srv_type.Response)
        self.key = self._key = bus.data_key(endpoint.topic, srv_type)
        token = bus.entity_token(endpoint, EntityKind.SERVICE, srv_type)
        self._queryable = bus.session.declare_queryable(
            self._key, direct(self._on_query), complete=True
        )
        self._token = bus.session.liveliness().declare_token(token.key())

    def _on_query(self, query: Any) -> None:  # a Zenoh thread: decode, then hand over
        name = self.endpoint.topic
        attachment = parse_attachment(query.attachment.to_bytes() if query.attachment else b"")
        if attachment is None:
            self._refuse(query, f"request to {name} without a valid rmw_zenoh attachment")
            return
        try:
            payload = query.payload.to_bytes() if query.payload is not None else b""
            request = deserialize(payload, self.srv_type.Request)
        except CDRError as exc:
            self._refuse(query, f"malformed {self.srv_type.__typename__} request to {name}: {exc}")
            return
        self._bus.executor.post(lambda: self._serve(query, request, attachment))

    def _refuse(self, query: Any, reason: str) -> None:
        self._bus.warn_once((self.endpoint.topic, "request"), "%s", reason)
        try:
            query.reply_err(reason)
        finally:
            query.drop()

    def _serve(self, query: Any, request: Message, attachment: Any) -> None:
        """On the executor: run the handler; reply now, or when a Deferred resolves."""
        served = request_being_served.set(RequestId(attachment.gid, attachment.sequence_number))
        try:
            answer = self.handler(request)
        except Exception as exc:  # the server goes on; the caller learns why
            log_failure(log, "service %s failed", self.endpoint.topic)
            self._refuse(query, f"service '{self.endpoint.topic}' failed: {exc}")
            return
        finally:
            request_being_served.reset(served)
        if isinstance(answer, Deferred):
            answer.then(lambda response: self._reply(query, response, attachment))
        else:
            self._reply(query, answer, attachment)

    def _reply(self, query: Any, response: Message, attachment: Any) -> None:
        try:
            if not isinstance(response, self.srv_type.Response):
                raise TypeError(
                    f"handler returned {type(response).__name__}, "
                    f"not {self.srv_type.Response.__typename__}"
                )
            reply = encode_attachment(attachment.sequence_number, time.time_ns(), attachment.gid)
            query.reply(self._key, serialize(response), attachment=reply)
        except Exception as exc:
            log_failure(log, "cannot answer %s", self.endpoint.topic)
            query.reply_err(f"service '{self.endpoint.topic}' failed: {exc}")
        finally:
            query.drop()

    def destroy(self) -> None:
        self._bus.forget_service(self)
        undeclare_all(self._token, self._queryable)


class ServiceClient:
    """Calls of one (node, service, type): its ``SC`` token, its GID and sequence numbers.

    As rmw_zenoh's ``ClientData::make`` (``rmw_client_data.cpp``): the token is the node's
    entity ``SC`` token (``liveliness_utils.cpp``, ``Entity::make``) and the GID that every
    request's attachment carries is derived from that token (``Entity::copy_gid``)."""

    def __init__(self, bus: ServiceOwner, name: str, srv_type: type[Service], node: str) -> None:
        self._bus = bus
        self.name = name
        self.srv_type = srv_type
        self._key = bus.data_key(name, srv_type)
        self._numbers = itertools.count(1)
        self._lock = threading.Lock()
        prepare(srv_type.Request)
        prepare(srv_type.Response)
        endpoint = Endpoint(node, name, srv_type.__typename__)
        self.token = bus.entity_token(endpoint, EntityKind.CLIENT, srv_type)
        self.gid = entity_gid(self.token.key())
        self._token = bus.session.liveliness().declare_token(self.token.key())

    def call(self, request: Message, timeout_s: float) -> Message:
        """The response to ``request``, waiting up to ``timeout_s`` for a server to appear.

        A query that ends with no reply reached no queryable: the server is not on the bus, or
        the router has not heard of it yet (a manager that has just started). As rclpy's
        ``wait_for_service`` before a call (ros2controlcli's ``service_caller``), the request
        is sent again, backing off, until one answers or the time is up."""
        with self._lock:
            number = next(self._numbers)
        told = request_sent.get()
        if told is not None:
            told(RequestId(self.gid, number))
        payload = serialize(request)
        deadline = time.monotonic() + timeout_s
        pause_s = 0.02
        while True:
            remaining_s = deadline - time.monotonic()
            answer, ended_early = self._ask(payload, number, max(remaining_s, 0.001))
            if answer is not None:
                return answer
            remaining_s = deadline - time.monotonic()
            if not ended_early or remaining_s <= pause_s:
                break
            time.sleep(pause_s)  # nobody served it yet: ask again, as wait_for_service polls
            pause_s = min(pause_s * 2, 0.25)
        if ended_early:
            raise ServiceCallError(
                f"service '{self.name}' ({self.srv_type.__typename__}) has no server on the "
                f"bus after {timeout_s:g} s (is its process running?)"
            )
        raise ServiceCallError(
            f"service '{self.name}' ({self.srv_type.__typename__}) did not answer within "
            f"{timeout_s:g} s (is its process running?)"
        )

    def _ask(self, payload: bytes, number: int, timeout_s: float) -> tuple[Message | None, bool]:
        """One query: (the response or None, whether it ended before ``timeout_s`` with no
        reply at all, which is how Zenoh says that no queryable matched)."""
        zenoh = import_zenoh()
        started = time.monotonic()
        replies = self._bus.session.get(
            self._key,
            payload=payload,
            attachment=encode_attachment(number, time.time_ns(), self.gid),
            target=zenoh.QueryTarget.ALL_COMPLETE,
            consolidation=zenoh.ConsolidationMode.NONE,
            timeout=timeout_s,
        )
        errors: list[str] = []
        replied = False
        for reply in replies:
            sample = reply.ok
            if sample is None:
                error = reply.err
                text = error.payload.to_string() if error is not None else "error reply"
                if text == ZENOH_QUERY_TIMEOUT:
                    continue  # nobody replied before the query's end
                replied = True
                errors.append(text)
                continue
            replied = True
            attachment = parse_attachment(
                sample.attachment.to_bytes() if sample.attachment else b""
            )
            if attachment is None or attachment.sequence_number != number:
                continue  # not the reply to this request
            try:
                return deserialize(sample.payload.to_bytes(), self.srv_type.Response), False
            except CDRError as exc:
                errors.append(f"malformed response: {exc}")
        if errors:
            raise ServiceCallError(f"service '{self.name}': {'; '.join(errors)}")
        return None, not replied and time.monotonic() - started < timeout_s * 0.9

    def destroy(self) -> None:
        undeclare_all(self._token)
