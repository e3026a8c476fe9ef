"""foxglove_bridge on Zenoh, started by its launch file (``robomodel launch foxglove_bridge
foxglove_bridge_launch.xml port:=P topic_whitelist:=...``), driven by @foxglove/ws-protocol's
FoxgloveClient with @foxglove/rosmsg2-serialization (tests/bridges/foxglove_client.js, on
Node.js; ``tools/system-deps test`` installs them into .node/): the channels' CDR messages
decode with their ros2msg schemas, a client's publication reaches robomodel's echo, a service
of the bus answers, a node's parameter reads, ``package://`` assets are fetched (and one that
leaves its package is not), and the connection graph comes. One bridge and one client run."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.bridges.started import wait_started
from tests.conftest import EXAMPLES, ROBOMODEL, free_port, unique_domain
from tests.docs.runner import ROOT
from tests.timing import scaled, wait_until

NODE_MODULES = ROOT / ".node" / "node_modules"
CLIENT = Path(__file__).with_name("foxglove_client.js")
ASSET = "package://two_link_arm/urdf/two_link_arm.urdf"
ESCAPING = "package://two_link_arm/../../etc/passwd.urdf"


def node_client(url: str, plan: dict[str, Any], log: Path) -> subprocess.Popen[str]:
    """The Foxglove client, started; it prints a JSON line per result into ``log``."""
    node = shutil.which("node")
    if node is None or not (NODE_MODULES / "@foxglove" / "ws-protocol").is_dir():
        pytest.fail("the Foxglove test clients are missing: tools/system-deps test installs them")
    env = {**os.environ, "ROBOMODEL_NODE_MODULES": str(NODE_MODULES)}
    return subprocess.Popen(
        [node, str(CLIENT), url, json.dumps(plan)], stdout=log.open("w"),
        stderr=subprocess.STDOUT, text=True, env=env, start_new_session=True,
    )  # fmt: skip


def results(log: Path) -> dict[str, list[Any]]:
    found: dict[str, list[Any]] = {}
    for line in log.read_text().splitlines():
        if line.startswith("{"):
            entry = json.loads(line)
            found.setdefault(entry["kind"], []).append(entry["value"])
    return found


def _end(proc: subprocess.Popen[Any]) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(scaled(20))
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


@pytest.fixture(scope="module")
def session(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[dict[str, list[Any]], str]]:
    tmp = tmp_path_factory.mktemp("foxglove")
    domain, port = unique_domain(), free_port()
    env = {**os.environ, "ROS_PACKAGE_PATH": str(EXAMPLES)}
    procs: list[subprocess.Popen[Any]] = []

    def start(name: str, *argv: str) -> subprocess.Popen[Any]:
        proc = subprocess.Popen([*ROBOMODEL, *argv], stdout=(tmp / f"{name}.log").open("w"),
                                stderr=subprocess.STDOUT, env=env, start_new_session=True)  # fmt: skip
        procs.append(proc)
        return proc

    try:
        bridge = start("bridge", "launch", "--domain-id", domain, "foxglove_bridge",
              "foxglove_bridge_launch.xml", f"port:={port}", "topic_whitelist:=['/c.*']")  # fmt: skip
        start("counter", "topic", "pub", "--domain-id", domain, "-r", "20", "/counter",
              "std_msgs/msg/Int32", "{data: 7}")  # fmt: skip
        echo = start("echo", "topic", "echo", "--domain-id", domain, "--once", "/chatter",
                     "std_msgs/msg/String")  # fmt: skip
        wait_started(bridge, tmp / "bridge.log", "listening at")
        plan = {
            "subscribe": "/counter",
            "param": "/robomodel_topic_pub.use_sim_time",
            "assets": [ASSET, ESCAPING],
            "service": {"name": "/robomodel_topic_pub/list_parameters",
                        "request": {"prefixes": [], "depth": 0}},
            "publish": {"topic": "/chatter", "type": "std_msgs/msg/String",
                        "schema": "string data", "data": "hello from foxglove"},
        }  # fmt: skip
        client = node_client(f"ws://127.0.0.1:{port}", plan, tmp / "client.log")
        procs.append(client)
        wanted = {"serverInfo", "message", "serviceResponse", "parameters", "asset", "graph"}

        def done() -> bool:
            found = results(tmp / "client.log")
            return wanted <= set(found) and len(found["asset"]) == 2 and echo.poll() is not None

        wait_until(
            done, 90, what=lambda: f"the client's results: {(tmp / 'client.log').read_text()}"
        )
        yield results(tmp / "client.log"), (tmp / "echo.log").read_text()
    finally:
        for proc in reversed(procs):
            _end(proc)


def test_channels_and_client_publish(session: tuple[dict[str, list[Any]], str]) -> None:
    found, echoed = session
    info = found["serverInfo"][0]
    assert info["encodings"] == ["cdr"] and "clientPublish" in info["capabilities"]
    message = found["message"][0]
    assert message["schemaName"] == "std_msgs/msg/Int32" and message["encoding"] == "cdr"
    assert message["msg"] == {"data": 7}
    assert "data: hello from foxglove" in echoed
    assert "/counter" in found["graph"][0]["publishedTopics"]
    offered = {topic for batch in found["channels"] for topic in batch}
    assert "/counter" in offered and "/rosout" not in offered  # the launch's topic_whitelist


def test_services_parameters_and_assets(session: tuple[dict[str, list[Any]], str]) -> None:
    found, _ = session
    assert found["serviceResponse"][0]["result"]["names"] == ["use_sim_time"]
    assert found["parameters"][0] == [{"name": "/robomodel_topic_pub.use_sim_time", "value": False}]
    assets = {a["requestId"]: a for a in found["asset"]}
    size = (EXAMPLES / "two_link_arm" / "urdf" / "two_link_arm.urdf").stat().st_size
    assert assets[1]["status"] == 0 and assets[1]["bytes"] == size
    assert assets[2]["status"] == 1  # outside its package: refused
