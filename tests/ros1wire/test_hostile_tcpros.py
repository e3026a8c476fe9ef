"""Hostile TCPROS peers against a robomodel node process: each
attack is refused or survived within its bound, in the process under test, with one log line
and no traceback, and the node answers afterwards (and ends promptly on SIGTERM).

The master is robomodel's, in the test's process; the process under test is a ``robomodel
topic`` command; the attackers are sockets of this process."""

from __future__ import annotations

import contextlib
import selectors
import signal
import socket
import struct
import subprocess
import threading
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest

from robomodel.runtime.transport.ros1.handshakes import MAX_HANDSHAKES
from robomodel.runtime.transport.ros1.master import Master
from robomodel.runtime.transport.ros1.publication import MAX_SUBSCRIBER_CONNECTIONS
from robomodel.runtime.transport.ros1.subscription import MAX_PUBLISHERS
from robomodel.runtime.transport.ros1.tcpros import (
    FRAME_BUDGET_BYTES,
    TcprosError,
    encode_header,
    read_header,
)
from robomodel.runtime.transport.ros1.xmlrpc_io import XmlRpcServer
from tests.measured import MIB, peak_rss_bytes, thread_count
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled, wait_until

STRING_MD5 = "992ce8a1687cec8c8bd883ec73ca41d1"
FLOAT64_MD5 = "fdb28210bfa9d7c91146260178d9a584"
# A ``robomodel topic`` process peaks near 100 MiB; each bound below adds what it allows.
BASE_RSS = 200 * MIB


@pytest.fixture
def master(ros1: Ros1) -> Iterator[Master]:
    m = Master(ros1.uri, "127.0.0.1")
    try:
        yield m
    finally:
        m.close()


def _node_api(ros1: Ros1, topic: str, kind: str) -> str:
    """The slave API URI of the first node that publishes (``pub``) or subscribes (``sub``)
    ``topic``, once the master has it."""
    proxy = xmlrpc.client.ServerProxy(ros1.uri)
    found: list[str] = []

    def registered() -> bool:
        pubs, subs, _ = proxy.getSystemState("/test")[2]
        for name, nodes in pubs if kind == "pub" else subs:
            if name == topic and nodes:
                found.append(proxy.lookupNode("/test", nodes[0])[2])
                return True
        return False

    ros1.until(registered, f"a {kind} of {topic}")
    return found[0]


def _log_lines(log: Path, word: str) -> list[str]:
    return [line for line in log.read_text().splitlines() if word in line]


def _sigterm_ends(proc: subprocess.Popen[str], log: Path) -> None:
    proc.send_signal(signal.SIGTERM)
    proc.wait(scaled(60))  # a node with thousands of threads did not end at all
    assert "Traceback" not in log.read_text(), log.read_text()


def test_publisher_update_with_3000_dead_uris(ros1: Ros1, master: Master, tmp_path: Path) -> None:
    """Finding 2: 3,000 dead publisher URIs gave 2,370 threads, the node's XML-RPC server
    stopped answering and SIGTERM did not end it. The URIs lead to a listener that never
    answers, so every connection attempt waits for its timeout."""
    log = tmp_path / "echo.log"
    proc = ros1.robomodel("topic", "echo", "/chatter", "std_msgs/msg/String", log=log)
    api = xmlrpc.client.ServerProxy(_node_api(ros1, "/chatter", "sub"))
    with socket.create_server(("127.0.0.1", 0), backlog=4096) as blackhole:
        port = blackhole.getsockname()[1]
        dead = [f"http://127.0.0.1:{port}/dead{k}" for k in range(3000)]
        assert api.publisherUpdate("/master", "/chatter", dead)[0] == 1
        threads = thread_count(proc.pid)
        assert threads < MAX_PUBLISHERS + 50, threads
        assert api.getPid("/test")[2] == proc.pid  # the slave API answers
        bus = api.getBusInfo("/test")[2]
        assert len(bus) == MAX_PUBLISHERS
        warned = _log_lines(log, "publishers listed")
        assert warned == [
            f"/chatter: 3000 publishers listed; reading from {MAX_PUBLISHERS} of them, "
            "the others are ignored"
        ], log.read_text()
        assert peak_rss_bytes(proc.pid) < BASE_RSS
        _sigterm_ends(proc, log)


