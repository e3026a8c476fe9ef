"""XML-RPC for the ROS 1 master and slave APIs, over the standard library, within bounds.

- :class:`XmlRpcServer` answers POSTs on one port with the methods of one API object (the
  ROS ``[code, statusMessage, value]`` triples), and ``system.multicall`` as rosgraph's
  servers do (rospy unregisters through it when a node ends). A request body above
  ``MAX_BODY_BYTES``, or one that would take the bodies in flight in this process above
  ``MAX_BODIES_IN_FLIGHT_BYTES``, gets an HTTP error (413, 503) and one log line; so does a
  request past ``MAX_CONCURRENT`` at once on one server (503). The listen backlog holds a
  burst of connections past the cap, so that each is accepted and refused at once (a backlog
  of 5 made the kernel drop SYNs and the flood's clients retry for seconds). A connection
  answered before its request was read whole is closed by :mod:`.linger` (its writing side
  shut down, what the peer still sends read and discarded within a bound), so that the peer
  reads its answer instead of a reset. A body that is not XML-RPC, an
  unknown method or a wrong argument count gets an error answer. A peer that sends nothing for
  ``IDLE_TIMEOUT_S``, or has not sent its whole request within ``REQUEST_TIMEOUT_S`` (a
  slowloris), is dropped. A peer that goes away mid-request costs one log line, no traceback;
  these lines are rate-limited (``log_throttled``). XML is parsed by expat (2.4.1 and later
  refuse entity-expansion bombs; external entities are never fetched).
- :func:`call` calls a method of another node or of the master and checks the triple; its
  answer is read up to ``MAX_BODY_BYTES`` too.
"""

from __future__ import annotations

import http.client
import io
import logging
import socket
import sys
import threading
import time
import xmlrpc.client
from collections.abc import Callable, Mapping
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.transport._failures import log_failure
from robomodel.runtime.transport.ros1.budget import ByteBudget
from robomodel.runtime.transport.ros1.linger import close_after_answer

__all__ = [
    "MAX_BODIES_IN_FLIGHT_BYTES",
    "MAX_BODY_BYTES",
    "MAX_CONCURRENT",
    "Ros1WireError",
    "XmlRpcServer",
    "call",
    "call_raw",
    "log_throttled",
]

log = logging.getLogger("robomodel.ros1")

MAX_BODY_BYTES = 64 << 20  # a robot_description with inlined meshes stays far below
MAX_BODIES_IN_FLIGHT_BYTES = 128 << 20  # every server of this process together
MAX_CONCURRENT = 64  # requests served at once, per server
LISTEN_BACKLOG = 2 * MAX_CONCURRENT  # connections waiting to be accepted (and maybe refused)
IDLE_TIMEOUT_S = 10.0
REQUEST_TIMEOUT_S = 30.0  # the whole request: 64 MiB needs > 2 MiB/s
THROTTLE_S = 5.0


class Ros1WireError(RobomodelError):
    """A ROS 1 master or node that cannot be reached, or that answered with an error."""


_throttle_lock = threading.Lock()
_throttled: dict[str, tuple[float, int]] = {}  # kind -> (last line's time, lines held back)


def log_throttled(kind: str, message: str, *args: object) -> None:
    """One warning line per ``kind`` per ``THROTTLE_S``; the lines held back are counted in the
    next one, so a flood of hostile connections cannot flood the log."""
    now = time.monotonic()
    with _throttle_lock:
        last, held = _throttled.get(kind, (-THROTTLE_S, 0))
        if now - last < THROTTLE_S:
            _throttled[kind] = (last, held + 1)
            return
        _throttled[kind] = (now, 0)
    suffix = f" ({held} more like it in the last {THROTTLE_S:.0f} s)" if held else ""
    log.warning(message + suffix, *args)


BODIES = ByteBudget(MAX_BODIES_IN_FLIGHT_BYTES)
_BUSY = b"HTTP/1.0 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"


class _Server(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True
    request_queue_size = LISTEN_BACKLOG

    def __init__(
        self,
        address: tuple[str, int],
        api: Mapping[str, Callable[..., Any]],
        request_timeout_s: float,
    ) -> None:
        self.api = api
        self.request_timeout_s = request_timeout_s
        self.slots = threading.BoundedSemaphore(MAX_CONCURRENT)
        self.address_family = socket.AF_INET6 if ":" in address[0] else socket.AF_INET
        super().__init__(address, _Handler)

    def server_bind(self) -> None:
        if self.address_family == socket.AF_INET6 and self.server_address[0] == "::":
            self.socket.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 0)  # IPv4 too
        super().server_bind()

    def process_request(self, request: Any, client_address: Any) -> None:
        if not self.slots.acquire(blocking=False):
            log_throttled(
                "xmlrpc-busy",
                "XML-RPC: more than %d requests at once; answering 503 to %s",
                MAX_CONCURRENT,
                client_address,
            )
            try:
                request.settimeout(0.5)
                request.sendall(_BUSY)
            except OSError:
                pass
            close_after_answer(request)  # its request, sent or coming, is not read
            return
        super().process_request(request, client_address)

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        """ThreadingMixIn's, but a request answered before it was read whole (an error) is
        closed by lingering, and the slot is given back either way."""
        answered_early = False
        try:
            answered_early = _Handler(request, client_address, self).answered_early
        except Exception:
            self.handle_error(request, client_address)
        finally:
            try:
                if answered_early:
                    close_after_answer(request)
                else:
                    self.shutdown_request(request)
            finally:
                self.slots.release()

    def handle_error(self, request: Any, client_address: Any) -> None:
        """One line instead of socketserver's traceback: a peer that closes mid-request."""
        exc = sys.exc_info()[1]
        log_throttled(
            "xmlrpc-dropped",
            "XML-RPC: a request from %s ended early: %s: %s",
            client_address,
            type(exc).__name__,
            str(exc)[:200],
        )


