"""A peer refused before its request was read reads the refusal, not a
reset, and a burst of connections past the XML-RPC request cap is refused at once.

A socket closed with unread input resets the connection (RST): a peer still sending its request
then fails in ``send`` and never reads the answer written for it. Each refusal test below sends
megabytes after the point where the server refuses, which a server that closed without
lingering (``robomodel.runtime.transport.ros1.linger``) answered with a reset (the peer's
``sendall`` failed); here the peer's send completes and it reads the refusal. In-process
servers; the peers are sockets of this process.
"""

from __future__ import annotations

import select
import socket
import threading
import xmlrpc.client
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from robomodel.runtime.executor import Executor
from robomodel.runtime.msg.schema import get_service_type
from robomodel.runtime.transport.ros1 import linger, xmlrpc_io
from robomodel.runtime.transport.ros1.budget import ByteBudget
from robomodel.runtime.transport.ros1.node_endpoint import NodeEndpoint
from robomodel.runtime.transport.ros1.publication import Publication
from robomodel.runtime.transport.ros1.ros1_types import ros1_service_type, ros1_type_named
from robomodel.runtime.transport.ros1.services import ServiceServer
from robomodel.runtime.transport.ros1.tcpros import encode_header, read_header
from robomodel.runtime.transport.ros1.xmlrpc_io import MAX_BODY_BYTES, MAX_CONCURRENT
from tests.timing import scaled, wait_until

MIB = 1 << 20
AFTER_REFUSAL = 8 * MIB  # more than loopback's socket buffers take while nobody reads


def _status_line(sock: socket.socket) -> bytes:
    sock.settimeout(scaled(30))
    return sock.recv(4096).split(b"\r\n", 1)[0]


@pytest.fixture(autouse=True)
def _fresh_throttle(monkeypatch: pytest.MonkeyPatch) -> None:
    """Refusal lines are held back per kind for 5 s in a process: each test starts afresh."""
    monkeypatch.setattr(xmlrpc_io, "_throttled", {})


@pytest.fixture
def server_factory() -> Iterator[Callable[[dict[str, Any]], xmlrpc_io.XmlRpcServer]]:
    servers: list[xmlrpc_io.XmlRpcServer] = []

    def make(api: dict[str, Any]) -> xmlrpc_io.XmlRpcServer:
        servers.append(xmlrpc_io.XmlRpcServer("127.0.0.1", 0, api))
        return servers[-1]

    yield make
    for server in servers:
        server.close()


def _post(port: int, body: bytes) -> socket.socket:
    sock = socket.create_connection(("127.0.0.1", port), timeout=scaled(30))
    sock.sendall(b"POST / HTTP/1.0\r\nContent-Length: %d\r\n\r\n" % len(body) + body)
    return sock


def test_a_burst_past_the_request_cap_waits_in_the_backlog_and_is_refused_at_once(
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
    server_factory: Callable[[dict[str, Any]], xmlrpc_io.XmlRpcServer],
) -> None:
    """While the server's accept loop is busy, the whole burst completes its handshakes in the
    listen backlog (with socketserver's backlog of 5 the kernel dropped the SYNs of the rest,
    whose clients retried for seconds: the first connections idled out and freed their slots
    before the last came, so nothing past the cap was refused); once it accepts, exactly the
    connections past the cap get a 503 and one log line, and one within it is served."""
    original = xmlrpc_io._Server.process_request
    accepting = threading.Event()

    def held(self: Any, request: Any, client_address: Any) -> None:
        accepting.wait(scaled(60))
        original(self, request, client_address)

    monkeypatch.setattr(xmlrpc_io._Server, "process_request", held)
    server = server_factory({"getPid": lambda caller_id: [1, "", 42]})
    burst = [socket.socket() for _ in range(MAX_CONCURRENT + 3)]
    try:
        for sock in burst:
            sock.setblocking(False)
            sock.connect_ex(("127.0.0.1", server.port))

        def all_connected() -> bool:
            return len(select.select([], burst, [], 0.1)[1]) == len(burst)

        wait_until(
            all_connected,
            30,
            what="every handshake of the burst while the server is busy",
            interval_s=0.02,
        )
        assert all(s.getsockopt(socket.SOL_SOCKET, socket.SO_ERROR) == 0 for s in burst)
        accepting.set()
        for sock in burst:
            sock.setblocking(True)
        past_cap = burst[MAX_CONCURRENT:]  # accepted in the order they connected
        assert [_status_line(sock) for sock in past_cap] == [
            b"HTTP/1.0 503 Service Unavailable"
        ] * 3
        request = xmlrpc.client.dumps(("/x",), "getPid").encode()
        within = burst[0]
        within.sendall(b"POST / HTTP/1.0\r\nContent-Length: %d\r\n\r\n" % len(request) + request)
        assert _status_line(within) == b"HTTP/1.0 200 OK"
    finally:
        accepting.set()
        for sock in burst:
            sock.close()
    lines = [r.getMessage() for r in caplog.records if "at once" in r.getMessage()]
    assert len(lines) == 1 and f"more than {MAX_CONCURRENT} requests" in lines[0], lines