class _FakePublisher:
    """A node that publishes ``topic`` with the right header, then sends ``frame_bytes`` as
    the size of a message: ``lead`` bytes of it at once, the rest when ``go`` is set, then a
    small message. It counts the connections the subscriber closed before the frame was
    whole."""

    def __init__(self, md5: str, frame_bytes: int, lead: int, go: threading.Event) -> None:
        self.md5, self.frame_bytes, self.lead, self.go = md5, frame_bytes, lead, go
        self.closed_early = 0
        self.sent_whole = 0
        self._server = socket.create_server(("127.0.0.1", 0))
        port = self._server.getsockname()[1]
        self.node = XmlRpcServer(
            "127.0.0.1", 0, {"requestTopic": lambda *a: [1, "", ["TCPROS", "127.0.0.1", port]]}
        )
        self.uri = f"http://127.0.0.1:{self.node.port}/"
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self) -> None:
        with contextlib.suppress(OSError):
            while True:
                sock, _ = self._server.accept()
                threading.Thread(target=self._serve, args=(sock,), daemon=True).start()

    def _serve(self, sock: socket.socket) -> None:
        piece = bytes(1 << 20)
        with sock:
            try:
                read_header(sock)
            except (OSError, TcprosError):
                return  # closed before its header: no frame was refused on it
            try:
                sock.sendall(encode_header({"md5sum": self.md5, "callerid": "/fake"}))
                size = self.frame_bytes  # a String: its byte count, then its bytes
                sock.sendall(struct.pack("<II", size, size - 4) + b"\x00" * self.lead)
                self.go.wait()
                left = size - 4 - self.lead
                while left > 0:
                    sent = sock.send(piece[: min(left, len(piece))])
                    left -= sent
                sock.sendall(struct.pack("<II", 8, 4) + b"done")  # a second, small String
                self.sent_whole += 1
                sock.recv(1)  # until the subscriber goes
            except OSError:
                self.closed_early += 1

    def close(self) -> None:
        self._server.close()
        self.node.close()


def _register(master_uri: str, topic: str, kind: str, fake: _FakePublisher, name: str) -> None:
    proxy = xmlrpc.client.ServerProxy(master_uri)
    assert proxy.registerPublisher(name, topic, kind, fake.uri)[0] == 1


def test_large_frames_are_bounded_per_connection_and_in_total(
    ros1: Ros1, master: Master, tmp_path: Path
) -> None:
    """Finding 9: 200 MB frames from fake publishers cost 200 MiB per connection while read,
    with no bound across connections. Now one 200 MB frame fits the process's budget of
    frames being read (charged twice: the bytes and their copy), the next two are refused
    while it is read, each with one warning, and a Float64 frame larger than 8 bytes is
    refused at once."""
    go = threading.Event()
    big = 200_000_000
    fakes = [_FakePublisher(STRING_MD5, big, 1 << 20, go) for _ in range(3)]
    log = tmp_path / "hz.log"
    for k, fake in enumerate(fakes):
        _register(ros1.uri, "/big", "std_msgs/String", fake, f"/fake{k}")
    proc = ros1.robomodel("topic", "hz", "/big", log=log)
    try:
        ros1.until(lambda: len(_log_lines(log, "closing the connection")) >= 2, "two refusals")
        assert 2 * big <= FRAME_BUDGET_BYTES < 4 * big
        go.set()
        ros1.until(lambda: sum(f.sent_whole for f in fakes) == 1, "one whole frame sent")
        # hz gives a rate once it has two messages: the large one was decoded
        ros1.until(lambda: bool(_log_lines(log, "average rate")), "the two messages received")
        refusals = _log_lines(log, "closing the connection")
        assert len(refusals) == 2 and all("512 MiB budget" in r for r in refusals), refusals
        assert sum(f.closed_early > 0 for f in fakes) == 2
        peak = peak_rss_bytes(proc.pid)
        assert peak < BASE_RSS + FRAME_BUDGET_BYTES + big, peak  # + the decoded string
        api = xmlrpc.client.ServerProxy(_node_api(ros1, "/big", "sub"))
        assert api.getPid("/test")[2] == proc.pid
        _sigterm_ends(proc, log)  # before a second node of the same name replaces it

        tiny = _FakePublisher(FLOAT64_MD5, big, 0, go)
        fakes.append(tiny)
        float_log = tmp_path / "float.log"
        _register(ros1.uri, "/float", "std_msgs/Float64", tiny, "/tiny")
        float_proc = ros1.robomodel("topic", "hz", "/float", log=float_log)
        ros1.until(lambda: bool(_log_lines(float_log, "closing the connection")), "refusal")
        line = _log_lines(float_log, "closing the connection")[0]
        assert f"message of {big} bytes is larger than the 8-byte limit" in line
        assert peak_rss_bytes(float_proc.pid) < BASE_RSS
        api = xmlrpc.client.ServerProxy(_node_api(ros1, "/float", "sub"))
        assert api.getPid("/test")[2] == float_proc.pid
        _sigterm_ends(float_proc, float_log)
    finally:
        go.set()
        for fake in fakes:
            fake.close()


