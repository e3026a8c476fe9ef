"""One bound per resource: a node's TCPROS server caps the subscriber connections
and the service connections of its process, each of which holds a thread while it lasts.

A hostile peer that opens connections with valid headers gets the cap's worth served; past it
each connection reads an error header (roscpp's refusal), one log line names the cap, and the
process's thread count stays within the cap plus a few. A connection that ends gives its slot
back, and a new connection is served. In-process node; the peers are sockets of this process.
"""

from __future__ import annotations

import select
import socket
import threading
from collections.abc import Iterator

import pytest

from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import get_message_type
from robomodel.runtime.msg.schema import get_service_type
from robomodel.runtime.transport.ros1 import publication, services, xmlrpc_io
from robomodel.runtime.transport.ros1.node_endpoint import NodeEndpoint
from robomodel.runtime.transport.ros1.publication import (
    MAX_SUBSCRIBER_CONNECTIONS,
    Publication,
    subscriber_connections,
)
from robomodel.runtime.transport.ros1.ros1_types import ros1_service_type, ros1_type_named
from robomodel.runtime.transport.ros1.services import (
    MAX_SERVICE_CONNECTIONS,
    ServiceServer,
    service_connections,
)
from robomodel.runtime.transport.ros1.tcpros import (
    encode_header,
    read_frame,
    read_header,
    recv_exact,
    write_frame,
)
from tests.timing import scaled, wait_until

PAST_CAP = 3
FEW_THREADS = 16  # the handshake, lingering and executor threads, and a refusal in progress


@pytest.fixture(autouse=True)
def _fresh_throttle(monkeypatch: pytest.MonkeyPatch) -> None:
    """Refusal lines are held back per kind for 5 s in a process: each test starts afresh."""
    monkeypatch.setattr(xmlrpc_io, "_throttled", {})


@pytest.fixture
def executor() -> Executor:
    return Executor()


@pytest.fixture
def endpoint(executor: Executor) -> Iterator[NodeEndpoint]:
    wait_until(
        lambda: subscriber_connections() == 0,
        30,
        what="subscriber connections of earlier tests",
        interval_s=0.02,
    )
    wait_until(
        lambda: service_connections() == 0,
        30,
        what="service connections of earlier tests",
        interval_s=0.02,
    )
    node = NodeEndpoint("/capped", "http://127.0.0.1:1/", "127.0.0.1")
    kind = ros1_type_named("std_msgs/String")
    node.publications["/chatter"] = Publication(
        "/capped", "/chatter", kind, latch=True, queue_size=1
    )
    trigger = get_service_type("std_srvs/srv/Trigger")
    node.services["/trigger"] = ServiceServer(
        "/capped", "/trigger", ros1_service_type(trigger),
        lambda request: trigger.Response(success=True, message="ok"), executor,
    )  # fmt: skip
    try:
        yield node
    finally:
        node.close()


def _connect(node: NodeEndpoint, header: dict[str, str]) -> tuple[socket.socket, dict[str, str]]:
    sock = socket.create_connection(("127.0.0.1", node.tcpros_port), timeout=scaled(30))
    sock.sendall(encode_header(header))
    return sock, read_header(sock)


def _threads(name: str) -> int:
    return sum(t.name == name for t in threading.enumerate())


SUBSCRIBER = {"callerid": "/flood", "topic": "/chatter", "md5sum": "*", "type": "*"}


