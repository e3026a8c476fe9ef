"""ROS 1 services over TCPROS (rospy's tcpros_service.py, roscpp's ServiceClientLink).

Server: a connection's header names the service; the reply header carries the md5sums and
types (a ``probe=1`` connection, as ``rosservice type`` makes, ends there); then each request
frame is answered with an ok byte and the response (1), or the error text (0). The handler runs
on the executor's thread, as every robomodel callback (one wrapped in :class:`OnReceivingThread`
runs on the connection's thread, as rospy runs its handlers); a :class:`Deferred` answer is
written when it resolves.

Bound: at most ``MAX_SERVICE_CONNECTIONS`` client connections at once in one process, across its
nodes and services, each served on a thread of its own for its lifetime; past it a new one is
refused with an error header and one throttled log line, and its slot is given back when it
closes.

Client: the master's ``lookupService`` gives ``rosrpc://host:port``; one connection per call
(``persistent=0``).
"""

from __future__ import annotations

import socket
import threading
import time
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg import Message
from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport.base import (
    Deferred,
    OnReceivingThread,
    ServiceCallError,
    ServiceHandler,
)
from robomodel.runtime.transport.ros1.budget import ByteBudget
from robomodel.runtime.transport.ros1.names import split_uri
from robomodel.runtime.transport.ros1.tcpros import (
    MAX_FRAME_BYTES,
    FrameRefused,
    TcprosError,
    read_frame,
    read_header,
    recv_exact,
    refuse,
    write_frame,
    write_header,
)
from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call, log, log_throttled

if TYPE_CHECKING:
    from robomodel.runtime.executor import Executor
    from robomodel.runtime.transport.ros1.ros1_types import Ros1ServiceType

__all__ = [
    "MAX_SERVICE_CONNECTIONS",
    "ServiceServer",
    "call_service",
    "probe_service_type",
    "service_connections",
]

HANDLER_TIMEOUT_S = 300.0  # a controller switch or a model spawn can take a while
# Clients connect once per call (rosservice, rospy and roscpp without persistent=1) and the
# handlers of a process run one at a time on its executor, so more connections at once only
# wait; 64 is what the XML-RPC server serves at once, for the same reason.
MAX_SERVICE_CONNECTIONS = 64
_SLOTS = ByteBudget(MAX_SERVICE_CONNECTIONS)  # counts connections, one unit each


def service_connections() -> int:
    """Service client connections being served in this process now (one thread each)."""
    return _SLOTS.used


class ServiceServer:
    """One service a node offers."""

    def __init__(
        self,
        caller_id: str,
        name: str,
        kind: Ros1ServiceType,
        handler: ServiceHandler,
        executor: Executor,
    ) -> None:
        self.caller_id = caller_id
        self.name = name
        self.kind = kind
        self.handler = handler
        self._executor = executor

    def _reply_header(self) -> dict[str, str]:
        return {
            "callerid": self.caller_id,
            "md5sum": self.kind.md5sum,
            "request_type": self.kind.request.name,
            "response_type": self.kind.response.name,
            "type": self.kind.name,
        }

    def serve(self, sock: socket.socket, header: dict[str, str]) -> None:
        """Serve one client connection (on its own thread) until it closes; then close it."""
        md5 = header.get("md5sum", "*")
        if md5 not in ("*", self.kind.md5sum):
            reason = (
                f"request from [{header.get('callerid', '?')}]: md5sums do not match: "
                f"[{md5}] vs. [{self.kind.md5sum}]"
            )
            log.warning("service %s: %s", self.name, reason)
            refuse(sock, reason)  # a request sent with the header is not read
            return
        if not _SLOTS.take(1):
            log_throttled(
                "tcpros-services",
                "TCPROS: more than %d service connections at once in this process "
                "(MAX_SERVICE_CONNECTIONS); refusing %r on %s",
                MAX_SERVICE_CONNECTIONS,
                header.get("callerid", "?"),
                self.name,
            )
            refuse(
                sock,
                f"{self.caller_id} serves {MAX_SERVICE_CONNECTIONS} service connections "
                f"already (its process's limit); try again later",
            )
            return
        try:
            self._serve_calls(sock, header)
        finally:
            _SLOTS.give(1)
            sock.close()

    def _serve_calls(self, sock: socket.socket, header: dict[str, str]) -> None:
        write_header(sock, self._reply_header())
        if header.get("probe") == "1":
            return
        persistent = header.get("persistent") == "1"
        sock.settimeout(None)
        limit = self.kind.request.fixed_size or MAX_FRAME_BYTES
        while True:
            try:
                payload = read_frame(sock, limit)
            except FrameRefused as exc:
                log.warning("service %s: closing the connection from %r: %s",
                            self.name, header.get("callerid", "?"), exc)  # fmt: skip
                return
            except TcprosError:
                return  # the client is done
            ok, body = self._answer(payload, header)
            sock.sendall(b"\x01" if ok else b"\x00")
            write_frame(sock, body)
            if not persistent:
                return

    def _answer(self, payload: bytes, header: dict[str, str]) -> tuple[bool, bytes]:
        from robomodel.runtime.transport.ros1.ros1_types import Ros1CodecError

        try:
            request = _with_header(self.kind.request.decode(payload), header)
        except Ros1CodecError as exc:
            return False, f"malformed request: {exc}".encode()
        done = threading.Event()
        box: dict[str, Any] = {}

        def finish(response: Any) -> None:
            box["response"] = response
            done.set()

        def run() -> None:
            try:
                answer = self.handler(request)
            except Exception as exc:
                log_failure(log, "service %s failed", self.name)
                box["error"] = f"service [{self.name}] failed: {exc}"
                done.set()
                return
            if isinstance(answer, Deferred):
                answer.then(finish)
            else:
                finish(answer)

        if isinstance(self.handler, OnReceivingThread):
            run()
        else:
            self._executor.post(run)
        if not done.wait(HANDLER_TIMEOUT_S):
            return False, f"service [{self.name}] did not answer in {HANDLER_TIMEOUT_S} s".encode()
        if "error" in box:
            return False, str(box["error"]).encode()
        try:
            return True, self.kind.response.encode(box["response"])
        except Exception as exc:
            log_failure(log, "service %s: cannot encode the response", self.name)
            return False, f"service [{self.name}] answered something unencodable: {exc}".encode()