def _stall(port: int, count: int, stop: threading.Event, opened: list[int]) -> None:
    """``count`` connections to ``port`` that send 2 bytes of a header and stall; each one the
    node closes is opened again at once, until ``stop``."""
    selector = selectors.DefaultSelector()

    def open_one() -> None:
        sock = socket.create_connection(("127.0.0.1", port), timeout=scaled(5))
        sock.sendall(b"\x10\x00")
        selector.register(sock, selectors.EVENT_READ)
        opened[0] += 1

    for _ in range(count):
        open_one()
    while not stop.is_set():
        for key, _ in selector.select(0.1):
            selector.unregister(key.fileobj)
            key.fileobj.close()  # type: ignore[union-attr]
            open_one()
    for key in list(selector.get_map().values()):
        key.fileobj.close()  # type: ignore[union-attr]
    selector.close()


def test_stalled_handshakes_do_not_keep_a_real_subscriber_out(
    ros1: Ros1, master: Master, tmp_path: Path
) -> None:
    """Finding 12: 100 connections that send 2 bytes and stall kept a real subscriber out
    (and reopening them kept it out for good). Debian's ``rostopic echo`` gets its message
    while 100 stalled connections, reopened whenever the node drops them, are held open."""
    log = tmp_path / "pub.log"
    proc = ros1.robomodel("topic", "pub", "/chatter", "std_msgs/String", "data: hi", "-r", "5",
                          log=log)  # fmt: skip
    api = xmlrpc.client.ServerProxy(_node_api(ros1, "/chatter", "pub"))
    _, _, (_, _, port) = api.requestTopic("/test", "/chatter", [["TCPROS"]])
    stop, opened = threading.Event(), [0]
    staller = threading.Thread(target=_stall, args=(port, 100, stop, opened), daemon=True)
    staller.start()
    try:
        ros1.until(lambda: opened[0] >= 100, "100 stalled connections")
        echo = ros1.run("/usr/bin/rostopic", "echo", "-n", "1", "/chatter", timeout=scaled(60))
        assert echo.returncode == 0 and 'data: "hi"' in echo.stdout, echo.stderr
        assert thread_count(proc.pid) < 40  # no thread per pending handshake
        ros1.until(lambda: opened[0] > 100, "the node drops a stalled connection")
    finally:
        stop.set()
        staller.join()
    assert MAX_HANDSHAKES > 100
    assert len(_log_lines(log, "dropping a TCPROS connection")) == 1, log.read_text()
    assert api.getPid("/test")[2] == proc.pid
    assert peak_rss_bytes(proc.pid) < BASE_RSS
    _sigterm_ends(proc, log)


def test_29_subscriber_connections_past_the_cap_are_refused_and_rostopic_echo_still_reads(
    ros1: Ros1, master: Master, tmp_path: Path
) -> None:
    """Each subscriber connection holds a writer thread: cap + 3 connections with valid headers
    to a ``robomodel topic pub`` process get 3 error headers and one log line naming the cap,
    the process's threads stay within the cap plus a few, and once the flood closes Debian's
    ``rostopic echo`` gets its message."""
    log = tmp_path / "pub.log"
    proc = ros1.robomodel("topic", "pub", "/chatter", "std_msgs/String", "data: hi", "-r", "5",
                          log=log)  # fmt: skip
    api = xmlrpc.client.ServerProxy(_node_api(ros1, "/chatter", "pub"))
    _, _, (_, _, port) = api.requestTopic("/test", "/chatter", [["TCPROS"]])
    header = encode_header({"callerid": "/flood", "topic": "/chatter", "md5sum": STRING_MD5,
                            "type": "std_msgs/String"})  # fmt: skip
    flood: list[socket.socket] = []
    try:
        refused = []
        for _ in range(MAX_SUBSCRIBER_CONNECTIONS + 3):
            sock = socket.create_connection(("127.0.0.1", port), timeout=scaled(30))
            flood.append(sock)
            sock.sendall(header)
            answer = read_header(sock)
            if "error" in answer:
                refused.append(answer["error"])
        assert len(refused) == 3 and all("limit" in e for e in refused), refused
        threads = thread_count(proc.pid)
        assert threads < MAX_SUBSCRIBER_CONNECTIONS + 40, threads
        # the reply header is written before the connection joins the publication's list
        ros1.until(lambda: len(api.getBusInfo("/test")[2]) == MAX_SUBSCRIBER_CONNECTIONS,
                   "every accepted connection in the bus info")  # fmt: skip
    finally:
        for sock in flood:
            sock.close()
    ros1.until(lambda: not api.getBusInfo("/test")[2], "the flood's slots given back")
    echo = ros1.run("/usr/bin/rostopic", "echo", "-n", "1", "/chatter", timeout=scaled(60))
    assert echo.returncode == 0 and 'data: "hi"' in echo.stdout, echo.stderr
    lines = _log_lines(log, "MAX_SUBSCRIBER_CONNECTIONS")
    assert len(lines) == 1 and f"more than {MAX_SUBSCRIBER_CONNECTIONS}" in lines[0], lines
    assert api.getPid("/test")[2] == proc.pid
    _sigterm_ends(proc, log)


