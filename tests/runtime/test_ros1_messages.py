"""robomodel's messages in ROS 1's serialization against Debian's genpy classes (the system
Python's python3-sensor-msgs, -tf2-msgs, -std-srvs, ...): md5sums, definitions and bytes; and
malformed input refused within bounds."""

from __future__ import annotations

import json
import subprocess
import time
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg import Header, JointState, Time, get_message_type
from robomodel.runtime.msg.schema import get_service_type
from robomodel.runtime.transport.ros1.ros1_types import (
    Ros1CodecError,
    Ros1TypeError,
    ros1_service_type,
    ros1_type,
    ros1_type_named,
)
from tests.timing import scaled

SYSTEM_PYTHON = "/usr/bin/python3"

MESSAGES = {
    "std_msgs/String": "std_msgs/msg/String",
    "std_msgs/Float64": "std_msgs/msg/Float64",
    "std_msgs/Float64MultiArray": "std_msgs/msg/Float64MultiArray",
    "sensor_msgs/JointState": "sensor_msgs/msg/JointState",
    "geometry_msgs/TransformStamped": "geometry_msgs/msg/TransformStamped",
    "tf2_msgs/TFMessage": "tf2_msgs/msg/TFMessage",
    "rosgraph_msgs/Clock": "rosgraph_msgs/msg/Clock",
    "geometry_msgs/Twist": "geometry_msgs/msg/Twist",
    "roscpp/Logger": "roscpp/msg/Logger",
}
SERVICES = {"std_srvs/Empty": "std_srvs/srv/Empty", "std_srvs/Trigger": "std_srvs/srv/Trigger",
            "std_srvs/SetBool": "std_srvs/srv/SetBool", "roscpp/GetLoggers": "roscpp/srv/GetLoggers",
            "roscpp/SetLoggerLevel": "roscpp/srv/SetLoggerLevel"}  # fmt: skip


def _genpy(script: str) -> Any:
    """Run ``script`` in Debian's Python (genpy's classes); its JSON output."""
    if not Path(SYSTEM_PYTHON).exists():
        pytest.fail("Debian's python3 with the ROS 1 message packages is missing")
    done = subprocess.run(
        [SYSTEM_PYTHON, "-c", script], capture_output=True, text=True, timeout=scaled(60)
    )
    if done.returncode != 0:
        pytest.fail(f"Debian's ROS 1 message packages: {done.stderr[-400:]}")
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def reference() -> Any:
    names = json.dumps([*MESSAGES, *SERVICES])
    return _genpy(
        "import json, importlib\n"
        f"out = {{}}\nfor name in {names}:\n"
        "    pkg, typ = name.split('/')\n"
        f"    kind = 'srv' if name in {json.dumps(list(SERVICES))} else 'msg'\n"
        "    cls = getattr(importlib.import_module(pkg + '.' + kind), typ)\n"
        "    entry = {'md5': cls._md5sum}\n"
        "    if kind == 'msg':\n"
        "        entry['text'] = cls._full_text\n"
        "    else:\n"
        "        entry['request'] = cls._request_class._md5sum\n"
        "        entry['response'] = cls._response_class._md5sum\n"
        "    out[name] = entry\n"
        "print(json.dumps(out))\n"
    )


@pytest.mark.parametrize("ros1_name", sorted(MESSAGES))
def test_md5sum_and_definition_equal_genpy(reference: Any, ros1_name: str) -> None:
    kind = ros1_type(get_message_type(MESSAGES[ros1_name]))
    assert kind.name == ros1_name
    assert kind.md5sum == reference[ros1_name]["md5"]
    assert _lines(kind.definition) == _lines(reference[ros1_name]["text"])


def _lines(definition: str) -> Counter[str]:
    """The definition's lines without comments, blank lines or spacing, field types without
    their package (genpy keeps the file's ``Header``, rosbags writes ``std_msgs/Header``; the
    order of the nested definitions may differ)."""
    out: Counter[str] = Counter()
    for line in definition.splitlines():
        words = line.split("#")[0].split()
        if words and not words[0].startswith(("=", "MSG:")):
            words[0] = words[0].rsplit("/", 1)[-1]
        if words:
            out[" ".join(words)] += 1
    return out


@pytest.mark.parametrize("ros1_name", sorted(SERVICES))
def test_service_md5sums_equal_genpy(reference: Any, ros1_name: str) -> None:
    kind = ros1_service_type(get_service_type(SERVICES[ros1_name]))
    assert kind.name == ros1_name
    assert kind.md5sum == reference[ros1_name]["md5"]
    assert kind.request.md5sum == reference[ros1_name]["request"]
    assert kind.response.md5sum == reference[ros1_name]["response"]