def test_a_request_past_the_cap_that_sends_its_body_reads_its_503(
    server_factory: Callable[[dict[str, Any]], xmlrpc_io.XmlRpcServer],
) -> None:
    """The cap is full of requests being served; one more, which sends its request whole (as
    every XML-RPC client does before it reads), reads the 503 instead of a reset."""
    entered = threading.Semaphore(0)
    leave = threading.Event()

    def block(caller_id: str) -> list[Any]:
        entered.release()
        leave.wait(scaled(60))
        return [1, "", 0]

    server = server_factory({"block": block})
    request = xmlrpc.client.dumps(("/x",), "block").encode()
    held = [_post(server.port, request) for _ in range(MAX_CONCURRENT)]
    try:
        for _ in held:
            assert entered.acquire(timeout=scaled(30)), "the cap filled with served requests"
        late = socket.create_connection(("127.0.0.1", server.port), timeout=scaled(30))
        with late:
            late.sendall(b"POST / HTTP/1.0\r\nContent-Length: %d\r\n\r\n" % AFTER_REFUSAL)
            late.sendall(b"<" * AFTER_REFUSAL)  # a reset here was the bug
            assert _status_line(late) == b"HTTP/1.0 503 Service Unavailable"
        leave.set()
        assert {_status_line(sock) for sock in held} == {b"HTTP/1.0 200 OK"}
    finally:
        leave.set()
        for sock in held:
            sock.close()


@pytest.mark.parametrize(
    ("declared", "budget", "status", "logged"),
    [
        (MAX_BODY_BYTES + 1, None, b"413", "refusing a"),
        (16 * MIB, 1 * MIB, b"503", "in flight"),
    ],
    ids=["too-large-413", "budget-503"],
)
def test_a_refused_body_is_drained_and_its_refusal_read(
    monkeypatch: pytest.MonkeyPatch,
    caplog: pytest.LogCaptureFixture,
    server_factory: Callable[[dict[str, Any]], xmlrpc_io.XmlRpcServer],
    declared: int,
    budget: int | None,
    status: bytes,
    logged: str,
) -> None:
    if budget is not None:
        monkeypatch.setattr(xmlrpc_io, "BODIES", ByteBudget(budget))
    server = server_factory({"getPid": lambda caller_id: [1, "", 42]})
    with socket.create_connection(("127.0.0.1", server.port), timeout=scaled(30)) as sock:
        sock.sendall(b"POST / HTTP/1.0\r\nContent-Length: %d\r\n\r\n" % declared)
        sock.sendall(b"<" * AFTER_REFUSAL)  # what the server will not read
        sock.shutdown(socket.SHUT_WR)
        assert status in _status_line(sock)
    assert [r for r in caplog.records if logged in r.getMessage()]
    # the server answers afterwards, and gives the lingering connection back
    proxy = xmlrpc.client.ServerProxy(f"http://127.0.0.1:{server.port}/")
    assert proxy.getPid("/x") == [1, "", 42]
    wait_until(
        lambda: linger.lingering() == 0, 30, what="the lingering connection closed", interval_s=0.02
    )