def test_the_frame_budget_is_given_back_whatever_happens() -> None:
    """The budget charged by a frame being read returns to 0 after a decoded frame, a refused
    one and a peer that closes mid-frame; a frame that does not fit is refused before its
    bytes are read."""
    from robomodel.runtime.transport.ros1.tcpros import (
        FrameRefused,
        TcprosError,
        frame_budget_in_use,
        read_frame,
        receive_frame,
    )

    ours, theirs = socket.socketpair()
    with ours, theirs:
        theirs.sendall(struct.pack("<I", 5) + b"hello")
        with receive_frame(ours) as data:
            assert data == b"hello" and frame_budget_in_use() == 10
        assert frame_budget_in_use() == 0
        theirs.sendall(struct.pack("<I", 9) + b"too long!")
        with pytest.raises(FrameRefused, match="larger than the 8-byte limit"):
            read_frame(ours, 8)
        assert frame_budget_in_use() == 0

    big, big_peer = socket.socketpair()
    small, small_peer = socket.socketpair()
    with big, big_peer, small, small_peer:
        half = FRAME_BUDGET_BYTES // 2  # charged twice: the whole budget
        big_peer.sendall(struct.pack("<I", half) + b"x")
        small_peer.sendall(struct.pack("<I", 1) + b"y")
        failed: list[BaseException] = []

        def read_big() -> None:
            try:
                read_frame(big)
            except TcprosError as exc:
                failed.append(exc)

        reader = threading.Thread(target=read_big)
        reader.start()
        while frame_budget_in_use() != FRAME_BUDGET_BYTES and reader.is_alive():
            reader.join(0.01)
        assert frame_budget_in_use() == FRAME_BUDGET_BYTES, failed
        with pytest.raises(FrameRefused, match="does not fit"):
            read_frame(small)  # 1 byte does not fit while the big frame is read
        big_peer.shutdown(socket.SHUT_WR)  # the big frame's peer goes away mid-frame
        reader.join()
        assert "closed by the peer" in str(failed[0])
        assert frame_budget_in_use() == 0


def test_past_the_bound_the_oldest_stalled_handshake_makes_room(
    caplog: pytest.LogCaptureFixture,
) -> None:
    """More stalled connections than handshakes may be in progress: the oldest are dropped
    (one warning), a real header that arrives among them is handed over, and nothing is
    left pending once the server closes."""
    import logging

    from robomodel.runtime.transport.ros1.handshakes import HandshakeServer

    got: list[dict[str, str]] = []
    listener = socket.create_server(("127.0.0.1", 0), backlog=512)
    port = listener.getsockname()[1]
    server = HandshakeServer(listener, lambda sock, header, _: (got.append(header), sock.close()),
                             "/under_test")  # fmt: skip
    stalled: list[socket.socket] = []
    caplog.set_level(logging.DEBUG, logger="robomodel.ros1")
    try:
        for _ in range(MAX_HANDSHAKES + 72):
            sock = socket.create_connection(("127.0.0.1", port), timeout=scaled(5))
            sock.sendall(b"\x10\x00")
            stalled.append(sock)
        with socket.create_connection(("127.0.0.1", port), timeout=scaled(5)) as real:
            real.sendall(encode_header({"callerid": "/real", "topic": "/chatter"}))
            wait_until(lambda: bool(got), 60, what="the real header read", interval_s=0.02)
        assert got == [{"callerid": "/real", "topic": "/chatter"}]
        assert server.in_progress <= MAX_HANDSHAKES
        warnings = [r for r in caplog.records if r.levelno >= logging.WARNING]
        assert len(warnings) == 1 and "dropping a TCPROS connection" in warnings[0].getMessage()
    finally:
        server.close()
        listener.close()
        for sock in stalled:
            sock.close()
    wait_until(
        lambda: server.in_progress == 0, 60, what="no handshake in progress", interval_s=0.02
    )
