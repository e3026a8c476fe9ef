"""State publishing of a launch file against ROS 1 itself: the same launch file (robot
description + joint_state_publisher with ``~zeros`` + robot_state_publisher) under Debian's
roslaunch (roscore, the C++ robot_state_publisher, the Python joint_state_publisher) and under
``robomodel launch``; the transforms on /tf and /tf_static must be the same."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path
from typing import Any

import pytest
import yaml

from robomodel.description.packages import PackageIndex
from robomodel.xacro import process_file
from tests.conftest import EXAMPLES, ROBOMODEL, unique_domain
from tests.launch.ros1.conftest import ROSLAUNCH
from tests.timing import scaled

pytest.importorskip("zenoh")

LAUNCH = """<launch>
  <param name="robot_description" textfile="{urdf}"/>
  <node name="joint_state_publisher" pkg="joint_state_publisher" type="joint_state_publisher">
    <rosparam param="zeros">{{shoulder_lift_joint: -1.2, elbow_joint: 0.7, wrist_2_joint: 0.3}}</rosparam>
  </node>
  <node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher">
    <param name="publish_frequency" value="20"/>
  </node>
</launch>
"""


def _transforms(text: str) -> dict[str, tuple[str, tuple[float, ...]]]:
    """child -> (parent, x y z qx qy qz qw) of the first TFMessage in ``topic echo`` output."""
    message = yaml.safe_load(text.split("---")[0])
    out = {}
    for item in message["transforms"]:
        t, r = item["transform"]["translation"], item["transform"]["rotation"]
        values = (t["x"], t["y"], t["z"], r["x"], r["y"], r["z"], r["w"])
        out[item["child_frame_id"].lstrip("/")] = (item["header"]["frame_id"].lstrip("/"), values)
    return out


def _reference(launch: Path, home: Path) -> tuple[str, str]:
    if not Path(ROSLAUNCH).exists():
        pytest.fail("Debian's roslaunch is missing: apt-get install python3-roslaunch")
    port = str(11400 + os.getpid() % 500)
    env = {
        "PATH": "/usr/bin:/bin",
        "HOME": str(home),
        "ROS_HOME": str(home / ".ros"),
        "ROS_MASTER_URI": f"http://localhost:{port}",
        "ROS_PACKAGE_PATH": "/usr/share",
        "LANG": "C.UTF-8",
    }
    proc = subprocess.Popen(
        [ROSLAUNCH, "-p", port, str(launch)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=env,
        start_new_session=True,
    )
    try:
        outputs = []
        for topic in ("/tf_static", "/tf"):
            deadline = time.monotonic() + scaled(60)
            while True:
                echo = subprocess.run(
                    ["/usr/bin/rostopic", "echo", "-n", "1", topic],
                    capture_output=True,
                    text=True,
                    env=env,
                    timeout=scaled(60),
                )
                if echo.returncode == 0 and "transforms" in echo.stdout:
                    outputs.append(echo.stdout)
                    break
                assert time.monotonic() < deadline, echo.stderr
                time.sleep(0.5)
        return outputs[0], outputs[1]
    finally:
        os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(scaled(30))
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def _ours(launch: Path) -> tuple[str, str]:
    domain = unique_domain()
    proc = subprocess.Popen(
        [*ROBOMODEL, "launch", str(launch), "--headless", "--domain-id", domain],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        outputs = []
        for topic in ("/tf_static", "/tf"):
            echo = subprocess.run(
                [*ROBOMODEL, "topic", "echo", topic, "--once", "--domain-id", domain],
                capture_output=True,
                text=True,
                timeout=scaled(90),
            )
            assert echo.returncode == 0, echo.stderr
            outputs.append(echo.stdout)
        return outputs[0], outputs[1]
    finally:
        proc.terminate()
        proc.wait(scaled(30))


def _close(ours: dict[str, Any], reference: dict[str, Any]) -> None:
    assert sorted(ours) == sorted(reference)
    for child, (parent, values) in reference.items():
        assert ours[child][0] == parent, child
        assert ours[child][1] == pytest.approx(values, abs=1e-9), child


def test_tf_of_a_launch_file_matches_ros1(tmp_path: Path) -> None:
    index = PackageIndex(package_paths=[EXAMPLES], use_environment=False)
    source = EXAMPLES / "ur5_description" / "urdf" / "ur5.urdf.xacro"
    urdf = tmp_path / "ur5.urdf"
    urdf.write_text(process_file(str(source), package_index=index).toxml())
    launch = tmp_path / "state.launch"
    launch.write_text(LAUNCH.format(urdf=urdf))
    (tmp_path / "home").mkdir()
    ref_static, ref_tf = _reference(launch, tmp_path / "home")
    our_static, our_tf = _ours(launch)
    reference_static = _transforms(ref_static)
    assert "world" in {parent for parent, _ in reference_static.values()}  # world_joint is fixed
    _close(_transforms(our_static), reference_static)
    reference_tf = _transforms(ref_tf)
    assert len(reference_tf) == 6  # the six revolute joints, zeros applied by joint_state_publisher
    _close(_transforms(our_tf), reference_tf)
