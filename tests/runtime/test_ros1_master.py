"""robomodel's ROS 1 master against rosmaster's API (rosmaster/master_api.py), and what it does
with malformed or hostile XML-RPC and TCPROS input: a log line, an error answer, and it goes on."""

from __future__ import annotations

import contextlib
import socket
import struct
import threading
import time
import xmlrpc.client
from collections.abc import Iterator
from typing import Any

import pytest

from robomodel.runtime.transport.ros1.master import Master
from robomodel.runtime.transport.ros1.names import (
    canonical,
    master_bind_host,
    namespace_of,
    resolve,
)
from robomodel.runtime.transport.ros1.tcpros import (
    MAX_HEADER_BYTES,
    TcprosError,
    encode_header,
    parse_header,
)
from robomodel.runtime.transport.ros1.xmlrpc_io import MAX_BODY_BYTES, XmlRpcServer
from tests.ros1wire.conftest import free_port
from tests.timing import scaled, wait_until


@pytest.fixture
def master() -> Iterator[tuple[Master, Any]]:
    uri = f"http://127.0.0.1:{free_port()}/"
    m = Master(uri, "127.0.0.1")
    try:
        yield m, xmlrpc.client.ServerProxy(uri)
    finally:
        m.close()


def test_names_resolve_as_rosgraph_does() -> None:
    assert resolve("chatter", "/ns/node") == "/ns/chatter"
    assert resolve("~private", "/ns/node") == "/ns/node/private"
    assert resolve("/abs//x/", "/ns/node") == "/abs/x"
    assert namespace_of("/a/b") == "/a/" and namespace_of("/a") == "/"
    assert canonical("//a///b/") == "/a/b"


