"""Types robomodel has no generated class for, published by an independent rmw_zenoh peer:
zenoh-ros2-sdk, with definitions from rosbags' Jazzy store (never robomodel's),
publishes an Image, a Marker, a PointCloud2, an OccupancyGrid and a type of the user's own
interface package. robomodel's ``topic echo`` prints each, ``bag record -a`` records them all,
and rosbags reads the bag back, from the bag's own definitions, equal to what was sent.
"""

from __future__ import annotations

import json
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import ROBOMODEL, unique_domain
from tests.ros2wire.msgtext import write_definitions
from tests.ros2wire.test_sdk_wire import AGENT, _sdk_python
from tests.timing import scaled

READING = "float64 value_c\nstring sensor\nuint32[] counts\n"
CHECKER = [0 if (x + y) % 2 else 255 for y in range(4) for x in range(4) for _ in range(3)]

SENT: dict[str, tuple[str, dict[str, Any]]] = {
    "/camera/image": (
        "sensor_msgs/msg/Image",
        {"header": {"frame_id": "camera"}, "height": 4, "width": 4, "encoding": "rgb8",
         "step": 12, "data": CHECKER},
    ),
    "/visualization_marker": (
        "visualization_msgs/msg/Marker",
        {"header": {"frame_id": "base_link"}, "ns": "cubes", "id": 7, "type": 1,
         "pose": {"position": {"x": 1.0}, "orientation": {"w": 1.0}},
         "scale": {"x": 0.2, "y": 0.2, "z": 0.2}, "color": {"r": 1.0, "a": 1.0}},
    ),
    "/points": (
        "sensor_msgs/msg/PointCloud2",
        {"header": {"frame_id": "lidar"}, "height": 1, "width": 1,
         "fields": [{"name": "x", "offset": 0, "datatype": 7, "count": 1}],
         "point_step": 4, "row_step": 4, "data": [0, 0, 128, 63], "is_dense": True},
    ),
    "/map": (
        "nav_msgs/msg/OccupancyGrid",
        {"header": {"frame_id": "map"}, "info": {"resolution": 0.5, "width": 2, "height": 2,
         "origin": {"orientation": {"w": 1.0}}}, "data": [0, 100, -1, 50]},
    ),
    "/reading": (
        "lab_msgs/msg/Reading",
        {"value_c": 21.5, "sensor": "bench thermometer", "counts": [3, 1, 4]},
    ),
}  # fmt: skip


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The SDK's definitions (rosbags' store; lab_msgs as the user wrote it) and the user's
    interface package, which robomodel finds with --package-path."""
    root = tmp_path_factory.mktemp("sdk_types")
    names = [t for t, _ in SENT.values() if not t.startswith("lab_msgs/")]
    write_definitions(root / "msgs", names)
    (root / "msgs/lab_msgs/msg").mkdir(parents=True)
    (root / "msgs/lab_msgs/msg/Reading.msg").write_text(READING)
    package = root / "src/lab_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "msg/Reading.msg").write_text(READING)
    (package / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>lab_msgs</name><version>0.0.0'
        "</version><description>d</description><maintainer email='a@b.c'>a</maintainer>"
        "<license>BSD</license></package>\n"
    )
    return root


@pytest.fixture(scope="module")
def publishing(workspace: Path) -> Iterator[str]:
    """The SDK's five publishers, 5 Hz, on a domain of their own."""
    domain = unique_domain()
    procs = []
    for topic, (type_name, values) in SENT.items():
        argv = [_sdk_python(), str(AGENT), "--messages", str(workspace / "msgs"), "--domain",
                domain, "publish", topic, type_name, json.dumps(values), "5", str(scaled(120))]  # fmt: skip
        procs.append(
            subprocess.Popen(
                argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=workspace / "msgs"
            )
        )
    try:
        yield domain
    finally:
        for proc in procs:
            proc.kill()
            proc.wait()


def _robomodel(workspace: Path, domain: str, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *args, "--domain-id", domain, "--package-path", str(workspace / "src")],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip


def _listed(workspace: Path, domain: str) -> str:
    deadline = time.monotonic() + scaled(40)
    listed = ""
    while time.monotonic() < deadline:
        listed = _robomodel(workspace, domain, "topic", "list", "-t").stdout
        if all(f"{t} [{n}]" in listed for t, (n, _) in SENT.items()):
            break
    return listed


def test_topic_list_and_echo_show_every_type(workspace: Path, publishing: str) -> None:
    listed = _listed(workspace, publishing)
    for topic, (type_name, _) in SENT.items():
        assert f"{topic} [{type_name}]" in listed, listed
    echoed = {
        topic: _robomodel(workspace, publishing, "topic", "echo", topic, "--once") for topic in SENT
    }
    for topic, run in echoed.items():
        assert run.returncode == 0, (topic, run.stderr)
    first = {t: yaml.safe_load(r.stdout.split("\n---")[0]) for t, r in echoed.items()}
    assert first["/camera/image"]["encoding"] == "rgb8"
    assert list(first["/camera/image"]["data"]) == CHECKER
    assert first["/visualization_marker"]["ns"] == "cubes"
    assert first["/visualization_marker"]["pose"]["position"]["x"] == 1.0
    assert [f["name"] for f in first["/points"]["fields"]] == ["x"]
    assert list(first["/map"]["data"]) == [0, 100, -1, 50]
    assert first["/reading"] == {
        "value_c": 21.5, "sensor": "bench thermometer", "counts": [3, 1, 4]
    }  # fmt: skip


def test_bag_record_all_and_rosbags_reads_it_back_equal(
    workspace: Path, publishing: str, tmp_path: Path
) -> None:
    from rosbags.highlevel import AnyReader

    _listed(workspace, publishing)
    out = tmp_path / "bag"
    run = _robomodel(
        workspace, publishing, "bag", "record", "-a", "-o", str(out), "--duration",
        str(scaled(4)), "--no-progress",
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    got: dict[str, Any] = {}
    with AnyReader([out]) as reader:  # the bag's own definitions: rosbags has no lab_msgs
        for connection, _, raw in reader.messages():
            if connection.topic in SENT and connection.topic not in got:
                got[connection.topic] = (connection.msgtype, reader.deserialize(raw, connection.msgtype))  # fmt: skip
    assert set(got) == set(SENT), (set(got), run.stderr)
    for topic, (type_name, _) in SENT.items():
        assert got[topic][0] == type_name
    image = got["/camera/image"][1]
    assert (image.width, image.height, image.encoding) == (4, 4, "rgb8")
    assert image.data.tolist() == CHECKER
    marker = got["/visualization_marker"][1]
    assert (marker.ns, marker.id, marker.type, marker.pose.position.x) == ("cubes", 7, 1, 1.0)
    cloud = got["/points"][1]
    assert cloud.data.tolist() == [0, 0, 128, 63] and cloud.fields[0].name == "x"
    grid = got["/map"][1]
    assert grid.data.tolist() == [0, 100, -1, 50] and grid.info.resolution == 0.5
    reading = got["/reading"][1]
    assert (reading.value_c, reading.sensor, reading.counts.tolist()) == (
        21.5, "bench thermometer", [3, 1, 4]
    )  # fmt: skip
