"""The simulated simplebot_camera on a ROS 1 graph, seen by Debian's rostopic: the
openni_kinect plugin's topics and types, CameraInfo's K, and N messages at the sensor's
``update_rate`` (stamps in sim time: waiting for N messages, no timed assertion)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from tests.conftest import EXAMPLES
from tests.ros1wire.conftest import Ros1

pytest.importorskip("mujoco")

EXPECTED = {
    "/camera/rgb/image_raw": "sensor_msgs/Image",
    "/camera/rgb/camera_info": "sensor_msgs/CameraInfo",
    "/camera/depth/image_raw": "sensor_msgs/Image",
    "/camera/depth/camera_info": "sensor_msgs/CameraInfo",
    "/camera/depth/points": "sensor_msgs/PointCloud2",
}


def _documents(text: str) -> list[Any]:
    return [yaml.safe_load(d) for d in text.split("\n---") if d.strip()]


def test_debian_rostopic_sees_the_camera_topics_at_their_rate(ros1: Ros1, tmp_path: Path) -> None:
    ros1.roscore()
    log = tmp_path / "sim.log"
    sim = ros1.robomodel(
        "sim", str(EXAMPLES / "simplebot_description/urdf/simplebot_camera.urdf.xacro"),
        "--world", str(EXAMPLES / "simplebot_description/worlds/wall.world"),
        "--spawn", "0", "0", "0.076", "--headless", "--bus", "ros1", "--master", ros1.uri,
        log=log,
    )  # fmt: skip

    def listed() -> bool:
        assert sim.poll() is None, log.read_text()
        run = ros1.run("/usr/bin/rostopic", "list", "-v")
        return all(topic in run.stdout for topic in EXPECTED)

    ros1.until(listed, "the camera's topics", timeout_s=120)
    for topic, msg_type in EXPECTED.items():
        assert ros1.run("/usr/bin/rostopic", "type", topic).stdout.strip() == msg_type
    echo = ros1.run("/usr/bin/rostopic", "echo", "-n", "4", "/camera/rgb/camera_info")
    assert echo.returncode == 0, echo.stderr
    infos = _documents(echo.stdout)
    assert len(infos) == 4
    f = 320 / (2 * math.tan(1.3962634 / 2))  # the example's width and <horizontal_fov>
    assert infos[0]["K"] == pytest.approx([f, 0, 160.5, 0, f, 120.5, 0, 0, 1])
    assert infos[0]["header"]["frame_id"] == "camera_optical_link"
    stamps = [i["header"]["stamp"]["secs"] + i["header"]["stamp"]["nsecs"] * 1e-9 for i in infos]
    # <update_rate> 10, in sim time
    assert list(np.diff(stamps)) == pytest.approx([0.1] * 3, abs=1e-6)
    cloud = ros1.run("/usr/bin/rostopic", "echo", "-n", "1", "--noarr", "/camera/depth/points")
    (points,) = _documents(cloud.stdout)
    assert (points["width"], points["height"], points["point_step"]) == (320, 240, 32)
    assert points["fields"] == "<array type: sensor_msgs/PointField, length: 4>"  # --noarr
    assert points["header"]["frame_id"] == "camera_optical_link"
