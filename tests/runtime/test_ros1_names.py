"""ROS 1 names and URIs in-process: rosgraph.names' resolution (the values below are what
rosgraph 1.16 answers), the URIs a node writes and reads, and the addresses it binds for the
host it is reached at (name resolution replaced, so the answers do not depend on the machine)."""

from __future__ import annotations

import socket
from typing import Any

import pytest

from robomodel.errors import RobomodelError
from robomodel.runtime.transport.ros1 import names
from robomodel.runtime.transport.ros1.names import (
    DEFAULT_MASTER_URI,
    MAX_NAME_BYTES,
    Ros1NameError,
    advertised_host,
    bind_host,
    canonical,
    check_name,
    check_uri,
    http_uri,
    is_loopback,
    listen_host,
    master_bind_host,
    master_uri,
    namespace_of,
    resolve,
    split_uri,
)


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("/wg/node1", "/wg/"),
        ("/a/b/", "/a/"),
        ("/a", "/"),
        ("/", "/"),
        ("", "/"),
        ("a/b", "a/"),
        ("a", "/"),  # a relative name without a slash is in the global namespace
    ],
)
def test_namespace_of_is_rosgraph_s_namespace(name: str, expected: str) -> None:
    assert namespace_of(name) == expected


@pytest.mark.parametrize(
    ("name", "caller_id", "expected"),
    [
        ("a", "/ns/node", "/ns/a"),
        ("~p", "/ns/node", "/ns/node/p"),
        ("~", "/ns/node", "/ns/node"),
        ("", "/ns/node", "/ns/"),
        ("/x/", "/n", "/x"),
        ("a/b", "/node", "/a/b"),
        ("b", "/ns/node/", "/ns/b"),
        ("chatter", "node", "/chatter"),  # a relative caller id is in the global namespace
    ],
)
def test_resolve_is_rosgraph_s_resolve_name(name: str, caller_id: str, expected: str) -> None:
    assert resolve(name, caller_id) == expected


def test_canonical_keeps_the_root_and_the_empty_name() -> None:
    assert canonical("/") == "/" and canonical("") == ""
    assert canonical("a//b/") == "a/b" and canonical("//a") == "/a"


def test_check_name_takes_rosmaster_s_names_and_says_what_is_wrong() -> None:
    assert check_name("/rosparam-1234", "caller_id") == "/rosparam-1234"
    assert check_name("x" * MAX_NAME_BYTES, "topic") == "x" * MAX_NAME_BYTES
    with pytest.raises(Ros1NameError, match=r"^topic must be a non-empty string$"):
        check_name("", "topic")
    with pytest.raises(Ros1NameError, match=r"^topic must be a non-empty string$"):
        check_name(7, "topic")
    with pytest.raises(Ros1NameError, match=rf"^topic is {MAX_NAME_BYTES + 1} characters; "):
        check_name("x" * (MAX_NAME_BYTES + 1), "topic")
    for bad in ("/a:b", "/a b", "/a\tb", "/a\x00", "/a\x7f", "/a\x9f"):
        with pytest.raises(Ros1NameError, match=r"^node '/a.*' is not a ROS name"):
            check_name(bad, "node")
    with pytest.raises(Ros1NameError) as info:  # a long name is shown by its first 80
        check_name("/" + "n" * 99 + ":", "node")
    assert str(info.value) == (
        f"node {'/' + 'n' * 79!r} is not a ROS name (no ':', whitespace or control characters)"
    )


def test_check_uri_takes_http_and_rosrpc_with_a_port() -> None:
    assert check_uri("http://h:1/", "caller_api") == "http://h:1/"
    assert check_uri("rosrpc://h:2", "service_api") == "rosrpc://h:2"
    with pytest.raises(Ros1NameError, match=r"^caller_api must be a URI of at most 1024 "):
        check_uri(None, "caller_api")
    with pytest.raises(Ros1NameError, match=r"^caller_api must be a URI of at most 1024 "):
        check_uri("http://h:1/" + "x" * MAX_NAME_BYTES, "caller_api")
    for bad in ("ftp://h:1/", "http://h/", "http://:1/"):
        with pytest.raises(Ros1NameError, match=rf"^caller_api '{bad}' is not an http://"):
            check_uri(bad, "caller_api")
    longest = "http://h:1/" + "p" * (MAX_NAME_BYTES - 11)
    assert check_uri(longest, "caller_api") == longest
    with pytest.raises(Ros1NameError) as info:
        check_uri("ftp://" + "h" * 100, "caller_api")
    assert (
        str(info.value)
        == f"caller_api {('ftp://' + 'h' * 100)[:80]!r} is not an http:// or rosrpc:// URI"
    )


