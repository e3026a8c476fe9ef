"""``bag record -a`` of types robomodel has no hand-written class for (a common interface
from rosbags' store, a custom type of a test interface package): the bag stores their
definitions, as ros2 bag does, and rosbags reads the messages back equal from the bag alone."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled

from .conftest import flushed_counts, stop

IMAGE = (
    "{height: 2, width: 2, encoding: rgb8, step: 6, data: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]}"
)


def _package(root: Path) -> Path:
    package = root / "ws" / "my_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="3"><name>my_msgs</name><version>0.0.0</version></package>'
    )
    (package / "msg" / "Reading.msg").write_text("float64 value\nstring unit\nint16[3] raw\n")
    return root / "ws"


def test_record_all_stores_definitions_rosbags_reads_back(tmp_path: Path) -> None:
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    env = {**os.environ, "ROS_PACKAGE_PATH": str(_package(tmp_path))}
    domain = unique_domain()
    bus = ("--domain-id", domain)

    def start(*argv: str) -> subprocess.Popen[str]:
        return subprocess.Popen(
            [*ROBOMODEL, *argv, *bus], env=env, text=True,
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
        )  # fmt: skip

    pubs = [
        start("topic", "pub", "/img", "sensor_msgs/msg/Image", IMAGE, "-r", "20"),
        start("topic", "pub", "/reading", "my_msgs/msg/Reading",
              "{value: 2.5, unit: bar, raw: [1, -2, 3]}", "-r", "20"),
    ]  # fmt: skip
    folder = tmp_path / "bag"
    record = start("bag", "record", "-a", "-o", str(folder))
    try:
        deadline = time.monotonic() + scaled(120)
        # until messages of both topics are in the bag (a busy machine may connect one late)
        while min(flushed_counts(folder).get(t, 0) for t in ("/img", "/reading")) < 5:
            assert record.poll() is None, record.communicate()[1]
            assert time.monotonic() < deadline, f"no messages recorded in {scaled(120):.0f} s"
            time.sleep(0.3)
    finally:
        stop(record, signal.SIGINT)
        for pub in pubs:
            stop(pub)
    store = get_typestore(Stores.EMPTY)  # only what the bag says
    seen: dict[str, object] = {}
    with Reader(folder) as reader:
        for conn in reader.connections:
            store.register(get_types_from_msg(conn.msgdef.data, conn.msgtype))
        for conn, _, data in reader.messages():
            seen.setdefault(conn.topic, store.deserialize_cdr(data, conn.msgtype))
    image, reading = seen["/img"], seen["/reading"]
    assert (image.height, image.encoding, image.data.tolist()) == (2, "rgb8", list(range(1, 13)))  # type: ignore[attr-defined]
    assert (reading.value, reading.unit, reading.raw.tolist()) == (2.5, "bar", [1, -2, 3])  # type: ignore[attr-defined]
    jazzy = get_typestore(Stores.ROS2_JAZZY)
    with Reader(folder) as reader:
        types = {c.topic: c.msgtype for c in reader.connections}
        hashes = {c.topic: c.digest for c in reader.connections}
    assert types["/img"] == "sensor_msgs/msg/Image"
    assert hashes["/img"] == jazzy.hash_rihs01("sensor_msgs/msg/Image")
    info = subprocess.run([*ROBOMODEL, "bag", "info", str(folder)], env=env, text=True,
                          capture_output=True, timeout=scaled(60))  # fmt: skip
    assert info.returncode == 0 and "my_msgs/msg/Reading" in info.stdout, info.stderr
