"""Types robomodel has no hand-written class for, on ROS 1's wire against Debian's tools:
``rostopic pub`` of sensor_msgs/Image to robomodel's master, robomodel echoes it; Debian's
``rostopic echo`` reads robomodel's publication of the same type; a custom type from an
interface package on ROS_PACKAGE_PATH goes both ways the same."""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.ros1wire.conftest import Ros1
from tests.timing import scaled


@dataclass
class _WithPackages(Ros1):
    """The test graph, with a folder of test interface packages on ROS_PACKAGE_PATH."""

    packages: Path | None = None

    @property
    def env(self) -> dict[str, str]:
        return {**Ros1.env.fget(self), "ROS_PACKAGE_PATH": f"{self.packages}:/usr/share"}  # type: ignore[attr-defined]


@pytest.fixture
def custom(ros1: Ros1, tmp_path: Path) -> Iterator[Ros1]:
    package = tmp_path / "ws" / "my_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="2"><name>my_msgs</name><version>0.0.0</version>'
        "<description>d</description><maintainer email='dev@example.com'>a</maintainer>"
        "<license>BSD</license></package>"
    )
    (package / "msg" / "Reading.msg").write_text(
        "Header header\nfloat64 value\nstring unit\nint16[3] raw\n"
    )
    graph = _WithPackages(tmp_path / "home", packages=tmp_path / "ws")
    (tmp_path / "home").mkdir()
    try:
        yield graph
    finally:
        graph.close()


IMAGE = (
    "{height: 2, width: 2, encoding: rgb8, step: 6, data: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]}"
)


def _master(ros1: Ros1) -> None:
    ros1.robomodel("master", "-p", str(ros1.port))
    ros1.wait_for_master()


def _first(text: str) -> Any:
    return yaml.safe_load(text.split("\n---")[0])


def _debian_echo(ros1: Ros1, topic: str, timeout_s: float = 60) -> Any:
    timeout_s = scaled(timeout_s)
    deadline = time.monotonic() + timeout_s
    while True:
        echo = ros1.run("/usr/bin/rostopic", "echo", "-n", "1", topic, timeout=timeout_s)
        if echo.returncode == 0 and echo.stdout.strip():
            return _first(echo.stdout)
        assert time.monotonic() < deadline, f"rostopic echo {topic}: {echo.stderr}"
        time.sleep(0.5)


def test_image_from_rostopic_pub_and_to_rostopic_echo(ros1: Ros1, tmp_path: Path) -> None:
    _master(ros1)
    ros1.start(["/usr/bin/rostopic", "pub", "-r", "5", "/theirs", "sensor_msgs/Image", IMAGE])
    echo = ros1.robomodel_run("topic", "echo", "/theirs", "--once", timeout=scaled(90))
    assert echo.returncode == 0, echo.stderr
    got = _first(echo.stdout)
    assert (got["height"], got["width"], got["encoding"], got["step"]) == (2, 2, "rgb8", 6)
    assert got["data"] == list(range(1, 13))

    log = tmp_path / "pub.log"
    ros1.robomodel("topic", "pub", "/ours", "sensor_msgs/msg/Image", IMAGE, "-r", "5", log=log)
    theirs = _debian_echo(ros1, "/ours")
    assert (theirs["height"], theirs["encoding"], theirs["step"]) == (2, "rgb8", 6)
    # genpy's echo prints uint8[] as a list of numbers
    assert list(theirs["data"]) == list(range(1, 13))


# Debian's rospy and genpy's dynamic classes (rostopic needs built messages): subscribe with
# AnyMsg, decode with a class generated from the publisher's message_definition header; publish
# with a class generated from the .msg text.
_GENPY = r"""
import sys, genpy.dynamic, rospy
from std_msgs.msg import Header
rospy.init_node("debian_side", anonymous=True)
if sys.argv[1] == "echo":
    got = []
    def seen(raw):
        header = raw._connection_header
        cls = genpy.dynamic.generate_dynamic(header["type"], header["message_definition"])
        got.append(cls[header["type"]]().deserialize(raw._buff))
    rospy.Subscriber("/reading", rospy.AnyMsg, seen)
    while not got and not rospy.is_shutdown():
        rospy.sleep(0.1)
    m = got[0]
    print(m.value, m.unit, list(m.raw), flush=True)
else:
    text = open(sys.argv[2]).read() + "\n" + "=" * 80 + "\nMSG: std_msgs/Header\n"
    text += "uint32 seq\ntime stamp\nstring frame_id\n"
    Reading = genpy.dynamic.generate_dynamic("my_msgs/Reading", text)["my_msgs/Reading"]
    pub = rospy.Publisher("/from_debian", Reading, queue_size=1)
    while not rospy.is_shutdown():
        pub.publish(Reading(value=-1.25, unit="psi", raw=[7, 8, -9]))
        rospy.sleep(0.2)
"""