@pytest.fixture
def endpoint() -> Iterator[NodeEndpoint]:
    node = NodeEndpoint("/refuser", "http://127.0.0.1:1/", "127.0.0.1")
    kind = ros1_type_named("std_msgs/String")
    node.publications["/chatter"] = Publication(
        "/refuser", "/chatter", kind, latch=False, queue_size=1
    )
    service = ros1_service_type(get_service_type("std_srvs/srv/Empty"))
    node.services["/reset"] = ServiceServer(
        "/refuser", "/reset", service, lambda request: request, Executor()
    )
    try:
        yield node
    finally:
        node.close()


WRONG_MD5 = "0" * 32


@pytest.mark.parametrize(
    ("header", "error"),
    [
        ({"callerid": "/x"}, "neither 'topic' nor 'service'"),
        ({"callerid": "/x", "topic": "/nothing", "md5sum": "*"}, "does not publish /nothing"),
        (
            {"callerid": "/x", "topic": "/chatter", "md5sum": WRONG_MD5, "type": "std_msgs/String"},
            "Dropping connection",
        ),
        ({"callerid": "/x", "service": "/nothing", "md5sum": "*"}, "does not offer /nothing"),
        ({"callerid": "/x", "service": "/reset", "md5sum": WRONG_MD5}, "md5sums do not match"),
    ],
    ids=["no-topic-or-service", "unknown-topic", "topic-md5", "unknown-service", "service-md5"],
)
def test_a_refused_tcpros_connection_reads_its_error_header(
    endpoint: NodeEndpoint, header: dict[str, str], error: str
) -> None:
    """A TCPROS peer that sends frames right after its header (a pipelining client, or a
    request sent with the service header) reads the error header it was refused with."""
    with socket.create_connection(("127.0.0.1", endpoint.tcpros_port), timeout=scaled(30)) as sock:
        sock.sendall(encode_header(header))
        sock.sendall(b"\0" * AFTER_REFUSAL)  # a reset here was the bug
        sock.shutdown(socket.SHUT_WR)
        answer = read_header(sock)
    assert error in answer.get("error", ""), answer


def test_lingering_is_bounded_in_connections_and_time_and_its_thread_ends(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    wait_until(
        lambda: linger.lingering() == 0,
        30,
        what="connections of earlier tests closed",
        interval_s=0.02,
    )
    monkeypatch.setattr(linger, "MAX_LINGERING", 2)
    monkeypatch.setattr(linger, "LINGER_S", 0.2)  # a peer that never closes
    pairs = [socket.socketpair() for _ in range(3)]
    try:
        for ours, _ in pairs:
            linger.close_after_answer(ours)
        assert linger.lingering() == 2
        assert pairs[2][0].fileno() == -1  # past the bound: closed at once
        for _, peer in pairs:
            peer.settimeout(scaled(30))
            assert peer.recv(1) == b""  # the writing side is shut down at once
        wait_until(
            lambda: linger.lingering() == 0,
            30,
            what="lingering connections closed at their deadline",
            interval_s=0.02,
        )
        assert all(ours.fileno() == -1 for ours, _ in pairs)
        monkeypatch.setattr(linger, "LINGER_S", 600.0)
        ours, peer = socket.socketpair()
        with peer:
            linger.close_after_answer(ours)
            peer.sendall(b"x" * MIB)  # read and discarded
            assert linger.lingering() == 1
        wait_until(
            lambda: ours.fileno() == -1,
            30,
            what="a lingering connection closed when its peer did",
            interval_s=0.02,
        )
        wait_until(
            lambda: all(t.name != "ros1-linger" for t in threading.enumerate()),
            30,
            what="the lingering thread ended with nothing left to drain",
            interval_s=0.02,
        )
    finally:
        for ours, peer in pairs:
            ours.close()
            peer.close()