@pytest.mark.parametrize(
    ("ros_ip", "uri", "expected"),
    [
        ("10.1.2.3", "http://[2001:db8::5]:11311/", "::"),  # "::" takes IPv4 peers too
        ("10.1.2.3", "http://[::1]:11311/", "::"),
        ("10.1.2.3", "http://127.0.0.1:11311/", "0.0.0.0"),
        ("2001:db8::7", "http://127.0.0.1:11311/", "::"),
        ("2001:db8::7", "http://[2001:db8::5]:11311/", "::"),
    ],
)
def test_a_master_with_an_address_others_use_binds_every_interface_of_its_uri_s_family(
    ros_ip: str, uri: str, expected: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A non-loopback ``ROS_IP`` binds every interface, as roscpp does; a master whose URI is
    IPv6 must bind "::" (on "0.0.0.0" the peers that ROS_MASTER_URI sends there are refused)."""
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    monkeypatch.setenv("ROS_IP", ros_ip)
    assert master_bind_host(uri) == expected


def test_registrations_lookups_and_system_state(master: tuple[Master, Any]) -> None:
    _, proxy = master
    code, _, subs = proxy.registerPublisher("/talker", "chatter", "std_msgs/String", "http://h:1/")
    assert code == 1 and subs == []
    code, _, pubs = proxy.registerSubscriber(
        "/ns/listener", "/chatter", "std_msgs/String", "http://h:2/"
    )
    assert code == 1 and pubs == ["http://h:1/"]
    assert proxy.lookupNode("/x", "/talker") == [
        1,
        "node api",
        "http://h:1/",
    ]  # rosmaster's message
    assert proxy.lookupNode("/x", "/nobody")[0] == -1
    assert proxy.registerService("/talker", "/srv", "rosrpc://h:3", "http://h:1/")[0] == 1
    assert proxy.lookupService("/x", "/srv")[2] == "rosrpc://h:3"
    assert proxy.lookupService("/x", "/other")[:2] == [-1, "no provider"]
    _, _, (publishers, subscribers, services) = proxy.getSystemState("/x")
    assert publishers == [["/chatter", ["/talker"]]]
    assert subscribers == [["/chatter", ["/ns/listener"]]]
    assert services == [["/srv", ["/talker"]]]
    assert proxy.getPublishedTopics("/x", "")[2] == [["/chatter", "std_msgs/String"]]
    assert proxy.getPublishedTopics("/x", "/")[2] == [["/chatter", "std_msgs/String"]]  # rosnode
    assert proxy.getTopicTypes("/x")[2] == [["/chatter", "std_msgs/String"]]
    assert proxy.unregisterPublisher("/talker", "/chatter", "http://h:1/")[2] == 1
    assert proxy.unregisterPublisher("/talker", "/chatter", "http://h:1/")[2] == 0
    assert proxy.getPublishedTopics("/x", "")[2] == []


def test_parameters_as_rosmaster_stores_and_searches_them(master: tuple[Master, Any]) -> None:
    _, proxy = master
    assert proxy.setParam("/ns/node", "gains", {"p": 1.5, "i": [1, 2]})[0] == 1
    assert proxy.getParam("/x", "/ns/gains") == [
        1,
        "Parameter [/ns/gains]",
        {"p": 1.5, "i": [1, 2]},
    ]
    assert proxy.getParam("/ns/node", "~missing")[0] == -1
    assert proxy.hasParam("/x", "/ns/gains/p")[2] is True
    assert sorted(proxy.getParamNames("/x")[2]) == ["/ns/gains/i", "/ns/gains/p"]
    assert proxy.searchParam("/ns/deeper/node", "gains")[2] == "/ns/gains"
    assert proxy.searchParam("/other/node", "gains")[0] == -1
    assert proxy.setParam("/x", "/ns/gains", 3)[0] == 1  # a value replaces the namespace
    assert proxy.getParamNames("/x")[2] == ["/ns/gains"]
    assert proxy.setParam("/x", "/", 5)[0] == -1  # the root stays a dictionary
    assert proxy.deleteParam("/x", "/ns")[0] == 1 and proxy.getParamNames("/x")[2] == []
    assert proxy.setParam("/x", "/blob", xmlrpc.client.Binary(b"\x00\x01"))[0] == 1
    assert proxy.getParam("/x", "/blob")[2] == xmlrpc.client.Binary(b"\x00\x01")


def test_param_subscribers_get_param_update(master: tuple[Master, Any]) -> None:
    updates: list[tuple[str, str, Any]] = []
    node = XmlRpcServer("127.0.0.1", 0, {"paramUpdate": lambda *a: updates.append(a) or [1, "", 0]})
    api = f"http://127.0.0.1:{node.port}/"
    _, proxy = master
    try:
        assert proxy.subscribeParam("/node", api, "/robot")[2] == {}
        proxy.setParam("/other", "/robot/x", 1)
        proxy.setParam("/node", "/robot/y", 2)  # the changing node itself is not told
        proxy.deleteParam("/other", "/robot")
        deadline = time.monotonic() + scaled(5)
        while len(updates) < 2 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert updates[0] == ("/master", "/robot/", {"x": 1})
        assert updates[-1] == ("/master", "/robot/", {})
    finally:
        node.close()


def test_param_subscribers_below_a_namespace_set_to_a_dict_get_their_value(
    master: tuple[Master, Any],
) -> None:
    """Setting ``/robot`` to a dict tells the subscribers of keys inside it their new value,
    and those of keys it no longer holds ``{}`` (rosmaster's compute_param_updates: the
    "exact matches within tree" and "parameter was deleted" cases)."""
    updates: list[tuple[str, str, Any]] = []
    node = XmlRpcServer("127.0.0.1", 0, {"paramUpdate": lambda *a: updates.append(a) or [1, "", 0]})
    api = f"http://127.0.0.1:{node.port}/"
    _, proxy = master
    try:
        proxy.setParam("/other", "/robot/gone", 3)
        for key in ("/robot/arm/gain", "/robot/gone", "/elsewhere"):
            proxy.subscribeParam("/node", api, key)
        proxy.setParam("/other", "/robot", {"arm": {"gain": 2.5}, "name": "r2"})
        proxy.setParam("/other", "/elsewhere", 1)  # one worker sends in order: this comes last
        deadline = time.monotonic() + scaled(5)
        while ("/master", "/elsewhere/", 1) not in updates and time.monotonic() < deadline:
            time.sleep(0.05)
        assert updates[-1] == ("/master", "/elsewhere/", 1)
        assert sorted(updates[:-1]) == [
            ("/master", "/robot/arm/gain/", 2.5),
            ("/master", "/robot/gone/", {}),
        ]
    finally:
        node.close()


def _post(port: int, body: bytes, length: int | None = None) -> bytes:
    with socket.create_connection(("127.0.0.1", port), timeout=scaled(5)) as sock:
        head = (
            f"POST / HTTP/1.0\r\nContent-Length: {len(body) if length is None else length}\r\n\r\n"
        )
        sock.sendall(head.encode() + body)
        chunks = b""
        while chunk := sock.recv(65536):
            chunks += chunk
        return chunks


def test_malformed_and_hostile_xmlrpc_get_an_error_and_the_master_goes_on(
    master: tuple[Master, Any],
) -> None:
    m, proxy = master
    port = int(m.uri.rsplit(":", 1)[1].strip("/"))
    assert b"parse error" in _post(port, b"<methodCall><methodName>getPid")
    bomb = (
        b'<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "aaaaaaaaaa">'
        + b"".join(
            b'<!ENTITY %c "&%c;&%c;&%c;&%c;&%c;&%c;&%c;&%c;&%c;&%c;">' % ((c,) + (c - 1,) * 10)
            for c in range(98, 108)
        )
        + b"]><methodCall><methodName>getParam</methodName><params><param><value>&k;</value></param></params></methodCall>"
    )
    started = time.monotonic()
    assert b"parse error" in _post(port, bomb)
    assert time.monotonic() - started < 5
    assert b"413" in _post(port, b"", length=MAX_BODY_BYTES + 1)
    assert b"not supported" in _post(port, xmlrpc.client.dumps(("/x",), "noSuchMethod").encode())
    assert b"bad call arity" in _post(port, xmlrpc.client.dumps(("/x", 1, 2, 3), "getPid").encode())
    assert proxy.getPid("/x")[0] == 1  # still serving


def test_tcpros_headers_are_parsed_within_bounds() -> None:
    fields = {"callerid": "/n", "topic": "/t", "md5sum": "*", "message_definition": "a=b\nc"}
    encoded = encode_header(fields)
    assert struct.unpack("<I", encoded[:4])[0] == len(encoded) - 4
    assert parse_header(encoded[4:]) == fields
    with pytest.raises(TcprosError, match="overruns"):
        parse_header(struct.pack("<I", 1000) + b"topic=/t")
    with pytest.raises(TcprosError, match="no '='"):
        parse_header(struct.pack("<I", 5) + b"topic")
    assert MAX_HEADER_BYTES <= 1 << 20


def test_nodes_drop_hostile_tcpros_peers_and_go_on(master: tuple[Master, Any]) -> None:
    """Garbage, an oversized header and a wrong md5sum on a node's TCPROS port, and a
    publisher that sends a malformed message: each ends its connection; messages still flow."""
    from robomodel.runtime import Context
    from robomodel.runtime.msg import get_message_type

    m, proxy = master
    string = get_message_type("std_msgs/msg/String")
    with Context("ros1", master=m.uri) as talker, Context("ros1", master=m.uri) as listener:
        pub = talker.create_node("talker").create_publisher(string, "/chatter", 10)
        got: list[str] = []
        listener.create_node("listener").create_subscription(
            string, "/chatter", lambda msg: got.append(msg.data), 10
        )
        api = proxy.lookupNode("/x", "/talker")[2]
        _, _, (_, host, port) = xmlrpc.client.ServerProxy(api).requestTopic(
            "/x", "/chatter", [["TCPROS"]]
        )
        for attack in (
            b"\x00" * 3,
            struct.pack("<I", 1 << 30) + b"topic=/chatter",
            encode_header({"callerid": "/evil", "topic": "/chatter", "md5sum": "0" * 32}),
        ):
            with socket.create_connection((host, port), timeout=scaled(5)) as sock:
                try:
                    sock.sendall(attack)
                    sock.shutdown(socket.SHUT_WR)
                    reply = sock.recv(4096)
                except OSError:  # the node already closed it (reset, or not connected any more)
                    reply = b""
                assert reply == b"" or b"error=" in reply

        def heard(text: str) -> bool:
            pub.publish(string(text))
            listener.spin_once(0.05)
            return text in got

        wait_until(lambda: heard("hello"), 10, what="'hello' heard")
        evil, dropped = _evil_publisher(proxy)  # a second publisher: its message does not decode
        try:
            assert dropped.wait(scaled(30)), "the listener did not drop the garbage publisher"
            got.clear()
            wait_until(lambda: heard("still"), 10, what="'still' heard")
            assert all(text in ("hello", "still") for text in got)
        finally:
            evil.close()


def _evil_publisher(proxy: Any) -> tuple[XmlRpcServer, threading.Event]:
    """A fake node that publishes /chatter: its header is right, its message is garbage; the
    event is set when the subscriber has closed that connection (it read the garbage)."""
    from robomodel.runtime.msg import get_message_type
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    kind = ros1_type(get_message_type("std_msgs/msg/String"))
    server = socket.create_server(("127.0.0.1", 0))
    tcp_port = server.getsockname()[1]

    def serve() -> None:
        with server:
            sock, _ = server.accept()
            with sock:
                sock.recv(65536)
                sock.sendall(
                    encode_header({"md5sum": kind.md5sum, "type": kind.name, "callerid": "/evil"})
                )
                sock.sendall(struct.pack("<I", 8) + struct.pack("<I", 1 << 31) + b"abcd")
                sock.settimeout(scaled(30))
                with contextlib.suppress(OSError):
                    while sock.recv(4096):
                        pass
                dropped.set()

    dropped = threading.Event()
    threading.Thread(target=serve, daemon=True).start()
    node = XmlRpcServer(
        "127.0.0.1", 0, {"requestTopic": lambda *a: [1, "", ["TCPROS", "127.0.0.1", tcp_port]]}
    )
    proxy.registerPublisher("/evil", "/chatter", kind.name, f"http://127.0.0.1:{node.port}/")
    return node, dropped


def test_unregistering_forgets_a_node_as_rosmaster_does(master: tuple[Master, Any]) -> None:
    """rosmaster/registrations.py: unregister* removes exactly the registration named (a
    service by its rosrpc URI), a node is forgotten with its last registration, and rospy's
    system.multicall of unregister calls (how a rospy node ends) is served."""
    _, proxy = master
    api, other = "http://h:1/", "http://h:2/"
    proxy.registerPublisher("/pub", "/foo", "std_msgs/String", api)
    proxy.registerSubscriber("/pub", "/bar", "std_msgs/String", api)
    proxy.registerService("/pub", "/pub/get_loggers", "rosrpc://h:3", api)
    assert proxy.unregisterPublisher("/pub", "/foo", other)[2] == 0  # not its API: kept
    assert proxy.unregisterService("/pub", "/pub/get_loggers", "rosrpc://h:4")[2] == 0
    multi = xmlrpc.client.MultiCall(proxy)
    multi.unregisterPublisher("/pub", "/foo", api)
    multi.unregisterSubscriber("/pub", "/bar", api)
    multi.noSuchMethod("/pub")
    answers = multi()
    assert [answers[0][2], answers[1][2]] == [1, 1]
    with pytest.raises(xmlrpc.client.Fault, match="not supported"):
        answers[2]
    assert proxy.lookupNode("/x", "/pub")[0] == 1  # it still offers a service
    assert proxy.unregisterService("/pub", "/pub/get_loggers", "rosrpc://h:3")[2] == 1
    assert proxy.lookupNode("/x", "/pub")[:2] == [-1, "unknown node [/pub]"]
    assert proxy.getSystemState("/x")[2] == [[], [], []]
    # a new node of the same name replaces the old: the old registrations go
    proxy.registerPublisher("/pub", "/foo", "std_msgs/String", api)
    proxy.registerSubscriber("/pub", "/baz", "std_msgs/String", other)
    assert proxy.getSystemState("/x")[2] == [[], [["/baz", ["/pub"]]], []]
    assert proxy.lookupNode("/x", "/pub")[2] == other
