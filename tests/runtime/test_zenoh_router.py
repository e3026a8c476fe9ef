"""The router and the session configuration, as rmw_zenoh reads them: the first robomodel
process becomes the router when none answers, ``robomodel router`` is rmw_zenohd, and
``ZENOH_CONFIG_OVERRIDE`` / ``ZENOH_SESSION_CONFIG_URI`` / ``ZENOH_ROUTER_CHECK_ATTEMPTS`` work.

Each test uses a router port of its own (through ZENOH_CONFIG_OVERRIDE), so the run's shared
router on 7447 (tests/conftest.py) takes no part.
"""

from __future__ import annotations

import socket
import subprocess
import time

import pytest

from robomodel.runtime import Context
from robomodel.runtime.msg import String
from robomodel.runtime.transport._zenoh_session import ZenohConfigError, parse_override
from tests.conftest import ROBOMODEL, unique_domain


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _use_router(monkeypatch: pytest.MonkeyPatch, port: int) -> None:
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f'connect/endpoints=["tcp/localhost:{port}"]')


def _exchange(a: Context, b: Context) -> list[str]:
    got: list[str] = []
    b.create_node("listener").create_subscription(String, "/chatter", lambda m: got.append(m.data))
    pub = a.create_node("talker").create_publisher(String, "/chatter")
    deadline = time.monotonic() + 10
    while not got and time.monotonic() < deadline:
        pub.publish(String("hi"))
        b.spin(duration_s=0.1)
    return got


def test_the_first_process_becomes_the_router(monkeypatch: pytest.MonkeyPatch) -> None:
    port = _free_port()
    _use_router(monkeypatch, port)
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as first:
        assert first.transport.is_router  # type: ignore[attr-defined]
        with socket.create_connection(("127.0.0.1", port), timeout=1):
            pass  # it listens on the router's endpoint
        with Context("zenoh", domain_id=domain) as second:
            assert not second.transport.is_router  # type: ignore[attr-defined]
            info = second.transport.session.info  # type: ignore[attr-defined]
            deadline = time.monotonic() + 3.0  # the link may finish after open() on a loaded box
            while not list(info.routers_zid()) and time.monotonic() < deadline:
                time.sleep(0.05)
            assert list(info.routers_zid())
            assert _exchange(second, first) and _exchange(first, second)


def test_peers_keep_talking_when_the_router_process_exits(monkeypatch: pytest.MonkeyPatch) -> None:
    port = _free_port()
    _use_router(monkeypatch, port)
    domain = int(unique_domain())
    router = Context("zenoh", domain_id=domain)
    a = Context("zenoh", domain_id=domain)
    b = Context("zenoh", domain_id=domain)
    try:
        assert _exchange(a, b)
        time.sleep(0.5)  # gossip: a and b link directly
        router.shutdown()
        assert _exchange(a, b)  # still linked without the router
        with Context("zenoh", domain_id=domain) as late:  # the next process takes the port
            assert late.transport.is_router  # type: ignore[attr-defined]
            time.sleep(1.5)  # a and b reconnect to the new router (retry every <= 1 s)
            assert _exchange(late, a)
    finally:
        for ctx in (a, b, router):
            ctx.shutdown()