def test_custom_package_type_both_ways(custom: Ros1, tmp_path: Path) -> None:
    """A ROS 1 message package that only exists in a test folder, on ROS_PACKAGE_PATH:
    robomodel's publication decodes in Debian's rospy by the definition robomodel sends, and
    robomodel echoes what Debian's rospy publishes."""
    _master(custom)
    script = tmp_path / "debian_side.py"
    script.write_text(_GENPY)
    log = tmp_path / "pub.log"
    proc = custom.robomodel(
        "topic", "pub", "/reading", "my_msgs/msg/Reading",
        "{value: 2.5, unit: bar, raw: [1, -2, 3]}", "-r", "5", log=log,
    )  # fmt: skip
    echo = custom.run("/usr/bin/python3", str(script), "echo", timeout=scaled(90))
    assert proc.poll() is None, log.read_text()
    assert echo.stdout.strip() == "2.5 bar [1, -2, 3]", echo.stderr
    msg = tmp_path / "ws" / "my_msgs" / "msg" / "Reading.msg"
    custom.start(["/usr/bin/python3", str(script), "pub", str(msg)])
    ours = custom.robomodel_run("topic", "echo", "/from_debian", "--once", timeout=scaled(90))
    assert ours.returncode == 0, ours.stderr
    got = _first(ours.stdout)
    assert (got["value"], got["unit"], got["raw"]) == (-1.25, "psi", [7, 8, -9])


_UNKNOWN = r"""
import genpy.dynamic, rospy
rospy.init_node("debian_unknown", anonymous=True)
text = "geometry_msgs/Point where\nuint8 level\nstring[] tags\n" + "=" * 80
text += "\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n"
Sample = genpy.dynamic.generate_dynamic("lab_msgs/Sample", text)["lab_msgs/Sample"]
Point = genpy.dynamic.generate_dynamic("geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n")
pub = rospy.Publisher("/sample", Sample, queue_size=1)
while not rospy.is_shutdown():
    pub.publish(Sample(where=Point["geometry_msgs/Point"](1.0, -2.0, 0.5), level=7,
                       tags=["a", "b"]))
    rospy.sleep(0.2)
"""


def test_a_type_only_the_publisher_knows_is_learned_from_its_definition(
    ros1: Ros1, tmp_path: Path
) -> None:
    """No package nor store has lab_msgs/Sample: robomodel's echo decodes it by the
    message_definition of the publisher's TCPROS header, as rostopic echo would."""
    _master(ros1)
    script = tmp_path / "unknown.py"
    script.write_text(_UNKNOWN)
    ros1.start(["/usr/bin/python3", str(script)])
    ros1.until(lambda: "/sample" in ros1.names("topics"), "publisher")
    echo = ros1.robomodel_run("topic", "echo", "/sample", "--once", timeout=scaled(90))
    assert echo.returncode == 0, echo.stderr
    got = _first(echo.stdout)
    assert got == {"where": {"x": 1.0, "y": -2.0, "z": 0.5}, "level": 7, "tags": ["a", "b"]}


MARKER = (
    "{header: {frame_id: map}, ns: path, id: 3, type: 4, action: 0, "
    "pose: {orientation: {w: 1.0}}, scale: {x: 0.05}, color: {r: 1.0, a: 1.0}, "
    "points: [{x: 1.0, y: 2.0, z: 0.0}, {x: -1.0, y: 0.5, z: 0.25}], text: hello}"
)


def test_marker_from_rostopic_pub_and_to_rostopic_echo(ros1: Ros1, tmp_path: Path) -> None:
    """visualization_msgs/Marker: ROS 1's (no texture, mesh_file, uv_coordinates) and Jazzy's
    class map field by field; what both have goes through."""
    _master(ros1)
    ros1.start(["/usr/bin/rostopic", "pub", "-r", "5", "/their_marker",
                "visualization_msgs/Marker", MARKER])  # fmt: skip
    echo = ros1.robomodel_run("topic", "echo", "/their_marker", "--once", timeout=scaled(90))
    assert echo.returncode == 0, echo.stderr
    got = _first(echo.stdout)
    assert (got["header"]["frame_id"], got["ns"], got["id"], got["type"]) == ("map", "path", 3, 4)
    assert got["points"] == [{"x": 1.0, "y": 2.0, "z": 0.0}, {"x": -1.0, "y": 0.5, "z": 0.25}]
    assert (got["text"], got["scale"]["x"], got["color"]["r"]) == ("hello", 0.05, 1.0)

    log = tmp_path / "pub.log"
    ros1.robomodel("topic", "pub", "/our_marker", "visualization_msgs/msg/Marker", MARKER,
                   "-r", "5", log=log)  # fmt: skip
    theirs = _debian_echo(ros1, "/our_marker")
    assert (theirs["header"]["frame_id"], theirs["ns"], theirs["id"]) == ("map", "path", 3)
    assert theirs["points"][1] == {"x": -1.0, "y": 0.5, "z": 0.25}
    assert theirs["text"] == "hello"