def test_split_uri_reads_bracketed_and_rospy_s_bare_ipv6() -> None:
    assert split_uri("http://host:11311/") == ("host", 11311)
    assert split_uri("rosrpc://10.0.0.1:4000") == ("10.0.0.1", 4000)
    assert split_uri("http://[::1]:11311/") == ("::1", 11311)
    assert split_uri("http://::1:11311/") == ("::1", 11311)  # rospy with ROS_IP=::1
    assert split_uri("http://fe80::1:2:80/x") == ("fe80::1:2", 80)
    assert split_uri("http://::1:11311/a/b:c/d") == ("::1", 11311)
    for bad in (
        "http://::1:port/", "http://host:99999/", "gopher://h:1/", "http://h/",
        "http://[::1]:99999/", "http://a:b:c/",
    ):  # fmt: skip
        with pytest.raises(RobomodelError, match="is not a ROS 1 URI; use http://HOST:PORT/"):
            split_uri(bad)
    with pytest.raises(RobomodelError) as info:
        split_uri("http://" + "h" * 300)
    assert str(info.value) == (
        f"'http://{'h' * 193}' is not a ROS 1 URI; use http://HOST:PORT/ (ROS_MASTER_URI), "
        "http://[IPV6]:PORT/ or rosrpc://HOST:PORT"
    )


def test_http_uri_brackets_ipv6_and_ends_http_with_a_slash() -> None:
    assert http_uri("10.0.0.1", 11311) == "http://10.0.0.1:11311/"
    assert http_uri("::1", 4000) == "http://[::1]:4000/"
    assert http_uri("h", 5, "rosrpc") == "rosrpc://h:5"
    assert http_uri("::1", 5, "rosrpc") == "rosrpc://[::1]:5"
    for host, port in (("::1", 4000), ("10.0.0.1", 1), ("name", 2)):
        assert split_uri(http_uri(host, port)) == (host, port)