def test_robomodel_router_serves_peers(monkeypatch: pytest.MonkeyPatch) -> None:
    port = _free_port()
    router = subprocess.Popen(
        [*ROBOMODEL, "router", "--listen", f"tcp/127.0.0.1:{port}"],
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        assert router.stderr is not None and "Started Zenoh router" in router.stderr.readline()
        _use_router(monkeypatch, port)
        domain = int(unique_domain())
        with Context("zenoh", domain_id=domain) as a, Context("zenoh", domain_id=domain) as b:
            assert not a.transport.is_router and not b.transport.is_router  # type: ignore[attr-defined]
            assert _exchange(a, b)
    finally:
        router.terminate()  # SIGTERM: it closes its session and exits 0
        assert router.wait(10) == 0


def test_check_attempts_below_zero_skip_the_router(monkeypatch: pytest.MonkeyPatch) -> None:
    port = _free_port()
    _use_router(monkeypatch, port)
    monkeypatch.setenv("ZENOH_ROUTER_CHECK_ATTEMPTS", "-1")
    with Context("zenoh", domain_id=int(unique_domain())) as ctx:
        assert not ctx.transport.is_router  # type: ignore[attr-defined]
    with socket.socket() as probe:
        assert probe.connect_ex(("127.0.0.1", port)) != 0  # nobody took the router's port


def test_domains_do_not_hear_each_other(monkeypatch: pytest.MonkeyPatch) -> None:
    _use_router(monkeypatch, _free_port())
    with Context("zenoh", domain_id=11) as a, Context("zenoh", domain_id=12) as b:
        got: list[str] = []
        b.create_node("listener").create_subscription(
            String, "/chatter", lambda m: got.append(m.data)
        )
        pub = a.create_node("talker").create_publisher(String, "/chatter")
        for _ in range(10):
            pub.publish(String("hi"))
            b.spin(duration_s=0.05)
        assert not got
        assert "/talker" not in b.graph().nodes and "/talker" in a.graph().nodes


def test_config_override_syntax() -> None:
    assert parse_override('mode="client";connect/endpoints=["tcp/1.2.3.4:7447"]') == [
        ("mode", '"client"'),
        ("connect/endpoints", '["tcp/1.2.3.4:7447"]'),
    ]
    assert parse_override(" ; ") == []
    with pytest.raises(ZenohConfigError, match="is not key=value"):
        parse_override("mode")


def test_bad_configuration_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", "scouting/delay=[not json5")
    with pytest.raises(ZenohConfigError, match="ZENOH_CONFIG_OVERRIDE: cannot set scouting/delay"):
        Context("zenoh")
    monkeypatch.delenv("ZENOH_CONFIG_OVERRIDE")
    monkeypatch.setenv("ZENOH_SESSION_CONFIG_URI", "/nonexistent/session.json5")
    with pytest.raises(
        ZenohConfigError, match=r"ZENOH_SESSION_CONFIG_URI=/nonexistent/session\.json5"
    ):
        Context("zenoh")
    listed = subprocess.run(
        [*ROBOMODEL, "topic", "list"],
        capture_output=True,
        text=True,
        timeout=20,
        env={**__import__("os").environ, "ZENOH_SESSION_CONFIG_URI": "/nonexistent/session.json5"},
    )
    assert listed.returncode == 2 and "Traceback" not in listed.stderr
    assert "not a usable Zenoh configuration" in listed.stderr


def test_humble_keys_have_no_type_hash(monkeypatch: pytest.MonkeyPatch) -> None:
    """Humble has no type hashes: its rmw_zenoh (0.1.x) writes ``TypeHashNotSupported``."""
    _use_router(monkeypatch, _free_port())
    monkeypatch.setenv("ROS_DISTRO", "humble")
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as a, Context("zenoh", domain_id=domain) as b:
        key = a.transport.data_key("/chatter", String)  # type: ignore[attr-defined]
        assert key == f"{domain}/chatter/std_msgs::msg::dds_::String_/TypeHashNotSupported"
        assert _exchange(a, b)
        tokens = [
            str(r.ok.key_expr)
            for r in b.transport.session.liveliness().get(f"@ros2_lv/{domain}/**", timeout=1.0)  # type: ignore[attr-defined]
            if r.ok is not None
            and "/MP/" in str(r.ok.key_expr)
            and "%chatter" in str(r.ok.key_expr)
        ]
        assert tokens and tokens[0].endswith("/TypeHashNotSupported/::,10:,:,:,,")


def test_a_peer_session_whose_close_times_out_still_becomes_the_router() -> None:
    """On a loaded machine the peer session's close() raised "close operation timed out" and
    ``robomodel launch`` ended with a traceback; now the session is left behind and the router
    opens (issue 27's seed runs)."""
    zenoh = pytest.importorskip("zenoh")
    from robomodel.runtime.transport._zenoh_session import _become_router

    class _Stuck:
        closed = False

        def close(self) -> None:
            self.closed = True
            raise zenoh.ZError("close operation timed out!")

    peer = _Stuck()
    endpoint = f"tcp/127.0.0.1:{_free_port()}"
    opened = _become_router(zenoh, peer, zenoh.Config(), endpoint)
    try:
        assert peer.closed and opened.is_router
    finally:
        opened.session.close()
