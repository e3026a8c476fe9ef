"""The bridges on a ROS 1 master (robomodel's, one for the module), started as rosrun starts
them (``_port:=P``). rosbridge_websocket, driven by roslibpy: ROS 1's JSON (times as
``secs``/``nsecs``, types as ``pkg/Name``), a publication robomodel's ROS 1 echo receives, the
master's parameters through rosapi; with a raw client, ``cbor`` (ROS 1's times) and
``cbor-raw`` (ROS 1's serialisation, read back with rosbags), and actions refused. foxglove_bridge, driven by @foxglove/ws-protocol with
@foxglove/rosmsg-serialization: ``ros1`` messages with ``ros1msg`` schemas both ways."""

from __future__ import annotations

import json
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import cbor2
import pytest
import roslibpy
from websockets.sync.client import connect

from tests.bridges.started import wait_started
from tests.bridges.test_foxglove_clients import node_client, results
from tests.conftest import ROBOMODEL, _listening, end_process, free_port
from tests.timing import scaled, wait_until


@pytest.fixture(scope="module")
def master_env(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    home = tmp_path_factory.mktemp("ros1")
    port = free_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS")}
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}/", ROS_IP="127.0.0.1", HOME=str(home))
    procs = [subprocess.Popen([*ROBOMODEL, "master", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT,
                              start_new_session=True)]  # fmt: skip
    try:
        wait_until(lambda: _listening(port), 30, what="the ROS 1 master")
        yield env
    finally:
        for proc in reversed(procs):
            end_process(proc, timeout_s=20, group=True)


def test_roslibpy_on_a_ros1_master(master_env: dict[str, str], tmp_path: Path) -> None:
    port = free_port()
    log = (tmp_path / "bridge.log").open("w")
    bridge = subprocess.Popen(
        [*ROBOMODEL, "run", "rosbridge_server", "rosbridge_websocket", f"_port:={port}"],
        env=master_env, stdout=log, stderr=subprocess.STDOUT, text=True, start_new_session=True,
    )  # fmt: skip
    echo = None
    ros = roslibpy.Ros(host="127.0.0.1", port=port)
    try:
        wait_started(bridge, tmp_path / "bridge.log", "server started at")
        ros.run(timeout=scaled(20))
        points: list[dict[str, Any]] = []
        stamped = roslibpy.Topic(ros, "/point", "geometry_msgs/PointStamped")
        stamped.subscribe(points.append)
        ros.set_param("/robot/gain", {"kp": 2.5})
        assert ros.get_param("/robot/gain") == {"kp": 2.5}
        assert "/robot/gain/kp" in ros.get_params()
        echo = subprocess.Popen(
            [*ROBOMODEL, "topic", "echo", "--once", "/chatter", "std_msgs/String"],
            env=master_env, stdout=subprocess.PIPE, text=True, start_new_session=True,
        )  # fmt: skip
        talker = roslibpy.Topic(ros, "/chatter", "std_msgs/String")
        talker.advertise()

        def heard() -> bool:
            talker.publish(roslibpy.Message({"data": "hello over ROS 1"}))
            return echo.poll() is not None

        wait_until(heard, 60, what="robomodel's ROS 1 echo", interval_s=0.3)
        assert "data: hello over ROS 1" in echo.communicate()[0]
        assert ros.get_topic_type("/chatter") == "std_msgs/String"
        point = subprocess.Popen(
            [*ROBOMODEL, "topic", "pub", "-r", "10", "/point", "geometry_msgs/PointStamped",
             "{header: {stamp: {sec: 5, nanosec: 6}, frame_id: base}, point: {x: 1.5}}"],
            env=master_env, stdout=subprocess.DEVNULL, start_new_session=True,
        )  # fmt: skip
        try:
            wait_until(lambda: points, 30, what="a /point message")
            compressed = _compressed(port)
        finally:
            end_process(point, timeout_s=10, group=True)
        assert compressed["cbor"]["header"]["stamp"] == {"secs": 5, "nsecs": 6}
        assert compressed["cbor"]["point"]["x"] == 1.5
        from rosbags.typesys import Stores, get_typestore

        raw = compressed["cbor-raw"]["bytes"]
        decoded = get_typestore(Stores.ROS1_NOETIC).deserialize_ros1(
            raw, "geometry_msgs/msg/PointStamped"
        )
        assert decoded.header.stamp.sec == 5 and decoded.header.frame_id == "base"
        assert decoded.point.x == 1.5
        assert "actions are ROS 2 rosbridge's" in compressed["action"]
        assert points[0]["header"]["stamp"] == {"secs": 5, "nsecs": 6}
        assert points[0]["header"]["frame_id"] == "base" and points[0]["point"]["x"] == 1.5
    finally:
        ros.close()
        if echo is not None:
            end_process(echo, timeout_s=10, group=True)
        end_process(bridge, timeout_s=20, group=True)


def _compressed(port: int) -> dict[str, Any]:
    """A /point message as cbor and cbor-raw, and the refusal of an action goal."""
    found: dict[str, Any] = {}
    with connect(f"ws://127.0.0.1:{port}") as ws:
        for compression in ("cbor", "cbor-raw"):
            ws.send(json.dumps({"op": "subscribe", "topic": "/point", "compression": compression,
                                "type": "geometry_msgs/PointStamped"}))  # fmt: skip
            key = "header" if compression == "cbor" else "bytes"
            while key not in found.get(compression, {}):  # one sent before the unsubscribe
                found[compression] = cbor2.loads(ws.recv(timeout=scaled(10)))["msg"]
            ws.send(json.dumps({"op": "unsubscribe", "topic": "/point"}))
        ws.send(json.dumps({"op": "send_action_goal", "action": "/fibonacci",
                            "action_type": "actionlib_tutorials/Fibonacci"}))  # fmt: skip
        while "action" not in found:
            message = ws.recv(timeout=scaled(10))
            if isinstance(message, str) and json.loads(message)["op"] == "status":
                found["action"] = json.loads(message)["msg"]
    return found


def test_foxglove_client_on_a_ros1_master(master_env: dict[str, str], tmp_path: Path) -> None:
    port = free_port()
    procs = []

    def start(name: str, *argv: str) -> subprocess.Popen[str]:
        proc = subprocess.Popen([*ROBOMODEL, *argv], env=master_env, text=True,
                                stdout=(tmp_path / f"{name}.log").open("w"),
                                stderr=subprocess.STDOUT, start_new_session=True)  # fmt: skip
        procs.append(proc)
        return proc

    try:
        bridge = start("bridge", "run", "foxglove_bridge", "foxglove_bridge", f"_port:={port}")
        start("point", "topic", "pub", "-r", "10", "/point", "geometry_msgs/PointStamped",
              "{header: {stamp: {sec: 5, nanosec: 6}, frame_id: base}, point: {x: 1.5}}")  # fmt: skip
        echo = start("echo", "topic", "echo", "--once", "/chatter", "std_msgs/String")
        wait_started(bridge, tmp_path / "bridge.log", "listening at")
        plan = {"subscribe": "/point",
                "publish": {"topic": "/chatter", "type": "std_msgs/String",
                            "schema": "string data", "data": "hello from foxglove"}}  # fmt: skip
        procs.append(node_client(f"ws://127.0.0.1:{port}", plan, tmp_path / "client.log"))
        wait_until(lambda: "message" in results(tmp_path / "client.log") and echo.poll() is not None,
                   60, what=lambda: (tmp_path / "client.log").read_text()
                   + "\nbridge:\n" + (tmp_path / "bridge.log").read_text()[-3000:])  # fmt: skip
        found = results(tmp_path / "client.log")
        assert found["serverInfo"][0]["encodings"] == ["ros1"]
        message = found["message"][0]
        assert message["schemaName"] == "geometry_msgs/PointStamped"
        assert message["encoding"] == "ros1"
        assert message["msg"]["header"]["stamp"] == {"sec": 5, "nsec": 6}
        assert message["msg"]["point"]["x"] == 1.5
        assert "data: hello from foxglove" in (tmp_path / "echo.log").read_text()
    finally:
        for proc in reversed(procs):
            end_process(proc, timeout_s=20, group=True)
