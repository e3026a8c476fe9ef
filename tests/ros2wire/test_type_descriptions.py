"""``~/get_type_description`` (REP-2011) between robomodel and the zenoh-ros2-sdk peer.

The peer (``sdk_agent.py``) asks a robomodel node for the description of a type the node
uses; the description must hash (REP-2011's RIHS01, computed here) to the hash rosbags computes
from the type's upstream definition. The other way round, the peer publishes a message type of
a real ROS 2 package that robomodel has no class of (geographic_msgs, ``custom_interfaces/``)
and answers ``~/get_type_description`` for it as rcl does: robomodel's ``topic echo`` and
``bag record`` learn the type from that answer, and rosbags reads the recorded bag back.
"""

from __future__ import annotations

import hashlib
import json
import subprocess
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg.typehash import type_hash
from robomodel.runtime.msg.types.type_description_interfaces import GetTypeDescription
from tests.conftest import ROBOMODEL, unique_domain
from tests.ros2wire.msgtext import write_definitions
from tests.ros2wire.test_sdk_wire import AGENT, _sdk, _sdk_python, state_publisher
from tests.timing import scaled

__all__ = ["state_publisher"]  # the fixture, shared with test_sdk_wire

typesys = pytest.importorskip("rosbags.typesys")
STORE = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)
SERVICE = "type_description_interfaces/srv/GetTypeDescription"
GEO = "geographic_msgs/msg/GeoPoseStamped"


@pytest.fixture(scope="module")
def definitions(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_definitions(tmp_path_factory.mktemp("msgs"), [SERVICE, GEO])


def _rihs01(description: dict[str, Any]) -> str:
    """REP-2011's hash of a TypeDescription (as JSON): default values are left out."""

    def individual(d: dict[str, Any]) -> dict[str, Any]:
        keys = ("type_id", "capacity", "string_capacity", "nested_type_name")  # not constants
        fields = [{"name": f["name"], "type": {k: f["type"][k] for k in keys}} for f in d["fields"]]
        return {"type_name": d["type_name"], "fields": fields}

    data = {
        "type_description": individual(description["type_description"]),
        "referenced_type_descriptions": [
            individual(d) for d in description["referenced_type_descriptions"]
        ],
    }
    return "RIHS01_" + hashlib.sha256(json.dumps(data).encode()).hexdigest()


def test_the_service_type_hashes_as_the_sdk_hashes_it(definitions: Path) -> None:
    assert _sdk(definitions, "0", "hash", SERVICE) == [type_hash(GetTypeDescription)]


def test_the_sdk_gets_a_robomodel_node_s_type_description(
    definitions: Path, state_publisher: str
) -> None:
    wanted = STORE.hash_rihs01("tf2_msgs/msg/TFMessage")
    request = {"type_name": "tf2_msgs/msg/TFMessage", "type_hash": wanted,
               "include_type_sources": True}  # fmt: skip
    [answer] = _sdk(definitions, state_publisher, "call", "/robot_state_publisher/get_type_description", SERVICE, json.dumps(request))  # fmt: skip
    response = answer["response"]
    assert response["successful"] is True and response["failure_reason"] == ""
    description = response["type_description"]
    assert description["type_description"]["type_name"] == "tf2_msgs/msg/TFMessage"
    assert _rihs01(description) == wanted
    referenced = [d["type_name"] for d in description["referenced_type_descriptions"]]
    assert referenced == sorted(referenced) and "geometry_msgs/msg/TransformStamped" in referenced
    sources = response["type_sources"]
    assert [s["type_name"] for s in sources] == ["tf2_msgs/msg/TFMessage", *referenced]
    vector = next(s for s in sources if s["type_name"] == "geometry_msgs/msg/Vector3")
    assert vector["encoding"] == "msg" and vector["raw_file_contents"].split() == [
        "float64", "x", "float64", "y", "float64", "z"
    ]  # fmt: skip

    request = {
        "type_name": "std_msgs/msg/Int8",
        "type_hash": STORE.hash_rihs01("std_msgs/msg/Int8"),
    }
    [answer] = _sdk(definitions, state_publisher, "call", "/robot_state_publisher/get_type_description", SERVICE, json.dumps(request))  # fmt: skip
    assert answer["response"]["successful"] is False
    assert answer["response"]["failure_reason"] == "Type not currently in use by this node"


GEO_MESSAGE = {
    "header": {"frame_id": "earth"},
    "pose": {
        "position": {"latitude": 48.8584, "longitude": 2.2945, "altitude": 35.5},
        "orientation": {"w": 1.0},
    },
}


def test_robomodel_echoes_and_records_a_type_learned_from_the_peer(
    definitions: Path, tmp_path: Path
) -> None:
    domain = unique_domain()
    talker = subprocess.Popen(
        [_sdk_python(), str(AGENT), "--messages", str(definitions), "--domain", domain,
         "publish", "/geo", GEO, json.dumps(GEO_MESSAGE), "10", str(scaled(40)), "--describe"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=definitions,
    )  # fmt: skip
    try:
        echo = subprocess.run([*ROBOMODEL, "topic", "echo", "/geo", "--once", "--domain-id", domain],
                              capture_output=True, text=True, timeout=scaled(30))  # fmt: skip
        assert echo.returncode == 0, echo.stderr
        assert "frame_id: earth" in echo.stdout and "latitude: 48.8584" in echo.stdout
        assert "altitude: 35.5" in echo.stdout
        out = tmp_path / "bag"
        record = subprocess.run(
            [*ROBOMODEL, "bag", "record", "/geo", "-o", str(out), "--duration", str(scaled(3)),
             "--no-progress", "--domain-id", domain],
            capture_output=True, text=True, timeout=scaled(40),
        )  # fmt: skip
        assert record.returncode == 0, record.stderr
    finally:
        talker.kill()
        talker.wait()
    from rosbags.highlevel import AnyReader

    with AnyReader([out]) as reader:  # the bag's own definitions: rosbags has no geographic_msgs
        connection = next(c for c in reader.connections if c.topic == "/geo")
        assert connection.msgtype == GEO
        messages = [reader.deserialize(raw, GEO) for _, _, raw in reader.messages([connection])]
    assert messages and messages[0].pose.position.longitude == pytest.approx(2.2945)


def test_a_type_no_publisher_describes_is_one_line(definitions: Path) -> None:
    domain = unique_domain()
    talker = subprocess.Popen(
        [_sdk_python(), str(AGENT), "--messages", str(definitions), "--domain", domain,
         "publish", "/geo", GEO, json.dumps(GEO_MESSAGE), "10", str(scaled(40))],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=definitions,
    )  # fmt: skip
    try:
        echo = subprocess.run([*ROBOMODEL, "topic", "echo", "/geo", "--once", "--domain-id", domain],
                              capture_output=True, text=True, timeout=scaled(30))  # fmt: skip
    finally:
        talker.kill()
        talker.wait()
    assert echo.returncode == 2 and echo.stdout == ""
    [line] = echo.stderr.splitlines()
    assert f"unknown message type '{GEO}'" in line
    assert line.endswith("and no publisher of /geo described it")
