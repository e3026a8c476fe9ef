"""The router and the session configuration, as rmw_zenoh reads them: a robomodel process
starts a detached router when none answers, which outlives it; ``robomodel router`` is
rmw_zenohd, and
``ZENOH_CONFIG_OVERRIDE`` / ``ZENOH_SESSION_CONFIG_URI`` / ``ZENOH_ROUTER_CHECK_ATTEMPTS`` work.

Each test uses a router port of its own (through ZENOH_CONFIG_OVERRIDE), so the run's shared
router on 7447 (tests/conftest.py) takes no part.
"""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from robomodel.runtime import Context
from robomodel.runtime.msg import String
from robomodel.runtime.transport._zenoh_router import (
    check_attempts,
    listening,
    read_record,
    stop_router,
)
from robomodel.runtime.transport._zenoh_session import ZenohConfigError, parse_override
from robomodel.runtime.transport.rmw_zenoh import EntityKind
from tests.conftest import ROBOMODEL, free_port, unique_domain
from tests.timing import scaled, wait_until


def _use_router(monkeypatch: pytest.MonkeyPatch, port: int) -> None:
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f'connect/endpoints=["tcp/localhost:{port}"]')


def _exchange(a: Context, b: Context) -> list[str]:
    got: list[str] = []
    b.create_node("listener").create_subscription(String, "/chatter", lambda m: got.append(m.data))
    pub = a.create_node("talker").create_publisher(String, "/chatter")
    deadline = time.monotonic() + scaled(10)
    while not got and time.monotonic() < deadline:
        pub.publish(String("hi"))
        b.spin(duration_s=0.1)
    return got


def _wait_linked(a: Context, b: Context, kind: str) -> None:
    """Until ``a``'s session lists ``b``'s among its ``kind`` (peers or routers)."""
    info = a.transport.session.info  # type: ignore[attr-defined]
    zid = str(b.transport.session.zid())  # type: ignore[attr-defined]
    listed = info.peers_zid if kind == "peers" else info.routers_zid
    wait_until(
        lambda: zid in {str(z) for z in listed()},
        10,
        what=lambda: f"{zid} among the {kind} of {info.zid()}",
        interval_s=0.02,
    )


@pytest.fixture
def private_router(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Iterator[str]:
    """A router endpoint of this test's own; the router a session starts there is stopped at
    teardown (it would outlive the test otherwise, as it outlives a session)."""
    endpoint = f"tcp/localhost:{free_port()}"
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(tmp_path))  # its record and log
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f'connect/endpoints=["{endpoint}"]')
    yield endpoint
    record = stop_router(endpoint)
    if record is not None:
        with contextlib.suppress(ChildProcessError):
            os.waitpid(record.pid, 0)  # started by this process: reap it


def _router_of(ctx: Context) -> list[str]:
    info = ctx.transport.session.info  # type: ignore[attr-defined]
    deadline = time.monotonic() + scaled(10.0)
    while not list(info.routers_zid()) and time.monotonic() < deadline:
        time.sleep(0.02)
    return [str(z) for z in info.routers_zid()]