def test_service_md5sums_of_the_vendored_ros1_packages() -> None:
    """The ROS 1 md5sums of these services (ros_control and gazebo_ros_pkgs, noetic) as the
    code genmsg's generators wrote for them publishes them (gennodejs' ``md5sum()``,
    genlisp's ``roslisp-msg-protocol:md5sum``), computed here from the vendored definitions."""
    expected = {
        "controller_manager_msgs/srv/LoadController": "647e5c54b8d6468952d8d31f1efe96c0",
        "controller_manager_msgs/srv/SwitchController": "b29a7abc673b2c54c14b54e50f8d06a5",
        "gazebo_msgs/srv/SpawnModel": "9ed9c82c96abe1a00c3e8cdaeee24413",
        "gazebo_msgs/srv/GetLinkState": "09d6c98cce97b35f7ab9bd70300657ab",
        "gazebo_msgs/srv/SetLinkState": "8a5146eb66ae4d26b0860b08f3f271be",
        "gazebo_msgs/srv/GetModelProperties": "5717f7bd34ed990fa80e28b3015027a3",
    }
    for name, md5 in expected.items():
        assert ros1_service_type(get_service_type(name)).md5sum == md5, name
    for name in ("gazebo_msgs/msg/ModelStates", "gazebo_msgs/msg/LinkStates"):
        assert ros1_type(get_message_type(name)).md5sum == "48c080191eb15c41858319b4d8a609c2"
    log = ros1_type(get_message_type("rosgraph_msgs/msg/Log"))
    assert log.md5sum == "acffd30cd6b6de30f120938c17c593fb"  # rosgraph_msgs/Log (noetic)


def test_bytes_equal_genpy_both_ways() -> None:
    theirs = _genpy(
        "import io, json, rospy\n"
        "from sensor_msgs.msg import JointState\n"
        "from tf2_msgs.msg import TFMessage\n"
        "from geometry_msgs.msg import TransformStamped\n"
        "from std_msgs.msg import Float64MultiArray, MultiArrayDimension\n"
        "def ser(m):\n    b = io.BytesIO(); m.serialize(b); return b.getvalue().hex()\n"
        "js = JointState(); js.header.seq = 7; js.header.stamp = rospy.Time(12, 345)\n"
        "js.header.frame_id = 'base'; js.name = ['a', 'bé']; js.position = [0.5, -1.25]\n"
        "js.velocity = [1.0, 2.0]\n"
        "tfs = []\n"
        "for i in range(2):\n"
        "    t = TransformStamped(); t.header.stamp = rospy.Time(3, i); t.header.frame_id = 'w'\n"
        "    t.child_frame_id = 'c%d' % i; t.transform.translation.x = i + 0.5\n"
        "    t.transform.rotation.w = 1.0; tfs.append(t)\n"
        "fm = Float64MultiArray(); fm.layout.dim = [MultiArrayDimension('x', 2, 2)]\n"
        "fm.data = [1.5, 2.5]\n"
        "print(json.dumps([ser(js), ser(TFMessage(tfs)), ser(fm)]))\n"
    )
    joint_state = JointState(Header(Time(12, 345), "base"), ["a", "bé"], [0.5, -1.25], [1.0, 2.0])
    kind = ros1_type(JointState)
    assert kind.encode(joint_state, 7).hex() == theirs[0]
    back = kind.decode(bytes.fromhex(theirs[0]))
    assert back == joint_state
    tf_type = get_message_type("tf2_msgs/msg/TFMessage")
    decoded = ros1_type(tf_type).decode(bytes.fromhex(theirs[1]))
    assert [t.child_frame_id for t in decoded.transforms] == ["c0", "c1"]  # type: ignore[attr-defined]
    assert decoded.transforms[1].transform.translation.x == 1.5  # type: ignore[attr-defined]
    assert decoded.transforms[1].header.stamp == Time(3, 1)  # type: ignore[attr-defined]
    assert ros1_type(tf_type).encode(decoded).hex() == theirs[1]
    array_type = get_message_type("std_msgs/msg/Float64MultiArray")
    array = ros1_type(array_type).decode(bytes.fromhex(theirs[2]))
    assert ros1_type(array_type).encode(array).hex() == theirs[2]


def test_tf_tfmessage_is_tf2_s_definition_and_decodes_into_tfmessage() -> None:
    old = ros1_type_named("tf/tfMessage")
    assert old.name == "tf/tfMessage" and old.md5sum == "94810edda583a504dfda3829e70d7eec"
    assert old.cls is get_message_type("tf2_msgs/msg/TFMessage")


def test_ros2_only_types_have_no_ros1_counterpart() -> None:
    with pytest.raises(Ros1TypeError):
        ros1_type(get_message_type("rcl_interfaces/msg/ParameterEvent"))
    with pytest.raises(Ros1TypeError):
        ros1_service_type(get_service_type("controller_manager_msgs/srv/ConfigureController"))


def test_malformed_bytes_are_refused_quickly() -> None:
    kind = ros1_type(JointState)
    good = kind.encode(JointState(Header(Time(1, 2), "f"), ["a"], [1.0]))
    started = time.monotonic()
    with pytest.raises(Ros1CodecError):
        kind.decode(good[:-3])  # truncated
    with pytest.raises(Ros1CodecError):
        kind.decode(good + b"\x00")  # left over
    with pytest.raises(Ros1CodecError, match="overruns"):
        kind.decode(good[:12] + b"\xff\xff\xff\x7f" + good[16:])  # a 2 GiB frame id
    names_at = 12 + 4 + 1  # seq, stamp, frame id "f"
    with pytest.raises(Ros1CodecError, match="overruns"):
        kind.decode(good[:names_at] + b"\xff\xff\xff\x0f" + good[names_at + 4 :])
    assert time.monotonic() - started < 1.0


def test_values_that_do_not_fit_are_refused() -> None:
    kind = ros1_type(JointState)
    with pytest.raises(Ros1CodecError):
        kind.encode(JointState(Header(Time(-1, 0), "f")))  # ROS 1 time is unsigned
    with pytest.raises(Ros1CodecError):  # an int no float64 holds: OverflowError inside
        kind.encode(JointState(position=[10**400]))