class _DeadlineReader(io.RawIOBase):
    """A socket's reading side that gives up at ``deadline`` (a slowloris cannot hold a
    thread by sending one byte at a time) and after ``idle_s`` without data."""

    def __init__(self, sock: socket.socket, deadline: float, idle_s: float) -> None:
        self._sock, self._deadline, self._idle_s = sock, deadline, idle_s

    def readable(self) -> bool:
        return True

    def readinto(self, buffer: Any) -> int:
        remaining = self._deadline - time.monotonic()
        if remaining <= 0:
            raise TimeoutError("the request was not complete in time")
        self._sock.settimeout(min(remaining, self._idle_s))
        return self._sock.recv_into(buffer)


class _Handler(BaseHTTPRequestHandler):
    server: _Server
    timeout = IDLE_TIMEOUT_S
    answered_early = False  # an error answer, written before the request was read whole

    def send_error(self, code: int, message: str | None = None, explain: str | None = None) -> None:
        self.answered_early = True
        super().send_error(code, message, explain)

    def setup(self) -> None:
        super().setup()
        deadline = time.monotonic() + self.server.request_timeout_s
        self.rfile = io.BufferedReader(_DeadlineReader(self.connection, deadline, self.timeout))

    def log_message(self, format: str, *args: Any) -> None:
        log.debug("XML-RPC %s: " + format, self.client_address, *args)

    def log_error(self, format: str, *args: Any) -> None:
        if format.startswith("Request timed out"):
            log_throttled("xmlrpc-timeout", "XML-RPC: dropped %s: %s", self.client_address, args)
        else:  # send_error's own line; the reason was logged where it was decided
            self.log_message(format, *args)

    def do_POST(self) -> None:
        try:
            size = int(self.headers.get("Content-Length", ""))
        except ValueError:
            self.send_error(411, "Content-Length required")
            return
        if not 0 <= size <= MAX_BODY_BYTES:
            log_throttled(
                "xmlrpc-large",
                "XML-RPC: refusing a %d-byte request from %s (at most %d)",
                size,
                self.client_address,
                MAX_BODY_BYTES,
            )
            self.send_error(413, f"request larger than {MAX_BODY_BYTES} bytes")
            return
        if not BODIES.take(size):
            log_throttled(
                "xmlrpc-budget",
                "XML-RPC: refusing a %d-byte request from %s: %d bytes of requests in flight "
                "(at most %d)",
                size,
                self.client_address,
                BODIES.used,
                BODIES.limit,
            )
            self.send_error(503, "too many request bytes in flight; retry later")
            return
        try:
            self._serve(size)
        finally:
            BODIES.give(size)

    def _serve(self, size: int) -> None:
        body = self.rfile.read(size)
        if len(body) < size:
            raise ConnectionError(f"the peer closed after {len(body)} of {size} bytes")
        try:
            params, method = xmlrpc.client.loads(body, use_builtin_types=True)
        except Exception as exc:  # expat errors, bad values: the peer's fault
            log_throttled(
                "xmlrpc-malformed",
                "XML-RPC: malformed request from %s: %s",
                self.client_address,
                str(exc)[:200],
            )
            self._reply(xmlrpc.client.dumps(xmlrpc.client.Fault(-32700, "parse error")))
            return
        del body
        self._reply(self._dispatch(str(method), params))

    def _dispatch(self, method: str, params: tuple[Any, ...]) -> str:
        if method == "system.multicall":
            result: Any = self._multicall(params)
        else:
            try:
                result = self._call(method, params)
            except xmlrpc.client.Fault as fault:
                return xmlrpc.client.dumps(fault, methodresponse=True)
        try:
            return xmlrpc.client.dumps((result,), methodresponse=True, allow_none=False)
        except (TypeError, OverflowError) as exc:
            log_failure(log, "XML-RPC: cannot marshal the answer of %s", method)
            return xmlrpc.client.dumps(([0, f"Internal failure: {exc}", 0],), methodresponse=True)

    def _call(self, method: str, params: Any) -> Any:
        function = self.server.api.get(method)
        if function is None or not isinstance(params, tuple | list):
            raise xmlrpc.client.Fault(-32601, f"method '{method[:100]}' not supported")
        try:
            return function(*params)
        except TypeError as exc:
            log_throttled(
                "xmlrpc-arity",
                "XML-RPC: bad call of %s from %s: %s",
                method,
                self.client_address,
                exc,
            )
            return [-1, f"Error: bad call arity or arguments: {exc}", 0]
        except Exception as exc:
            log_failure(log, "XML-RPC: %s failed", method)
            return [0, f"Internal failure: {exc}", 0]

    def _multicall(self, params: tuple[Any, ...]) -> list[Any]:
        """SimpleXMLRPCDispatcher.system_multicall: ``[[result] | fault struct, ...]``."""
        calls = params[0] if len(params) == 1 and isinstance(params[0], list) else None
        if calls is None:
            return [{"faultCode": -32602, "faultString": "system.multicall takes one list"}]
        results: list[Any] = []
        for one in calls:
            try:
                if not isinstance(one, dict) or one.get("methodName") == "system.multicall":
                    raise xmlrpc.client.Fault(-32600, "not a call (or a nested multicall)")
                results.append([self._call(str(one.get("methodName")), one.get("params", []))])
            except xmlrpc.client.Fault as fault:
                results.append({"faultCode": fault.faultCode, "faultString": fault.faultString})
        return results

    def _reply(self, text: str) -> None:
        body = text.encode()
        self.connection.settimeout(self.timeout)  # the answer may take longer than the rest
        self.send_response(200)
        self.send_header("Content-Type", "text/xml")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