def test_a_session_starts_a_router_that_outlives_it(private_router: str) -> None:
    """Start a session, exit it, start another: the same router (pid and Zenoh id)
    serves both; ``robomodel router --stop`` ends it."""
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as first:
        assert not first.transport.is_router  # type: ignore[attr-defined]
        record = read_record(private_router)
        assert record is not None and _router_of(first) == [record.zid]
    assert read_record(private_router) == record  # the session is gone, the router is not
    with Context("zenoh", domain_id=domain) as second, Context("zenoh", domain_id=domain) as third:
        assert _router_of(second) == [record.zid] and _router_of(third) == [record.zid]
        assert _exchange(second, third)
    stopped = subprocess.run(
        [*ROBOMODEL, "router", "--stop", "--listen", private_router],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert stopped.returncode == 0
    assert f"stopped the Zenoh router {record.zid} (pid {record.pid})" in stopped.stderr
    assert read_record(private_router) is None and not listening(private_router)
    again = subprocess.run(
        [*ROBOMODEL, "router", "--stop", "--listen", private_router],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert again.returncode == 0 and "no robomodel router is running" in again.stderr


def test_peers_keep_talking_when_the_router_stops(private_router: str) -> None:
    domain = int(unique_domain())
    a = Context("zenoh", domain_id=domain)
    b = Context("zenoh", domain_id=domain)
    try:
        assert _exchange(a, b)
        _wait_linked(a, b, "peers")  # gossip: a and b link directly
        old = stop_router(private_router)
        assert old is not None
        assert _exchange(a, b)  # still linked without the router
        with Context("zenoh", domain_id=domain) as late:  # starts the next router
            new = read_record(private_router)
            assert new is not None and new.pid != old.pid
            assert _router_of(a) == [new.zid]  # a reconnects (retry every <= 1 s)
            assert _exchange(late, a)
    finally:
        for ctx in (a, b):
            ctx.shutdown()


def test_the_router_ends_when_no_session_uses_it() -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    router = subprocess.Popen(
        [*ROBOMODEL, "router", "--listen", endpoint, "--idle-exit", "1"],
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        assert router.stderr is not None and "Started Zenoh router" in router.stderr.readline()
        with pytest.MonkeyPatch.context() as env:
            env.setenv("ZENOH_CONFIG_OVERRIDE", f'connect/endpoints=["{endpoint}"]')
            with Context("zenoh", domain_id=int(unique_domain())) as ctx:
                assert _router_of(ctx)
                ctx.spin(duration_s=2.5)  # linked for longer than --idle-exit: it stays
                assert router.poll() is None
        assert router.wait(scaled(30)) == 0
        assert "no session for 1 s; stopping" in router.stderr.read()
    finally:
        router.kill()
        router.wait()


@pytest.mark.parametrize(
    ("text", "attempts"),
    [(None, 1), ("", 1), ("3", 3), ("0", 0), ("abc", 0), (" 2x", 2), ("-1", None)],
)
def test_check_attempts_are_read_as_rmw_zenoh_reads_them(
    monkeypatch: pytest.MonkeyPatch, text: str | None, attempts: int | None
) -> None:
    """zenoh_config.cpp ``zenoh_router_check_attempts``: unset is 1, strtoll of the text
    otherwise (so "abc" is 0: for ever), below zero is None (no check)."""
    if text is None:
        monkeypatch.delenv("ZENOH_ROUTER_CHECK_ATTEMPTS", raising=False)
    else:
        monkeypatch.setenv("ZENOH_ROUTER_CHECK_ATTEMPTS", text)
    assert check_attempts() == attempts


def test_check_attempts_zero_waits_for_a_router() -> None:
    """0: the process waits for a router (and starts none of its own) until one comes."""
    endpoint = f"tcp/localhost:{free_port()}"
    env = {**os.environ, "ZENOH_ROUTER_CHECK_ATTEMPTS": "0",
           "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["{endpoint}"]'}  # fmt: skip
    waiting = subprocess.Popen(
        [*ROBOMODEL, "topic", "list", "--domain-id", unique_domain()],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
    )  # fmt: skip
    router = None
    try:
        assert waiting.stderr is not None and "waiting for one" in waiting.stderr.readline()
        assert waiting.poll() is None and not listening(endpoint)
        router = subprocess.Popen(
            [*ROBOMODEL, "router", "--listen", endpoint], stderr=subprocess.DEVNULL
        )
        assert waiting.wait(scaled(60)) == 0
    finally:
        waiting.kill()
        waiting.wait()
        if router is not None:
            router.terminate()
            router.wait(scaled(10))


def test_robomodel_router_serves_peers(monkeypatch: pytest.MonkeyPatch) -> None:
    port = free_port()
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
        assert router.wait(scaled(10)) == 0


def test_check_attempts_below_zero_skip_the_router(monkeypatch: pytest.MonkeyPatch) -> None:
    port = free_port()
    _use_router(monkeypatch, port)
    monkeypatch.setenv("ZENOH_ROUTER_CHECK_ATTEMPTS", "-1")
    with Context("zenoh", domain_id=int(unique_domain())) as ctx:
        assert not ctx.transport.is_router  # type: ignore[attr-defined]
    with socket.socket() as probe:
        assert probe.connect_ex(("127.0.0.1", port)) != 0  # nobody took the router's port


def test_domains_do_not_hear_each_other(private_router: str) -> None:
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
        timeout=scaled(20),
        env={**__import__("os").environ, "ZENOH_SESSION_CONFIG_URI": "/nonexistent/session.json5"},
    )
    assert listed.returncode == 2 and "Traceback" not in listed.stderr
    assert "not a usable Zenoh configuration" in listed.stderr


def test_humble_keys_have_no_type_hash(
    monkeypatch: pytest.MonkeyPatch, private_router: str
) -> None:
    """Humble has no type hashes: its rmw_zenoh (0.1.x) writes ``TypeHashNotSupported``."""
    monkeypatch.setenv("ROS_DISTRO", "humble")
    domain = int(unique_domain())
    with Context("zenoh", domain_id=domain) as a, Context("zenoh", domain_id=domain) as b:
        key = a.transport.data_key("/chatter", String)  # type: ignore[attr-defined]
        assert key == f"{domain}/chatter/std_msgs::msg::dds_::String_/TypeHashNotSupported"
        assert _exchange(a, b)
        deadline = time.monotonic() + scaled(10)
        while True:  # the tokens b follows (its graph cache), as a's session declared them
            tokens = [
                token.key()
                for token in b.transport._graph.tokens()  # type: ignore[attr-defined]
                if token.kind is EntityKind.PUBLISHER and token.name == "/chatter"
            ]
            if tokens or time.monotonic() > deadline:
                break
            time.sleep(0.02)
        assert tokens and tokens[0].endswith("/TypeHashNotSupported/::,10:,:,:,,")
