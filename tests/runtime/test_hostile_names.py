"""Names from a peer are printed with control characters escaped, on both buses."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import time
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest

from robomodel._escape import escape_name, escape_names
from tests.conftest import ROBOMODEL, ROOT, free_port, unique_domain
from tests.timing import scaled

# Retitle the terminal, then turn its text red.
HOSTILE = "evil\x1b]0;pwned\x07\x1b[31m"
RAW_CONTROLS = ("\x1b", "\x07", "\x9b", "\r", "\u202e")


def test_escape_name_escapes_controls_and_keeps_printable_unicode() -> None:
    assert escape_name("/robot_state_publisher") == "/robot_state_publisher"
    assert escape_name("/ロボット/bras é") == "/ロボット/bras é"
    assert escape_name(HOSTILE) == "evil\\x1b]0;pwned\\x07\\x1b[31m"
    assert escape_name("/a\r\n\t\x9b\x7f\u202e\U000e0001") == (
        "/a\\x0d\\x0a\\x09\\x9b\\x7f\\u202e\\U000e0001"
    )
    # a name spelling an escape out stays distinguishable from an escaped control
    assert escape_name("/x\\x1b") == "/x\\\\x1b" != escape_name("/x\x1b")
    assert escape_names(["/b\x07", "/c"]) == "/b\\x07, /c"


def _cli_env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS")}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), str(ROOT)])
    return env


def _run(*argv: str, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *argv], capture_output=True, text=True, env=env, timeout=scaled(60)
    )


def _assert_no_raw_controls(result: subprocess.CompletedProcess[str]) -> None:
    for char in RAW_CONTROLS:
        assert char not in result.stdout + result.stderr, (char, result)


def test_hostile_zenoh_liveliness_names_are_escaped_in_listings() -> None:
    """A peer declares rmw_zenoh tokens, with zenoh itself, whose node, topic and type names
    hold terminal escapes; ``node list/info`` and ``topic list/info`` print them escaped."""
    pytest.importorskip("zenoh")
    from robomodel.runtime.transport._zenoh_session import open_session

    domain = unique_domain()
    session = open_session().session  # joins the test run's router
    zid = str(session.zid())
    node = f"@ros2_lv/{domain}/{zid}/0/0/NN/%/%/{HOSTILE}"
    publisher = (
        f"@ros2_lv/{domain}/{zid}/0/1/MP/%/%/{HOSTILE}/%chat\x1b[31mter"
        "/std_msgs::msg::dds_::String_\x9b0m/RIHS01_x/::,7:,:,:,,"
    )
    tokens = [session.liveliness().declare_token(key) for key in (node, publisher)]
    env = _cli_env()
    try:
        nodes = _run("node", "list", "--domain-id", domain, env=env)
        topics = _run("topic", "list", "-t", "--domain-id", domain, env=env)
        info = _run("node", "info", HOSTILE, "--domain-id", domain, env=env)
        topic_info = _run("topic", "info", "-v", "/chat\x1b[31mter", "--domain-id", domain, env=env)
    finally:
        for token in tokens:
            token.undeclare()
        session.close()
    assert nodes.returncode == 0 and nodes.stdout == "/evil\\x1b]0;pwned\\x07\\x1b[31m\n"
    assert topics.stdout == "/chat\\x1b[31mter [std_msgs::msg::dds_::String_\\x9b0m]\n"
    assert "/chat\\x1b[31mter: std_msgs::msg::dds_::String_\\x9b0m" in info.stdout
    assert "Node name: /evil\\x1b]0;pwned\\x07\\x1b[31m" in topic_info.stdout
    for result in (nodes, topics, info, topic_info):
        _assert_no_raw_controls(result)


@pytest.fixture
def ros1_master(tmp_path: Path) -> Iterator[str]:
    port = free_port()
    env = {**_cli_env(), "ROS_HOME": str(tmp_path)}
    # Debian's rosmaster: it registers names holding controls, which robomodel's own master
    # refuses, so that what a listing prints of them can be seen
    proc = subprocess.Popen(
        ["/usr/bin/roscore", "-p", str(port)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=env,
        start_new_session=True,
    )
    uri = f"http://127.0.0.1:{port}/"
    try:
        deadline = time.monotonic() + scaled(30)
        while time.monotonic() < deadline:
            with socket.socket() as probe:
                if probe.connect_ex(("127.0.0.1", port)) == 0:
                    break
            time.sleep(0.05)
        yield uri
    finally:
        os.killpg(proc.pid, signal.SIGINT)  # roscore and its rosmaster and rosout
        try:
            proc.wait(scaled(20))
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def test_hostile_ros1_names_are_escaped_in_listings(ros1_master: str) -> None:
    """A peer registers with the ROS 1 master, through xmlrpc.client, names holding every
    control that XML-RPC can carry (XML 1.0 refuses ESC and BEL, which the master answers
    with a parse error): newline, carriage return, C1's CSI and a bidi override. ``node
    list`` and ``topic list`` print them escaped from getSystemState."""
    master = xmlrpc.client.ServerProxy(ros1_master)
    with pytest.raises(xmlrpc.client.Fault):
        master.registerPublisher(f"/{HOSTILE}", "/t", "std_msgs/String", "http://127.0.0.1:1/")
    for tail in ("\r", "\n/forged", "\x9b31m", "\u202e"):
        code, _, _ = master.registerPublisher(
            f"/evil{tail}", f"/t{tail}", "std_msgs/String", "http://127.0.0.1:1/"
        )
        assert code == 1
    env = {**_cli_env(), "ROS_MASTER_URI": ros1_master}
    nodes = _run("node", "list", env=env)
    topics = _run("topic", "list", "-t", env=env)
    assert nodes.returncode == 0 and topics.returncode == 0, (nodes, topics)
    # XML turns a raw carriage return into a newline; both arrive as one line each
    assert [n for n in nodes.stdout.splitlines() if n != "/rosout"] == [
        "/evil\\x0a",
        "/evil\\x0a/forged",
        "/evil\\x9b31m",
        "/evil\\u202e",
    ]
    assert "/t\\x9b31m [std_msgs/msg/String]" in topics.stdout.splitlines()
    for result in (nodes, topics):
        _assert_no_raw_controls(result)