class XmlRpcServer:
    """An XML-RPC server on ``host:port`` (0: any free port) serving ``api``'s functions.
    ``host`` may be an IPv6 address (``::1``; ``::`` takes IPv4 too)."""

    def __init__(
        self,
        host: str,
        port: int,
        api: Mapping[str, Callable[..., Any]],
        *,
        request_timeout_s: float = REQUEST_TIMEOUT_S,
    ) -> None:
        try:
            self._server = _Server((host, port), api, request_timeout_s)
        except OSError as exc:
            raise Ros1WireError(f"cannot listen on {host}:{port}: {exc.strerror}") from None
        self.port = int(self._server.server_address[1])
        self._thread = threading.Thread(
            target=self._server.serve_forever, name=f"ros1-xmlrpc-{self.port}", daemon=True
        )
        self._thread.start()

    def close(self) -> None:
        self._server.shutdown()
        self._server.server_close()


class _BoundedTransport(xmlrpc.client.Transport):
    """xmlrpc.client's transport with a timeout and a cap on the answer's size. It does not
    ask for gzip (rosmaster would compress a large parameter): a compressed answer could
    expand past any cap."""

    accept_gzip_encoding = False

    def __init__(self, timeout_s: float) -> None:
        super().__init__(use_builtin_types=True)
        self._timeout_s = timeout_s

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout_s
        return connection

    def parse_response(self, response: http.client.HTTPResponse) -> Any:
        parser, unmarshaller = self.getparser()
        received = 0
        while chunk := response.read(1 << 16):
            received += len(chunk)
            if received > MAX_BODY_BYTES:
                raise Ros1WireError(f"an XML-RPC answer above {MAX_BODY_BYTES} bytes")
            parser.feed(chunk)
        response.close()
        parser.close()
        return unmarshaller.close()


def call_raw(uri: str, method: str, *args: Any, timeout_s: float = 5.0) -> Any:
    """``method(*args)`` at ``uri``: whatever it answers; Ros1WireError if nothing does."""
    try:  # a peer's URI may be anything: ServerProxy refuses an unknown scheme with OSError
        proxy = xmlrpc.client.ServerProxy(uri, transport=_BoundedTransport(timeout_s))
    except (OSError, ValueError, TypeError) as exc:
        raise Ros1WireError(f"cannot call {str(uri)[:200]!r}: {exc}") from None
    try:
        return getattr(proxy, method)(*args)
    except xmlrpc.client.Fault as exc:
        raise Ros1WireError(f"{uri} {method}: {exc.faultString}") from None
    except TimeoutError:
        raise Ros1WireError(f"{uri} did not answer {method} within {timeout_s} s") from None
    except (OSError, http.client.HTTPException, xmlrpc.client.ProtocolError) as exc:
        raise Ros1WireError(f"{uri} does not answer {method}: {exc}") from None
    except Exception as exc:  # expat errors in a malformed answer
        raise Ros1WireError(f"{uri} answered {method} with something malformed: {exc}") from None
    finally:
        proxy("close")()


def call(uri: str, method: str, *args: Any, timeout_s: float = 5.0) -> Any:
    """``method(*args)`` at ``uri`` under the ROS API convention: the value of a
    ``[1, message, value]`` answer; Ros1WireError with the message for any other code."""
    answer = call_raw(uri, method, *args, timeout_s=timeout_s)
    if not (isinstance(answer, list | tuple) and len(answer) == 3):
        raise Ros1WireError(f"{uri} {method}: not a [code, message, value] answer: {answer!r:.80}")
    code, message, value = answer
    if code != 1:
        raise Ros1WireError(f"{method}: {message}")
    return value
