"""XML-RPC for the ROS 1 master and slave APIs, over the standard library, within bounds.

- :class:`XmlRpcServer` answers POSTs on one port with the methods of one API object (the
  ROS ``[code, statusMessage, value]`` triples). A request body above ``MAX_BODY_BYTES``, one
  that is not XML-RPC, an unknown method or a wrong argument count gets a one-line log and an
  error answer; at most ``MAX_CONCURRENT`` requests are served at once and a peer that stalls
  is dropped after ``REQUEST_TIMEOUT_S``. XML is parsed by expat (2.4.1 and later refuse
  entity-expansion bombs; external entities are never fetched).
- :func:`call` calls a method of another node or of the master and checks the triple; its
  answer is read up to ``MAX_BODY_BYTES`` too.
"""

from __future__ import annotations

import http.client
import logging
import threading
import xmlrpc.client
from collections.abc import Callable, Mapping
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.transport._failures import log_failure

__all__ = [
    "MAX_BODY_BYTES",
    "Ros1WireError",
    "XmlRpcServer",
    "call",
    "call_raw",
]

log = logging.getLogger("robomodel.ros1")

MAX_BODY_BYTES = 64 << 20  # a robot_description with inlined meshes stays far below
MAX_CONCURRENT = 64
REQUEST_TIMEOUT_S = 10.0


class Ros1WireError(RobomodelError):
    """A ROS 1 master or node that cannot be reached, or that answered with an error."""


class _Server(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, address: tuple[str, int], api: Mapping[str, Callable[..., Any]]) -> None:
        self.api = api
        self.slots = threading.BoundedSemaphore(MAX_CONCURRENT)
        super().__init__(address, _Handler)

    def process_request(self, request: Any, client_address: Any) -> None:
        if not self.slots.acquire(blocking=False):
            log.warning("XML-RPC: too many requests at once; dropping one from %s", client_address)
            self.shutdown_request(request)
            return
        super().process_request(request, client_address)

    def process_request_thread(self, request: Any, client_address: Any) -> None:
        try:
            super().process_request_thread(request, client_address)
        finally:
            self.slots.release()


class _Handler(BaseHTTPRequestHandler):
    server: _Server
    timeout = REQUEST_TIMEOUT_S

    def log_message(self, format: str, *args: Any) -> None:
        log.debug("XML-RPC %s: " + format, self.client_address, *args)

    def do_POST(self) -> None:
        try:
            size = int(self.headers.get("Content-Length", ""))
        except ValueError:
            self.send_error(411, "Content-Length required")
            return
        if not 0 <= size <= MAX_BODY_BYTES:
            log.warning("XML-RPC: refusing a %d-byte request from %s", size, self.client_address)
            self.send_error(413, "request too large")
            return
        try:
            params, method = xmlrpc.client.loads(self.rfile.read(size), use_builtin_types=True)
        except Exception as exc:  # expat errors, bad values: the peer's fault
            log.warning("XML-RPC: malformed request from %s: %s", self.client_address, exc)
            self._reply(xmlrpc.client.dumps(xmlrpc.client.Fault(-32700, "parse error")))
            return
        self._reply(self._dispatch(str(method), params))

    def _dispatch(self, method: str, params: tuple[Any, ...]) -> str:
        function = self.server.api.get(method)
        if function is None:
            fault = xmlrpc.client.Fault(-32601, f"method '{method}' not supported")
            return xmlrpc.client.dumps(fault, methodresponse=True)
        try:
            result = function(*params)
        except TypeError as exc:
            log.warning("XML-RPC: bad call of %s from %s: %s", method, self.client_address, exc)
            result = [-1, f"Error: bad call arity or arguments: {exc}", 0]
        except Exception as exc:
            log_failure(log, "XML-RPC: %s failed", method)
            result = [0, f"Internal failure: {exc}", 0]
        try:
            return xmlrpc.client.dumps((result,), methodresponse=True, allow_none=False)
        except (TypeError, OverflowError) as exc:
            log_failure(log, "XML-RPC: cannot marshal the answer of %s", method)
            return xmlrpc.client.dumps(([0, f"Internal failure: {exc}", 0],), methodresponse=True)

    def _reply(self, text: str) -> None:
        body = text.encode()
        self.send_response(200)
        self.send_header("Content-Type", "text/xml")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


class XmlRpcServer:
    """An XML-RPC server on ``host:port`` (0: any free port) serving ``api``'s functions."""

    def __init__(self, host: str, port: int, api: Mapping[str, Callable[..., Any]]) -> None:
        try:
            self._server = _Server((host, port), api)
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
    proxy = xmlrpc.client.ServerProxy(uri, transport=_BoundedTransport(timeout_s))
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
