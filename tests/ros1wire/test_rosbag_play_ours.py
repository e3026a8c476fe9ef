"""Debian's ``rosbag play`` plays a ROS 1 bag that robomodel wrote, on a
master robomodel runs, to a robomodel subscriber: the md5sums, definitions and bytes of the
bag are what ROS 1's own player accepts and sends."""

from __future__ import annotations

from pathlib import Path

import yaml

from robomodel.bag import Ros1BagWriter
from robomodel.runtime.msg import JointState, serialize
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled


def _write_bag(path: Path, count: int) -> None:
    writer = Ros1BagWriter(path)
    writer.add_topic("/joint_states", JointState, ())
    for k in range(count):
        msg = JointState(name=["joint1", "joint2"], position=[0.01 * k, -0.02 * k])
        t_ns = 1_700_000_000_000_000_000 + k * 50_000_000  # 20 Hz
        writer.write("/joint_states", serialize(msg), t_ns, t_ns, k)
    writer.close()


def test_debian_rosbag_plays_a_robomodel_bag_to_robomodel(ros1: Ros1, tmp_path: Path) -> None:
    bag = tmp_path / "ours.bag"
    _write_bag(bag, 80)  # 4 s of /joint_states
    ros1.robomodel("master", "-p", str(ros1.port))
    ros1.wait_for_master()
    echo = ros1.robomodel(
        "topic", "echo", "/joint_states", "sensor_msgs/msg/JointState", "--count", "3",
        "--bus", "ros1", log=tmp_path / "echo.log",
    )  # fmt: skip
    ros1.until(
        lambda: "/joint_states" in ros1.names("topics") or echo.poll() is not None,
        "the echo's subscription",
        timeout_s=scaled(30),
    )
    play = ros1.start(["/usr/bin/rosbag", "play", str(bag)], log=tmp_path / "play.log")
    ros1.until(lambda: echo.poll() is not None, "three messages echoed", timeout_s=60)
    ros1.stop(play)
    assert echo.returncode == 0, (tmp_path / "echo.log").read_text()
    docs = [
        yaml.safe_load(doc)
        for doc in (tmp_path / "echo.log").read_text().split("---")
        if doc.strip().startswith(("header", "name"))
    ]
    assert len(docs) == 3
    for doc in docs:
        k = round(doc["position"][0] / 0.01)
        assert doc["name"] == ["joint1", "joint2"]
        assert doc["position"] == [0.01 * k, -0.02 * k]