def test_29_subscriber_connections_past_the_cap_read_an_error_header(
    endpoint: NodeEndpoint, caplog: pytest.LogCaptureFixture
) -> None:
    before = threading.active_count()
    opened: list[socket.socket] = []
    try:
        answers = []
        for _ in range(MAX_SUBSCRIBER_CONNECTIONS + PAST_CAP):
            sock, answer = _connect(endpoint, SUBSCRIBER)
            opened.append(sock)
            answers.append(answer)
        refused = [a["error"] for a in answers if "error" in a]
        assert len(refused) == PAST_CAP, refused
        assert all("already (its process's limit)" in e for e in refused), refused
        assert all(a["topic"] == "/chatter" for a in answers[:MAX_SUBSCRIBER_CONNECTIONS])
        assert subscriber_connections() == MAX_SUBSCRIBER_CONNECTIONS
        # a subscriber reads its reply header just before its writer thread starts
        wait_until(
            lambda: _threads("ros1-pub-writer") == MAX_SUBSCRIBER_CONNECTIONS,
            30,
            what="a writer thread per subscriber",
            interval_s=0.02,
        )
        assert threading.active_count() <= before + MAX_SUBSCRIBER_CONNECTIONS + FEW_THREADS
        lines = [r.getMessage() for r in caplog.records if "MAX_SUBSCRIBER" in r.getMessage()]
        assert len(lines) == 1 and f"more than {MAX_SUBSCRIBER_CONNECTIONS}" in lines[0], lines
        # one subscriber leaves, without anything published: its writer notices, its slot is
        # given back, and a new subscriber is served (and gets the latched message)
        opened.pop(0).close()
        wait_until(
            lambda: subscriber_connections() < MAX_SUBSCRIBER_CONNECTIONS,
            30,
            what="a slot back",
            interval_s=0.02,
        )
        endpoint.publications["/chatter"].publish(
            get_message_type("std_msgs/msg/String")(data="latched")
        )
        sock, answer = _connect(endpoint, SUBSCRIBER)
        opened.append(sock)
        assert "error" not in answer and answer["latching"] == "1", answer
        assert b"latched" in read_frame(sock)
    finally:
        for sock in opened:
            sock.close()
    wait_until(
        lambda: subscriber_connections() == 0,
        30,
        what="every slot back once all closed",
        interval_s=0.02,
    )
    wait_until(
        lambda: _threads("ros1-pub-writer") == 0,
        30,
        what="every writer thread ended",
        interval_s=0.02,
    )


def test_29_service_connections_past_the_cap_read_an_error_header(
    endpoint: NodeEndpoint, executor: Executor, caplog: pytest.LogCaptureFixture
) -> None:
    """Persistent service clients that connect and send no request each hold a thread."""
    header = {"callerid": "/flood", "service": "/trigger", "md5sum": "*", "persistent": "1"}
    before = threading.active_count()
    opened: list[socket.socket] = []
    try:
        answers = []
        for _ in range(MAX_SERVICE_CONNECTIONS + PAST_CAP):
            sock, answer = _connect(endpoint, header)
            opened.append(sock)
            answers.append(answer)
        refused = [a["error"] for a in answers if "error" in a]
        assert len(refused) == PAST_CAP, refused
        assert all("already (its process's limit)" in e for e in refused), refused
        assert service_connections() == MAX_SERVICE_CONNECTIONS
        wait_until(
            lambda: _threads("ros1-tcpros-conn") == MAX_SERVICE_CONNECTIONS,
            30,
            what="the refusals' threads ended",
            interval_s=0.02,
        )
        assert threading.active_count() <= before + MAX_SERVICE_CONNECTIONS + FEW_THREADS
        lines = [r.getMessage() for r in caplog.records if "MAX_SERVICE" in r.getMessage()]
        assert len(lines) == 1 and f"more than {MAX_SERVICE_CONNECTIONS}" in lines[0], lines
        opened.pop(0).close()
        wait_until(
            lambda: service_connections() < MAX_SERVICE_CONNECTIONS,
            30,
            what="a slot back",
            interval_s=0.02,
        )
        sock, answer = _connect(endpoint, header)
        opened.append(sock)
        assert "error" not in answer and answer["type"] == "std_srvs/Trigger", answer
        write_frame(sock, b"")  # std_srvs/Trigger's request is empty
        executor.spin(  # the handler runs on the executor's thread
            until=lambda: bool(select.select([sock], [], [], 0)[0]), duration_s=scaled(30)
        )
        assert recv_exact(sock, 1) == b"\x01"
        assert read_frame(sock).endswith(b"ok")
    finally:
        for sock in opened:
            sock.close()
    wait_until(
        lambda: service_connections() == 0,
        30,
        what="every slot back once all closed",
        interval_s=0.02,
    )


def test_29_the_caps_count_the_process_not_one_node(endpoint: NodeEndpoint) -> None:
    """Slots are the process's: a second node's subscriber is refused while the first node's
    fill the cap."""
    assert publication._SLOTS is not services._SLOTS
    second = NodeEndpoint("/second", "http://127.0.0.1:1/", "127.0.0.1")
    second.publications["/chatter"] = Publication(
        "/second", "/chatter", ros1_type_named("std_msgs/String"), latch=False, queue_size=1
    )
    opened: list[socket.socket] = []
    try:
        for _ in range(MAX_SUBSCRIBER_CONNECTIONS):
            opened.append(_connect(endpoint, SUBSCRIBER)[0])
        sock, answer = _connect(second, SUBSCRIBER)
        opened.append(sock)
        assert "error" in answer, answer
    finally:
        for sock in opened:
            sock.close()
        second.close()
    wait_until(
        lambda: subscriber_connections() == 0,
        30,
        what="every slot back once all closed",
        interval_s=0.02,
    )
