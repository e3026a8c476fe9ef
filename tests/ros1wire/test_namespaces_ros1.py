"""A ROS 1 launch with ``<group ns="r1">`` and ``<group ns="r2">`` (robot_description,
tf_prefix, joint_state_publisher_gui and robot_state_publisher in each), robomodel as the master:
Debian's ``rostopic list`` and robomodel's ``topic list`` show the namespaced topics, and /tf
carries each robot's prefixed frames, as roscpp's name resolution gives with real nodes."""

from __future__ import annotations

import time
from pathlib import Path

import yaml

from tests.launch.test_namespaces import ARM
from tests.ros1wire.conftest import Ros1
from tests.ros1wire.test_debian_ros1 import _launch
from tests.timing import scaled

GROUP = """  <group ns="{ns}">
    <param name="robot_description" textfile="{urdf}"/>
    <param name="tf_prefix" value="{ns}"/>
    <node pkg="joint_state_publisher_gui" type="joint_state_publisher_gui" name="jsp_gui"/>
    <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
  </group>
"""


def test_group_ns_gives_namespaced_topics_and_prefixed_frames(ros1: Ros1, tmp_path: Path) -> None:
    urdf = tmp_path / "arm.urdf"
    urdf.write_text(ARM)
    launch = tmp_path / "two.launch"
    groups = "".join(GROUP.format(ns=ns, urdf=urdf) for ns in ("r1", "r2"))
    launch.write_text(f"<launch>\n{groups}</launch>\n")
    log = tmp_path / "launch.log"
    _launch(ros1, log, str(launch), "--ros1-master", ros1.uri)
    topics = set(ros1.run("/usr/bin/rostopic", "list").stdout.split())
    assert {"/r1/joint_states", "/r2/joint_states", "/tf", "/tf_static"} <= topics, topics
    assert "/joint_states" not in topics
    ours = set(ros1.robomodel_run("topic", "list").stdout.split())
    assert {"/r1/joint_states", "/r2/joint_states", "/tf"} <= ours and "/joint_states" not in ours
    info = ros1.run("/usr/bin/rostopic", "info", "/r1/joint_states").stdout
    assert "/r1/jsp_gui" in info and "/r1/rsp" in info  # published there, and subscribed
    deadline = time.monotonic() + scaled(60)
    frames: set[str] = set()
    parents: set[str] = set()
    while not {"r1/link_1", "r2/link_1"} <= frames:
        assert time.monotonic() < deadline, f"frames on /tf: {frames}"
        echo = ros1.run("/usr/bin/rostopic", "echo", "-n", "20", "/tf", timeout=scaled(60))
        for doc in yaml.safe_load_all(echo.stdout.replace("\n---", "\n---\n")):
            for t in (doc or {}).get("transforms", ()):
                frames.add(t["child_frame_id"])
                parents.add(t["header"]["frame_id"])
    assert frames == {"r1/link_1", "r2/link_1"} and parents == {"r1/base", "r2/base"}