def test_bag_record_of_rostopic_pub_s_image_and_marker(ros1: Ros1, tmp_path: Path) -> None:
    """Types from definitions on ROS 1: what Debian's ``rostopic pub`` sends as sensor_msgs/Image and
    visualization_msgs/Marker, ``bag record`` records, and rosbags reads back from the bag's
    own definitions equal to what was sent."""
    from rosbags.highlevel import AnyReader

    _master(ros1)
    ros1.start(["/usr/bin/rostopic", "pub", "-r", "5", "/img", "sensor_msgs/Image", IMAGE])
    ros1.start(["/usr/bin/rostopic", "pub", "-r", "5", "/mk", "visualization_msgs/Marker",
                MARKER])  # fmt: skip
    ros1.until(lambda: {"/img", "/mk"} <= ros1.names("topics"), "publishers")
    folder = tmp_path / "bag"
    rec = ros1.robomodel_run(
        "bag", "record", "/img", "/mk", "-o", str(folder), "--duration", f"{scaled(4):.1f}"
    )
    assert rec.returncode == 0, rec.stderr
    got: dict[str, Any] = {}
    with AnyReader([folder]) as reader:
        for conn, _, data in reader.messages():
            got.setdefault(conn.topic, reader.deserialize(data, conn.msgtype))
    assert set(got) == {"/img", "/mk"}, rec.stderr
    image, marker = got["/img"], got["/mk"]
    assert (image.width, image.height, image.encoding) == (2, 2, "rgb8")
    assert image.data.tolist() == list(range(1, 13))
    assert (marker.header.frame_id, marker.ns, marker.id, marker.type) == ("map", "path", 3, 4)
    assert [(p.x, p.y, p.z) for p in marker.points] == [(1.0, 2.0, 0.0), (-1.0, 0.5, 0.25)]


def test_bag_record_of_a_learned_type(ros1: Ros1, tmp_path: Path) -> None:
    """``bag record -a`` on ROS 1 records lab_msgs/Sample, which only its publisher knows: the
    bag stores the definition, and rosbags reads the messages back from the bag alone."""
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    _master(ros1)
    script = tmp_path / "unknown.py"
    script.write_text(_UNKNOWN)
    ros1.start(["/usr/bin/python3", str(script)])
    ros1.until(lambda: "/sample" in ros1.names("topics"), "publisher")
    folder = tmp_path / "bag"
    rec = ros1.robomodel_run(
        "bag", "record", "-a", "-o", str(folder), "--duration", f"{scaled(3):.1f}"
    )
    assert rec.returncode == 0, rec.stderr
    store = get_typestore(Stores.EMPTY)
    samples = []
    with Reader(folder) as reader:
        for conn in reader.connections:
            store.register(get_types_from_msg(conn.msgdef.data, conn.msgtype))
        for conn, _, data in reader.messages():
            if conn.topic == "/sample":
                samples.append(store.deserialize_cdr(data, conn.msgtype))
    assert samples, rec.stderr
    first = samples[0]
    assert (first.where.x, first.where.y, first.level, first.tags) == (1.0, -2.0, 7, ["a", "b"])


def test_genaction_types_of_a_package_action(custom: Ros1, tmp_path: Path) -> None:
    """An action of a ROS 1 package (action/Fibonacci.action) gives genaction's messages: the
    feedback topic's my_msgs/FibonacciActionFeedback goes from robomodel's pub to its echo,
    and the master (Debian's rostopic type) holds the ROS 1 type name."""
    action = tmp_path / "ws" / "my_msgs" / "action"
    action.mkdir()
    (action / "Fibonacci.action").write_text("int32 order\n---\nint32[] sequence\n---\n"
                                             "int32[] partial_sequence\n")  # fmt: skip
    _master(custom)
    log = tmp_path / "pub.log"
    custom.robomodel("topic", "pub", "/fib/feedback", "my_msgs/FibonacciActionFeedback",
                     "{status: {status: 1, text: going}, feedback: {partial_sequence: [0, 1, 1]}}",
                     "-r", "5", "--bus", "ros1", log=log)  # fmt: skip
    custom.until(
        lambda: (
            custom.run("/usr/bin/rostopic", "type", "/fib/feedback").stdout.strip()
            == "my_msgs/FibonacciActionFeedback"
        ),
        "the feedback topic on the master",
    )
    echo = custom.robomodel_run("topic", "echo", "/fib/feedback", "--once", "--bus", "ros1",
                                timeout=scaled(90))  # fmt: skip
    assert echo.returncode == 0, echo.stderr + log.read_text()
    got = _first(echo.stdout)
    assert got["status"]["text"] == "going" and got["status"]["status"] == 1
    assert got["feedback"] == {"partial_sequence": [0, 1, 1]}