def _lookup(master: str, caller_id: str, name: str, timeout_s: float) -> tuple[str, int]:
    try:
        uri = str(call(master, "lookupService", caller_id, name, timeout_s=timeout_s))
        return split_uri(uri)
    except (Ros1WireError, Exception) as exc:
        raise ServiceCallError(f"service '{name}' is not available: {exc}") from None


def probe_service_type(master: str, caller_id: str, name: str, timeout_s: float = 3.0) -> str:
    """The ROS 1 type of service ``name`` (``std_srvs/Empty``), asked of its provider as
    rosservice's ``get_service_headers`` asks: a connection with ``probe=1`` and md5sum ``*``,
    whose reply header names the ``type``. ServiceCallError if no provider answers."""
    host, port = _lookup(master, caller_id, name, timeout_s)
    try:
        with socket.create_connection((host, port), timeout=max(0.1, timeout_s)) as sock:
            write_header(
                sock, {"callerid": caller_id, "md5sum": "*", "probe": "1", "service": name}
            )
            header = read_header(sock)
    except (OSError, TcprosError) as exc:
        raise ServiceCallError(f"service '{name}' did not answer a type probe: {exc}") from None
    if "error" in header or not header.get("type"):
        reason = header.get("error", "its header names no type")
        raise ServiceCallError(f"service '{name}' did not say its type: {reason}")
    return header["type"]


def call_service(
    master: str,
    caller_id: str,
    name: str,
    kind: Ros1ServiceType,
    request: Message,
    timeout_s: float,
    *,
    header_fields: dict[str, str] | None = None,
) -> Message:
    """Call ``name`` through the master's registration; ServiceCallError if it fails.
    ``header_fields`` go into the connection header (rospy's ``ServiceProxy(headers=...)``);
    a response whose class has genpy's ``_connection_header`` slot gets the provider's."""
    deadline = time.monotonic() + timeout_s
    host, port = _lookup(master, caller_id, name, timeout_s)
    try:
        with socket.create_connection((host, port), timeout=max(0.1, timeout_s)) as sock:
            write_header(
                sock,
                {
                    **(header_fields or {}),
                    "callerid": caller_id,
                    "md5sum": kind.md5sum,
                    "persistent": "0",
                    "service": name,
                },
            )
            header = read_header(sock)
            if "error" in header:
                raise ServiceCallError(f"service '{name}' refused the call: {header['error']}")
            write_frame(sock, kind.request.encode(request))
            sock.settimeout(max(0.1, deadline - time.monotonic()))
            ok = recv_exact(sock, 1)
            fixed = kind.response.fixed_size if ok == b"\x01" else None  # else an error text
            body = read_frame(sock, fixed or MAX_FRAME_BYTES)
    except (OSError, TcprosError) as exc:
        raise ServiceCallError(f"service '{name}' did not answer: {exc}") from None
    if ok != b"\x01":
        raise ServiceCallError(f"service '{name}' failed: {body.decode(errors='replace')}")
    return _with_header(kind.response.decode(body), header)


def _with_header(msg: Message, header: dict[str, str]) -> Message:
    """``msg`` with the connection header, if its class keeps one (genpy's, for rospy)."""
    if any("_connection_header" in getattr(c, "__slots__", ()) for c in type(msg).__mro__):
        msg._connection_header = header  # type: ignore[attr-defined]
    return msg