def test_master_uri_is_explicit_then_the_environment_then_the_default(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.delenv("ROS_MASTER_URI", raising=False)
    assert master_uri() == DEFAULT_MASTER_URI == "http://localhost:11311/"
    monkeypatch.setenv("ROS_MASTER_URI", "http://robot:11312/")
    assert master_uri() == "http://robot:11312/"
    assert master_uri("http://other:1/") == "http://other:1/"
    monkeypatch.setenv("ROS_MASTER_URI", "robot:11311")
    with pytest.raises(RobomodelError, match="'robot:11311' is not a ROS 1 URI"):
        master_uri()


def test_advertised_host_is_ros_ip_then_ros_hostname_then_loopback(
    monkeypatch: pytest.MonkeyPatch, resolver: dict[str, list[str]]
) -> None:
    resolver.update({"robot.local": ["10.0.0.9"], "localhost": ["127.0.0.1"]})
    monkeypatch.delenv("ROS_IP", raising=False)
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    assert advertised_host() == "127.0.0.1" and bind_host() == "127.0.0.1"
    monkeypatch.setenv("ROS_HOSTNAME", "localhost")
    assert advertised_host() == "localhost" and bind_host() == "127.0.0.1"
    monkeypatch.setenv("ROS_HOSTNAME", "robot.local")
    assert advertised_host() == "robot.local" and bind_host() == "0.0.0.0"
    monkeypatch.setenv("ROS_IP", "10.0.0.7")
    assert advertised_host() == "10.0.0.7" and bind_host() == "0.0.0.0"


@pytest.fixture
def resolver(monkeypatch: pytest.MonkeyPatch) -> dict[str, list[str]]:
    """Host names resolve to what this dict says; others do not resolve."""
    table: dict[str, list[str]] = {}

    def getaddrinfo(host: str, port: Any) -> list[tuple[Any, ...]]:
        if host not in table:
            raise socket.gaierror(socket.EAI_NONAME, "Name or service not known")
        return [(0, 0, 0, "", (a, 0)) for a in table[host] for _ in range(2)]

    monkeypatch.setattr(names.socket, "getaddrinfo", getaddrinfo)
    return table


def test_loopback_is_judged_by_every_address_a_host_has(resolver: dict[str, list[str]]) -> None:
    resolver.update(
        {
            "localhost": ["127.0.0.1", "::1"],
            "lo6": ["::1"],
            "scoped": ["fe80::1%eth0"],
            "mixed": ["127.0.0.1", "10.0.0.1"],
            "robot": ["10.0.0.9"],
        }
    )
    assert is_loopback("127.0.0.1") and is_loopback("127.3.2.1") and is_loopback("::1")
    assert is_loopback("[::1]") and is_loopback("localhost") and is_loopback("lo6")
    assert not is_loopback("10.0.0.1") and not is_loopback("mixed") and not is_loopback("robot")
    assert not is_loopback("scoped")
    # loopback names that do not resolve here are still loopback; other names are not
    assert is_loopback("ip6-localhost") and is_loopback("IP6-Loopback")
    assert not is_loopback("nowhere")


def test_a_name_that_fails_to_encode_resolves_to_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    def getaddrinfo(host: str, port: Any) -> list[tuple[Any, ...]]:
        raise UnicodeError("label too long")

    monkeypatch.setattr(names.socket, "getaddrinfo", getaddrinfo)
    assert not is_loopback("x" * 70 + ".example")
    assert listen_host("x" * 70 + ".example") == "0.0.0.0"


def test_listen_host_is_the_loopback_address_or_every_interface_of_the_family(
    resolver: dict[str, list[str]],
) -> None:
    resolver.update(
        {
            "localhost": ["::1", "127.0.0.1"],
            "lo6": ["::1"],
            "robot": ["10.0.0.9"],
            "robot6": ["2001:db8::9"],
            "both": ["2001:db8::9", "10.0.0.9"],
        }
    )
    assert listen_host("127.0.0.2") == "127.0.0.2"
    assert listen_host("::1") == "::1" and listen_host("[::1]") == "::1"
    assert listen_host("localhost") == "127.0.0.1"  # IPv4 preferred
    assert listen_host("lo6") == "::1"
    assert listen_host("ip6-localhost") == "::1"  # does not resolve here
    assert listen_host("LOCALHOST") == "127.0.0.1"
    assert listen_host("10.0.0.1") == "0.0.0.0" and listen_host("robot") == "0.0.0.0"
    assert listen_host("2001:db8::1") == "::" and listen_host("robot6") == "::"
    assert listen_host("both") == "0.0.0.0"
    assert listen_host("nowhere") == "0.0.0.0"


@pytest.mark.parametrize(
    ("ros_ip", "uri", "expected"),
    [
        (None, "http://localhost:11311/", "127.0.0.1"),
        (None, "http://[::1]:11311/", "::1"),
        (None, "http://10.0.0.5:11311/", "0.0.0.0"),
        ("127.0.0.2", "http://localhost:11311/", "127.0.0.1"),
        ("127.0.0.2", "http://127.0.0.3:11311/", "127.0.0.3"),
    ],
)
def test_a_master_binds_where_its_uri_points_unless_ros_ip_is_used_by_others(
    ros_ip: str | None,
    uri: str,
    expected: str,
    monkeypatch: pytest.MonkeyPatch,
    resolver: dict[str, list[str]],
) -> None:
    resolver["localhost"] = ["127.0.0.1", "::1"]
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    if ros_ip is None:
        monkeypatch.delenv("ROS_IP", raising=False)
    else:
        monkeypatch.setenv("ROS_IP", ros_ip)
    assert master_bind_host(uri) == expected
