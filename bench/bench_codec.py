"""Message codecs: robomodel's generated CDR (ROS 2) and ROS 1 codecs against rosbags'.

Run: ``.venv/bin/python bench/bench_codec.py [--rounds 7]``.

For talos' messages (a 32-joint JointState, a 44-transform TFMessage as robot_state_publisher
publishes it), encode and decode with robomodel (its message classes, CDR for the Zenoh wire,
ROS 1 serialization for TCPROS) and with rosbags (its message classes, ``serialize_cdr`` /
``deserialize_cdr`` and ``serialize_ros1`` / ``deserialize_ros1``), interleaved round by
round; prints the median µs per message and the ratio rosbags / robomodel. Both sides produce
the same bytes (checked before timing).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))


def _messages() -> dict[str, Any]:
    from robomodel.runtime.msg import (
        Header,
        JointState,
        Quaternion,
        TFMessage,
        Time,
        Transform,
        TransformStamped,
        Vector3,
    )

    joints = JointState(
        Header(Time(1795000000, 123456789), ""),
        [f"joint_{i}" for i in range(32)],
        [0.01 * i for i in range(32)],
        [0.0] * 32,
        [],
    )
    transforms = TFMessage(
        [
            TransformStamped(
                Header(Time(1795000000, 123456789), f"link_{i}"),
                f"link_{i + 1}",
                Transform(Vector3(0.1 * i, 0.2, 0.3), Quaternion(0.0, 0.0, 0.38268343, 0.92387953)),
            )
            for i in range(44)
        ]
    )
    return {
        "JointState (32 joints)": joints,
        "TFMessage (44 transforms)": transforms,
        **_generated_messages(),
    }


def _generated_messages() -> dict[str, Any]:
    """Types robomodel has no hand-written class for: built from rosbags' Jazzy definitions."""
    from robomodel.runtime.msg import get_message_type, message_from_dict

    header = {"stamp": {"sec": 1795000000, "nanosec": 123456789}, "frame_id": "camera"}
    image = message_from_dict(
        get_message_type("sensor_msgs/msg/Image"),
        {"header": header, "height": 48, "width": 64, "encoding": "rgb8", "step": 192,
         "data": [i % 256 for i in range(48 * 192)]},
    )  # fmt: skip
    marker = message_from_dict(
        get_message_type("visualization_msgs/msg/Marker"),
        {"header": header, "ns": "path", "type": 8,
         "points": [{"x": 0.1 * i, "y": 0.2, "z": 0.3} for i in range(50)],
         "colors": [{"r": 1.0, "g": 0.5, "b": 0.0, "a": 1.0}] * 50},
    )  # fmt: skip
    return {"Image 64x48 rgb8 (generated)": image, "Marker, 50 points (generated)": marker}


def _time(function: Callable[[], Any], repeat: int) -> float:
    start = time.perf_counter()
    for _ in range(repeat):
        function()
    return (time.perf_counter() - start) / repeat * 1e6


def _cases(label: str, msg: Any) -> list[tuple[str, Callable[[], Any], Callable[[], Any]]]:
    """(what, robomodel's call, rosbags' call) for one message."""
    from rosbags.typesys import Stores, get_typestore

    from robomodel.runtime.msg import deserialize, serialize
    from robomodel.runtime.transport.ros1.ros1_types import _store, ros1_type

    name = type(msg).__typename__
    ros2 = get_typestore(Stores.ROS2_JAZZY)
    ros1 = _store()  # rosbags' Noetic store plus the vendored definitions (tf2_msgs, ...)
    cdr = serialize(msg)
    theirs2 = ros2.deserialize_cdr(cdr, name)
    assert bytes(ros2.serialize_cdr(theirs2, name)) == cdr, label
    kind = ros1_type(type(msg))
    raw1 = kind.encode(msg, 0)
    theirs1 = ros1.deserialize_ros1(raw1, name)
    assert bytes(ros1.serialize_ros1(theirs1, name)) == raw1, label
    return [
        ("CDR encode", lambda: serialize(msg), lambda: ros2.serialize_cdr(theirs2, name)),
        (
            "CDR decode",
            lambda: deserialize(cdr, type(msg)),
            lambda: ros2.deserialize_cdr(cdr, name),
        ),
        ("ROS 1 encode", lambda: kind.encode(msg, 0), lambda: ros1.serialize_ros1(theirs1, name)),
        ("ROS 1 decode", lambda: kind.decode(raw1), lambda: ros1.deserialize_ros1(raw1, name)),
    ]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--repeat", type=int, default=2000)
    parser.add_argument("--only", default="", help="only the messages whose label has this text")
    args = parser.parse_args()
    print("| message | codec | robomodel | rosbags | rosbags / robomodel |")
    print("|---|---|---|---|---|")
    for label, msg in _messages().items():
        if args.only not in label:
            continue
        for what, ours, theirs in _cases(label, msg):
            a: list[float] = []
            b: list[float] = []
            for _ in range(args.rounds):  # interleaved
                a.append(_time(ours, args.repeat))
                b.append(_time(theirs, args.repeat))
            mine, other = statistics.median(a), statistics.median(b)
            print(f"| {label} | {what} | {mine:.1f} µs | {other:.1f} µs | {other / mine:.2f} |")


if __name__ == "__main__":
    main()
