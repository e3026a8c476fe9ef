"""``robomodel run rosbridge_server rosbridge_websocket`` on Zenoh, driven by real rosbridge
clients, one bridge for the module: roslibpy lists topics and nodes through rosapi, subscribes to
a topic robomodel publishes, publishes one robomodel echoes, offers a service robomodel calls,
calls one on the bus, reads a node's parameter and sends an action goal; roslibjs (npm
``roslib`` in Node.js) lists, subscribes plain and with each compression, publishes, calls a
service, serves and sends an action goal, and reads a reply in fragments."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import roslibpy

from tests.bridges.started import wait_started
from tests.conftest import ROBOMODEL, free_port, unique_domain
from tests.docs.runner import ROOT
from tests.timing import scaled, wait_until

NODE_MODULES = ROOT / ".node" / "node_modules"
ROSLIBJS = Path(__file__).with_name("roslib_client.mjs")


class _Graph:
    def __init__(self, tmp: Path) -> None:
        self.domain = unique_domain()
        self.port = free_port()
        self.tmp = tmp
        self.procs: list[subprocess.Popen[str]] = []

    def start(self, name: str, *argv: str) -> subprocess.Popen[str]:
        log = (self.tmp / f"{name}.log").open("w")
        proc = subprocess.Popen(
            [*ROBOMODEL, *argv], stdout=log, stderr=subprocess.STDOUT, text=True,
            start_new_session=True,
        )  # fmt: skip
        self.procs.append(proc)
        return proc

    def log(self, name: str) -> str:
        return (self.tmp / f"{name}.log").read_text()

    def cli(self, *argv: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [*ROBOMODEL, *argv, "--domain-id", self.domain],
            capture_output=True, text=True, timeout=scaled(60),
        )  # fmt: skip

    def close(self) -> None:
        for proc in self.procs:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
                try:
                    proc.wait(scaled(20))
                except subprocess.TimeoutExpired:
                    os.killpg(proc.pid, signal.SIGKILL)
                    proc.wait()


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[_Graph]:
    found = _Graph(tmp_path_factory.mktemp("rosbridge"))
    try:
        bridge = found.start("bridge", "run", "--domain-id", found.domain, "rosbridge_server",
                    "rosbridge_websocket", "--ros-args", "-p", f"port:={found.port}")  # fmt: skip
        found.start("counter", "topic", "pub", "--domain-id", found.domain, "-r", "20",
                    "/counter", "std_msgs/msg/Int32", "{data: 7}")  # fmt: skip
        wait_started(bridge, found.tmp / "bridge.log", "server started at")
        yield found
    finally:
        found.close()


@pytest.fixture(scope="module")
def ros(graph: _Graph) -> Iterator[Any]:
    client = roslibpy.Ros(host="127.0.0.1", port=graph.port)
    client.run(timeout=scaled(20))
    try:
        yield client
    finally:
        client.close()


def test_roslibpy_lists_subscribes_and_reads_parameters(graph: _Graph, ros: Any) -> None:
    wait_until(lambda: "/counter" in ros.get_topics(), 30, what="/counter via rosapi")
    assert ros.get_topic_type("/counter") == "std_msgs/msg/Int32"
    assert "/rosbridge_websocket" in ros.get_nodes()
    got: list[dict[str, Any]] = []
    listener = roslibpy.Topic(ros, "/counter", "std_msgs/msg/Int32")
    listener.subscribe(got.append)
    wait_until(lambda: got, 20, what="a /counter message through the bridge")
    listener.unsubscribe()
    assert got[0] == {"data": 7}
    assert ros.get_param("/rosbridge_websocket:port") == graph.port


def test_roslibpy_publishes_and_serves_and_calls(graph: _Graph, ros: Any) -> None:
    echo = graph.start("echo", "topic", "echo", "--domain-id", graph.domain, "--once",
                       "/chatter", "std_msgs/msg/String")  # fmt: skip
    talker = roslibpy.Topic(ros, "/chatter", "std_msgs/msg/String")
    talker.advertise()
    stop = threading.Event()

    def talk() -> None:  # until the echo, which may subscribe after the first ones, has one
        while not stop.wait(0.2):
            talker.publish(roslibpy.Message({"data": "hello from roslibpy"}))

    threading.Thread(target=talk, daemon=True).start()
    try:
        echo.wait(scaled(60))
    finally:
        stop.set()
    assert "data: hello from roslibpy" in graph.log("echo")

    def flip(request: dict[str, Any], response: dict[str, Any]) -> bool:
        response["success"] = not request["data"]
        response["message"] = "flipped by roslibpy"
        return True

    service = roslibpy.Service(ros, "/flip", "std_srvs/srv/SetBool")
    service.advertise(flip)
    wait_until(lambda: "/flip" in ros.get_services(), 30, what="/flip on the bus")
    called = graph.cli("service", "call", "/flip", "std_srvs/srv/SetBool", "{data: true}")
    assert "success: false\nmessage: flipped by roslibpy" in called.stdout, called

    get = roslibpy.Service(ros, "/rosbridge_websocket/get_parameters",
                           "rcl_interfaces/srv/GetParameters")  # fmt: skip
    reply = get.call(roslibpy.ServiceRequest({"names": ["port"]}), timeout=scaled(20))
    assert reply["values"][0]["integer_value"] == graph.port


def test_roslibjs_lists_subscribes_publishes_calls_and_runs_an_action(graph: _Graph) -> None:
    node = shutil.which("node")
    if node is None or not (NODE_MODULES / "roslib").is_dir():
        pytest.fail("the roslibjs test client is missing: tools/system-deps test installs it")
    wait_until(lambda: "/counter" in graph.cli("topic", "list").stdout, 30, what="/counter")
    echo = graph.start("echo_js", "topic", "echo", "--domain-id", graph.domain, "--once",
                       "/from_roslibjs", "std_msgs/msg/String")  # fmt: skip
    plan = {
        "wait_ms": int(scaled(30) * 1000),
        "topic": "/counter", "type": "std_msgs/msg/Int32",
        "publish": {"topic": "/from_roslibjs", "data": "hello from roslibjs"},
        "service": {"name": "/rosbridge_websocket/get_parameters",
                    "type": "rcl_interfaces/srv/GetParameters", "request": {"names": ["port"]}},
        "action": {"name": "/roslibjs_gripper", "type": "control_msgs/action/GripperCommand",
                   "goal": {"command": {"position": 0.5, "max_effort": 2.0}}},
        "fragment_size": 100,
    }  # fmt: skip
    log = graph.tmp / "roslibjs.log"
    env = {**os.environ, "ROBOMODEL_NODE_MODULES": str(NODE_MODULES)}
    client = subprocess.Popen(
        [node, str(ROSLIBJS), f"ws://127.0.0.1:{graph.port}", json.dumps(plan)],
        stdout=log.open("w"), stderr=subprocess.STDOUT, text=True, env=env,
        start_new_session=True,
    )  # fmt: skip
    graph.procs.append(client)
    found: dict[str, Any] = {}

    def done() -> bool:
        for line in log.read_text().splitlines():
            if line.startswith("{"):
                entry = json.loads(line)
                found[entry["kind"]] = entry["value"]
        if client.poll() is not None and "fragmented" not in found:
            raise AssertionError(f"roslibjs ended: {log.read_text()}")
        return "fragmented" in found

    wait_until(done, 120, what=lambda: f"roslibjs's results: {log.read_text()}")
    echo.wait(scaled(60))
    assert "data: hello from roslibjs" in graph.log("echo_js")
    topics = found["topics"]
    assert topics["types"][topics["topics"].index("/counter")] == "std_msgs/msg/Int32"
    assert found["none"] == found["cbor"] == found["png"] == {"data": 7}
    # cbor-raw: the CDR bytes (4 of encapsulation, 4 of the int32)
    assert found["cbor-raw"]["length"] == 8 and found["cbor-raw"]["secs"] > 0
    assert found["service"]["values"][0]["integer_value"] == graph.port
    action = found["action"]
    assert action["feedback"] == [{"position": 0.25, "effort": 0.0, "stalled": False,
                                   "reached_goal": False}]  # fmt: skip
    assert action["result"] == {"position": 0.5, "effort": 0.0, "stalled": False,
                                "reached_goal": True}  # fmt: skip
    fragmented = found["fragmented"]
    assert set(found["topics"]["topics"]) <= set(fragmented["topics"])
    assert fragmented["frames"] >= len(json.dumps(fragmented["topics"])) // plan["fragment_size"]


class _Gripper:
    """A GripperCommand goal that succeeds once its feedback was sent a few times."""

    def __init__(self, action: Any, position: float) -> None:
        self.action, self.position, self.ticks = action, position, 0

    def status(self) -> int:
        return 4 if self.ticks >= 5 else 2  # succeeded after 5 feedbacks, executing before

    def result(self) -> Any:
        return self.action.Result(position=self.position, reached_goal=True)

    def feedback(self) -> Any:
        self.ticks += 1
        return self.action.Feedback(position=self.position * self.ticks / 5)

    def cancel(self) -> bool:
        return False


def test_roslibpy_action_client_on_a_bus_action_server(graph: _Graph, ros: Any) -> None:
    from robomodel.runtime import Context
    from robomodel.runtime.action_server import ActionServer
    from robomodel.runtime.msg._resolver import resolve_action

    action = resolve_action("control_msgs/action/GripperCommand", "control_msgs/GripperCommand")
    with Context("zenoh", domain_id=int(graph.domain)) as ctx:
        node = ctx.create_node("gripper")
        server = ActionServer(node, action, "/bus_gripper", lambda g: _Gripper(action, 0.4))
        stop = threading.Event()
        spinner = threading.Thread(target=lambda: ctx.spin(until=stop.is_set), daemon=True)
        spinner.start()
        try:
            wait_until(lambda: "/bus_gripper/_action/send_goal" in ros.get_services(), 30,
                       what="the action's services through rosapi")  # fmt: skip
            client = roslibpy.ActionClient(
                ros, "/bus_gripper", "control_msgs/action/GripperCommand"
            )
            results: list[Any] = []
            feedback: list[Any] = []
            goal_id = client.send_goal(
                roslibpy.Goal({"command": {"position": 0.4, "max_effort": 1.0}}),
                results.append, feedback.append, results.append,
            )  # fmt: skip
            client.wait_goal(goal_id, timeout=scaled(30))
        finally:
            stop.set()
            spinner.join(scaled(10))
            server.destroy()
    assert results[0]["status"] == roslibpy.core.GoalStatus.SUCCEEDED
    assert results[0]["values"] == {"position": 0.4, "effort": 0.0, "stalled": False,
                                    "reached_goal": True}  # fmt: skip
    assert feedback and feedback[-1]["position"] <= 0.4
