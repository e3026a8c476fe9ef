"""A hostile ROS 1 publisher beside a legitimate one, on Debian's roscore: its TCPROS
connection header gives ``evil_msgs/SelfRec``, a type that contains itself. ``robomodel bag
record -a`` records /chatter and skips /evil with one warning line; ``robomodel topic echo
/evil`` is one error line and exit code 2; neither prints a traceback.

The hostile publisher is this test process's: an XML-RPC slave API that answers
``requestTopic`` and a TCPROS server that answers every subscriber with that header, then
sends frames. The legitimate one is Debian's ``rostopic pub -r 10 /chatter``."""

from __future__ import annotations

import contextlib
import socket
import struct
import threading
import xmlrpc.client
import xmlrpc.server
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.ros1wire.conftest import ROSCORE, Ros1
from tests.timing import scaled

pytest.importorskip("rosbags.rosbag2")

# Both tests look at one started hostile graph: one worker starts it once
pytestmark = pytest.mark.xdist_group("hostile_definitions_ros1")

SELF_REC = "int32 a\nSelfRec child\n"


def _header(fields: dict[str, str]) -> bytes:
    """A TCPROS connection header: each ``key=value`` length-prefixed, the whole too."""
    body = b"".join(
        struct.pack("<I", len(item)) + item
        for item in (f"{k}={v}".encode() for k, v in fields.items())
    )
    return struct.pack("<I", len(body)) + body


def _read_exactly(sock: socket.socket, count: int) -> bytes:
    data = b""
    while len(data) < count:
        chunk = sock.recv(count - len(data))
        if not chunk:
            raise ConnectionError("closed")
        data += chunk
    return data


class HostilePublisher:
    """Publishes /evil as ``evil_msgs/SelfRec`` with a definition that nests itself."""

    def __init__(self, master_uri: str) -> None:
        self._stop = threading.Event()
        self._tcp = socket.create_server(("127.0.0.1", 0))
        self._tcp.settimeout(0.2)
        self._api = xmlrpc.server.SimpleXMLRPCServer(
            ("127.0.0.1", 0), logRequests=False, allow_none=True
        )
        self._api.register_function(self._request_topic, "requestTopic")
        self._api.register_function(lambda *_: [1, "", 4242], "getPid")
        self._api.register_function(lambda *_: [1, "", []], "getBusInfo")
        self._api.register_function(lambda *_: [1, "", master_uri], "getMasterUri")
        self._api.register_function(lambda *_: [1, "", 0], "publisherUpdate")
        self.connections = 0
        self._threads = [
            threading.Thread(target=self._api.serve_forever, daemon=True),
            threading.Thread(target=self._accept, daemon=True),
        ]
        for thread in self._threads:
            thread.start()
        api_uri = f"http://127.0.0.1:{self._api.server_address[1]}/"
        code, message, _ = xmlrpc.client.ServerProxy(master_uri).registerPublisher(
            "/evil_pub", "/evil", "evil_msgs/SelfRec", api_uri
        )
        assert code == 1, message

    def _request_topic(self, caller_id: str, topic: str, protocols: list[object]) -> list[object]:
        return [1, "ready on TCPROS", ["TCPROS", "127.0.0.1", self._tcp.getsockname()[1]]]

    def _accept(self) -> None:
        while not self._stop.is_set():
            try:
                conn, _ = self._tcp.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            threading.Thread(target=self._serve, args=(conn,), daemon=True).start()

    def _serve(self, conn: socket.socket) -> None:
        self.connections += 1
        with conn, contextlib.suppress(OSError, ConnectionError):
            conn.settimeout(scaled(10))
            (size,) = struct.unpack("<I", _read_exactly(conn, 4))
            _read_exactly(conn, size)
            conn.sendall(
                _header({
                    "callerid": "/evil_pub",
                    "topic": "/evil",
                    "type": "evil_msgs/SelfRec",
                    "md5sum": "0123456789abcdef0123456789abcdef",
                    "message_definition": SELF_REC,
                    "latching": "0",
                })
            )  # fmt: skip
            while not self._stop.wait(0.1):  # frames that no subscriber should decode
                conn.sendall(struct.pack("<Ii", 4, 7))

    def close(self) -> None:
        self._stop.set()
        self._api.shutdown()
        self._api.server_close()
        self._tcp.close()


@pytest.fixture(scope="module")
def evil_graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Ros1]:
    """One roscore for the module, with /chatter at 10 Hz and the hostile /evil."""
    if not Path(ROSCORE).exists():
        pytest.fail(f"Debian's ROS 1 is missing ({ROSCORE}): tools/system-deps test installs it")
    graph = Ros1(tmp_path_factory.mktemp("evil_graph"))
    hostile = None
    try:
        graph.roscore()
        graph.start(["/usr/bin/rostopic", "pub", "-r", "10", "/chatter", "std_msgs/String",
                     "data: hello"])  # fmt: skip
        hostile = HostilePublisher(graph.uri)
        graph.until(
            lambda: {"/chatter", "/evil"} <= graph.names("topics"),
            "/chatter and /evil",
        )
        yield graph
    finally:
        if hostile is not None:
            hostile.close()
        graph.close()


def _lines(text: str) -> list[str]:
    return [line for line in text.splitlines() if line.strip()]


def test_bag_record_keeps_chatter_and_skips_the_self_recursive_topic(
    evil_graph: Ros1, tmp_path: Path
) -> None:
    from rosbags.rosbag2 import Reader

    folder = tmp_path / "bag"
    # longer on a busy machine, where the recorder starts late into its duration
    rec = evil_graph.robomodel_run(
        "bag", "record", "-a", "-o", str(folder), "--duration", f"{scaled(3):.1f}"
    )
    assert rec.returncode == 0, rec.stderr
    assert "Traceback" not in rec.stderr
    evil = [line for line in _lines(rec.stderr) if "/evil" in line]
    assert len(evil) == 1 and evil[0].startswith("robomodel bag: not recording /evil: "), rec.stderr
    assert "evil_msgs/msg/SelfRec: its definition contains itself" in evil[0]
    with Reader(folder) as reader:
        topics = {conn.topic for conn in reader.connections}
        chatter = [c for c in reader.connections if c.topic == "/chatter"]
        count = sum(1 for _ in reader.messages(connections=chatter))
    assert "/evil" not in topics
    # 30 sent; the first come before the subscription is connected, and the machine is shared
    assert count >= 3, f"{count} /chatter messages in 3 s at 10 Hz"


def test_topic_echo_of_the_self_recursive_topic_is_one_line_and_exit_2(evil_graph: Ros1) -> None:
    echo = evil_graph.robomodel_run("topic", "echo", "/evil", timeout=scaled(60))
    assert echo.returncode == 2, echo.stderr
    # the bus line every verb prints, then the one error line
    lines = [
        line for line in _lines(echo.stderr) if not line.startswith("robomodel topic echo: bus:")
    ]
    assert len(lines) == 1, echo.stderr
    assert lines[0].startswith(
        "robomodel: error: evil_msgs/msg/SelfRec: its definition contains itself"
    )
    assert "Traceback" not in echo.stderr
    # the legitimate topic beside it is still echoed
    chatter = evil_graph.robomodel_run("topic", "echo", "/chatter", "--once")
    assert chatter.returncode == 0 and "hello" in chatter.stdout, chatter.stderr
