"""robomodel's ROS 1 launch files on the ROS 1 wire, seen and driven by Debian's real ROS 1.

- robomodel as the master: rostopic, rosparam, rosnode and rosservice see a launch's nodes;
- a real roscore: the launch registers with it, and the C++ robot_state_publisher turns
  robomodel's /joint_states into the /tf robomodel's own publishes;
- the seeds' two-terminal rrbot workflow, its joint moved by Debian's ``rostopic pub``;
- rosbag records robomodel's topics and its playback drives a robomodel viewer;
- rviz under Xvfb draws the robot robomodel publishes (a screenshot, checked for its colours).
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any

import pytest
import yaml

from robomodel.runtime.msg import JointState
from tests.conftest import EXAMPLES
from tests.ros1wire.conftest import Ros1, has
from tests.ros1wire.rviz_window import rviz_until, xvfb
from tests.timing import scaled

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"


def _echo(ros1: Ros1, topic: str, timeout_s: float | None = None) -> Any:
    """The first message on ``topic`` as Debian's ``rostopic echo -n 1`` prints it."""
    timeout_s = scaled(30) if timeout_s is None else timeout_s
    deadline = time.monotonic() + timeout_s
    while True:
        echo = ros1.run("/usr/bin/rostopic", "echo", "-n", "1", topic, timeout=timeout_s)
        if echo.returncode == 0 and echo.stdout.strip():
            return yaml.safe_load(echo.stdout.split("\n---")[0])
        assert time.monotonic() < deadline, f"rostopic echo {topic}: {echo.stderr}"
        time.sleep(0.5)


def _transforms(message: Any) -> dict[str, tuple[str, tuple[float, ...]]]:
    out = {}
    for item in message["transforms"]:
        t, r = item["transform"]["translation"], item["transform"]["rotation"]
        values = (t["x"], t["y"], t["z"], r["x"], r["y"], r["z"], r["w"])
        out[item["child_frame_id"].lstrip("/")] = (item["header"]["frame_id"].lstrip("/"), values)
    return out


def _launch(ros1: Ros1, log: Path, *argv: str, until: str = "nodes running") -> None:
    proc = ros1.robomodel("launch", *argv, "--headless", log=log)
    ros1.until(lambda: until in log.read_text() or proc.poll() is not None, f"'{until}'")
    assert proc.poll() is None, log.read_text()


def test_debian_tools_see_a_launch_whose_master_robomodel_runs(ros1: Ros1, tmp_path: Path) -> None:
    log = tmp_path / "launch.log"
    _launch(ros1, log, "gripper_description", "display.launch", "--ros1-master", ros1.uri)
    assert "started one (as roscore)" in log.read_text()
    states = _echo(ros1, "/joint_states")
    assert {"joint_1", "joint_2", "joint_3"} <= set(states["name"]) and "seq" in states["header"]
    frames = _transforms(_echo(ros1, "/tf"))
    assert {"link_1", "link_2"} <= set(frames)
    description = ros1.run("/usr/bin/rosparam", "get", "/robot_description")
    assert description.returncode == 0 and "planar_3dof" in description.stdout
    nodes = ros1.run("/usr/bin/rosnode", "list").stdout.split()
    assert {"/joint_state_publisher", "/robot_state_publisher"} <= set(nodes)
    info = ros1.run("/usr/bin/rosnode", "info", "/robot_state_publisher").stdout
    assert "/tf [tf2_msgs/TFMessage]" in info and "/joint_states [sensor_msgs/JointState]" in info
    assert "Pid: " in info and "TCPROS" in info
    topic = ros1.run("/usr/bin/rostopic", "info", "/joint_states").stdout
    assert "sensor_msgs/JointState" in topic and "/joint_state_publisher" in topic
    ours = ros1.robomodel_run("topic", "list")
    assert "/tf" in ours.stdout.split(), ours.stderr


def test_a_real_roscore_and_debian_s_cpp_robot_state_publisher(ros1: Ros1, tmp_path: Path) -> None:
    """The launch joins Debian's roscore (ROS_MASTER_URI is set); Debian's C++
    robot_state_publisher, remapped to /tf_cpp, turns robomodel's /joint_states into the same
    transforms robomodel's own robot_state_publisher puts on /tf."""
    ros1.roscore()
    log = tmp_path / "launch.log"
    _launch(ros1, log, "gripper_description", "display.launch")
    assert f"ROS 1 master at {ros1.uri}" in log.read_text()
    ros1.start(
        ["/usr/lib/robot_state_publisher/robot_state_publisher", "__name:=cpp_state_publisher",
         "/tf:=/tf_cpp", "/tf_static:=/tf_static_cpp"]
    )  # fmt: skip
    ours, theirs = _transforms(_echo(ros1, "/tf")), _transforms(_echo(ros1, "/tf_cpp"))
    assert set(ours) == set(theirs) and ours
    for child, (parent, values) in ours.items():
        assert theirs[child][0] == parent
        assert theirs[child][1] == pytest.approx(values, abs=1e-6), child
    # robomodel's commands on the real graph (ROS_MASTER_URI is set: the ROS 1 bus)
    value = ros1.robomodel_run("param", "get", "/robot_description")
    assert "planar_3dof" in value.stdout, value.stderr
    echo = ros1.robomodel_run("topic", "echo", "/tf_cpp", "--once")
    assert echo.returncode == 0 and "child_frame_id" in echo.stdout, echo.stderr
    tf = ros1.robomodel_run(
        "tf", "base_link", "gripper", "--once", "--timeout", f"{scaled(20):.1f}"
    )
    assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr
    nodes = ros1.robomodel_run("node", "list")
    assert "/cpp_state_publisher" in nodes.stdout.split(), nodes.stderr


def test_rostopic_pub_moves_the_rrbot_joint_of_the_two_terminal_workflow(
    ros1: Ros1, tmp_path: Path
) -> None:
    """Seed 000: roslaunch rrbot_gazebo rrbot_world.launch; roslaunch rrbot_control
    rrbot_control.launch; rostopic pub .../command: the joint goes there."""
    world, control = tmp_path / "world.log", tmp_path / "control.log"
    _launch(
        ros1, world, "rrbot_gazebo", "rrbot_world.launch", "gui:=false", "--ros1-master",
        until="Successfully spawned entity",
    )  # fmt: skip
    _launch(
        ros1, control, "rrbot_control", "rrbot_control.launch",
        until="Started controllers: joint_state_controller",
    )  # fmt: skip
    gain = ros1.run("/usr/bin/rosparam", "get", "/rrbot/joint1_position_controller/pid/p")
    assert float(gain.stdout) == 100.0
    services = ros1.run("/usr/bin/rosservice", "list").stdout.split()
    assert "/gazebo/pause_physics" in services
    assert "/rrbot/controller_manager/list_controllers" in services
    kind = ros1.run("/usr/bin/rosservice", "type", "/rrbot/controller_manager/switch_controller")
    assert kind.stdout.strip() == "controller_manager_msgs/SwitchController", kind.stderr
    pub = ros1.run(
        "/usr/bin/rostopic", "pub", "-1", "/rrbot/joint1_position_controller/command",
        "std_msgs/Float64", "data: 0.8",
    )  # fmt: skip
    assert pub.returncode == 0, pub.stderr
    deadline = time.monotonic() + scaled(30)
    while True:
        states = _echo(ros1, "/rrbot/joint_states")
        position = states["position"][states["name"].index("joint1")]
        if abs(position - 0.8) < 0.25:  # effort PID against gravity: near, off by the sag
            break
        assert time.monotonic() < deadline, f"joint1 at {position}"
    listed = ros1.robomodel_run("control", "list-controllers", "-c", "/rrbot/controller_manager")
    assert "joint1_position_controller" in listed.stdout and "active" in listed.stdout, (
        listed.stderr
    )
    paused = ros1.run("/usr/bin/rosservice", "call", "/gazebo/pause_physics")
    assert paused.returncode == 0, paused.stderr
    ours = ros1.robomodel_run("service", "call", "/gazebo/unpause_physics", "std_srvs/srv/Empty")
    assert ours.returncode == 0, ours.stderr


def _receive_after_recorder_joined(ros1: Ros1, topic: str, msg_type: Any, count: int) -> None:
    """Once ``rosbag record`` has subscribed to ``topic`` (the master says so), receive
    ``count`` of its messages here: the recorder, subscribed before, has them too. (A fixed
    4 s recording had fewer than 20 messages on a loaded machine.)"""
    import xmlrpc.client

    from robomodel.runtime import Context

    master = xmlrpc.client.ServerProxy(ros1.uri)

    def recorder_subscribed() -> bool:
        _, _, (_, subscribers, _) = master.getSystemState("/test")
        return any(
            t == topic and any(n.startswith("/record") for n in nodes) for t, nodes in subscribers
        )

    ros1.until(recorder_subscribed, "rosbag record subscribed", timeout_s=60)
    got: list[object] = []
    os.environ["ROS_IP"] = "127.0.0.1"
    try:
        with Context("ros1", master=ros1.uri) as ctx:
            ctx.create_node("count").create_subscription(msg_type, topic, got.append)
            ctx.spin(duration_s=scaled(60), until=lambda: len(got) >= count)
    finally:
        os.environ.pop("ROS_IP", None)
    assert len(got) >= count, f"{len(got)} messages on {topic}"


def test_rosbag_records_robomodel_topics_and_its_playback_drives_a_viewer(
    ros1: Ros1, tmp_path: Path
) -> None:
    from robomodel.viewer import RobotSource, Viewer, ViewerOptions
    from tests.viewer.conftest import wait_for

    ros1.robomodel("master", "--port", str(ros1.port))
    ros1.wait_for_master()
    robot = ros1.robomodel("publish-state", str(PLANAR), "--delta", "0.02", "--bus", "ros1")
    bag = tmp_path / "states.bag"
    record = ros1.start(["/usr/bin/rosbag", "record", "-O", str(bag), "/joint_states"])
    _receive_after_recorder_joined(ros1, "/joint_states", JointState, 40)
    ros1.stop(record)
    ros1.stop(robot)
    info = ros1.run("/usr/bin/rosbag", "info", "--yaml", str(bag))
    summary = yaml.safe_load(info.stdout)
    [topic] = summary["topics"]
    assert topic["topic"] == "/joint_states" and topic["type"] == "sensor_msgs/JointState"
    assert topic["messages"] > 20
    os.environ["ROS_IP"] = "127.0.0.1"
    viewer = Viewer(
        ViewerOptions(
            sources=(RobotSource(str(PLANAR)),), port=0, bus="ros1", master=ros1.uri, external=True
        )
    )
    viewer.start()
    try:
        # Played once the viewer subscribed, at half speed: the stamps of a second loop are
        # the first's, older than the buffer's newest, so only the first loop moves the robot
        # (as in RViz), and a loaded machine may take a while to look five times
        ros1.start(["/usr/bin/rosbag", "play", "-l", "--wait-for-subscribers", "-r", "0.5", str(bag)])  # fmt: skip
        wait_for(lambda: viewer.buffer.can_transform("base_link", "gripper"), what="/tf")
        seen = set()
        deadline = time.monotonic() + scaled(20)
        while len(seen) < 5:
            pose = viewer.buffer.lookup_transform("base_link", "gripper").translation_m
            seen.add(tuple(round(v, 4) for v in pose))
            assert time.monotonic() < deadline, seen
            time.sleep(0.1)
    finally:
        viewer.close()
        os.environ.pop("ROS_IP", None)


def _orange_pixels(png: Path) -> int:
    """Pixels of planar_3dof's orange links (rgba 1.0 0.55 0.0) under RViz's lighting."""
    import numpy as np
    from PIL import Image

    rgb = np.asarray(Image.open(png).convert("RGB")).astype(float)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return int(((r > 120) & (g > 0.3 * r) & (g < 0.8 * r) & (b < 0.3 * r)).sum())


RVIZ_CONFIG = """Panels: []
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz/Grid
      Name: Grid
      Enabled: true
    - Class: rviz/RobotModel
      Name: RobotModel
      Enabled: true
      Robot Description: robot_description
  Global Options:
    Fixed Frame: base_link
    Background Color: 48; 48; 48
  Views:
    Current:
      Class: rviz/Orbit
      Distance: 2.2
      Focal Point: {X: 0.7, Y: 0, Z: 0}
      Pitch: 0.3
      Yaw: 0.8
Window Geometry:
  Height: 700
  Width: 900
  X: 0
  Y: 0
"""


def test_rviz_under_xvfb_draws_the_robot_robomodel_publishes(ros1: Ros1, tmp_path: Path) -> None:
    if not (has("Xvfb") and Path("/usr/bin/rviz").exists()):
        pytest.fail("rviz and Xvfb are missing: tools/system-deps test installs them")

    display = xvfb(ros1, "1024x768x24")
    log = tmp_path / "launch.log"
    _launch(ros1, log, "gripper_description", "display.launch", "--ros1-master", ros1.uri)
    config = tmp_path / "robot.rviz"
    config.write_text(RVIZ_CONFIG)
    shot = rviz_until(ros1, config, display, tmp_path / "rviz.log",
                       lambda shot: _orange_pixels(shot) > 500, 60)  # fmt: skip
    kept = Path(os.environ.get("ROBOMODEL_SCREENSHOTS", str(tmp_path))) / "rviz_ros1.png"
    kept.parent.mkdir(parents=True, exist_ok=True)
    kept.write_bytes(shot.read_bytes())
    assert _orange_pixels(shot) > 500, f"no orange links in rviz's window ({kept})"


def _axis_green_pixels(png: Path) -> int:
    """Pixels of the TF display's green y axes (nothing else in the scene is green)."""
    import numpy as np
    from PIL import Image

    rgb = np.asarray(Image.open(png).convert("RGB")).astype(float)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return int(((g > 100) & (r < 0.5 * g) & (b < 0.5 * g)).sum())


def _robomodel_saved_config(ros1: Ros1, path: Path) -> None:
    """``robomodel view`` on the ROS 1 graph, with no -d: the Fixed Frame set, Save Config As
    ``path`` (what the page's File folder does). The launch runs the robot_state_publisher (a
    second one of that name would make the master shut the first down)."""
    from robomodel.viewer import RobotSource, Viewer, ViewerOptions
    from tests.viewer.conftest import wait_for

    os.environ["ROS_IP"] = "127.0.0.1"
    viewer = Viewer(
        ViewerOptions(
            sources=(RobotSource(str(PLANAR)),), port=0, bus="ros1", master=ros1.uri,
            external=True, state_publisher=False,
        )
    )  # fmt: skip
    viewer.start()
    try:
        wait_for(lambda: viewer.buffer.can_transform("base_link", "gripper"), what="/tf")
        viewer.fixed_dropdown.value = "base_link"
        assert viewer.config_panel.save(str(path)), viewer.config_panel.status.content
    finally:
        viewer.close()
        os.environ.pop("ROS_IP", None)


def test_rviz_opens_a_config_robomodel_saved_with_its_displays_and_fixed_frame(
    ros1: Ros1, tmp_path: Path
) -> None:
    """Debian's ``rviz -d`` opens the file robomodel's viewer saved (ROS 1 class
    names on a ROS 1 graph): the robot (RobotModel) and its frames' axes (TF) are drawn in the
    fixed frame, and rviz's log names no unknown display class and no missing frame."""
    from robomodel.viewer.rviz_config import read_rviz_file

    if not (has("Xvfb") and Path("/usr/bin/rviz").exists()):
        pytest.fail("rviz and Xvfb are missing: tools/system-deps test installs them")

    _launch(ros1, tmp_path / "launch.log", "gripper_description", "display.launch",
            "--ros1-master", ros1.uri)  # fmt: skip
    config = tmp_path / "saved.rviz"
    _robomodel_saved_config(ros1, config)
    saved = read_rviz_file(config)
    assert saved.fixed_frame == "base_link"
    assert [d.class_name for d in saved.displays] == ["rviz/Grid", "rviz/RobotModel", "rviz/TF"]
    display = xvfb(ros1, "1280x900x24")
    log = tmp_path / "rviz.log"
    shot = rviz_until(
        ros1, config, display, log,
        lambda shot: _orange_pixels(shot) > 500 and _axis_green_pixels(shot) > 50, 90,
    )  # fmt: skip
    kept = Path(os.environ.get("ROBOMODEL_SCREENSHOTS", str(tmp_path))) / "rviz_saved_config.png"
    kept.parent.mkdir(parents=True, exist_ok=True)
    kept.write_bytes(shot.read_bytes())
    assert _orange_pixels(shot) > 500, f"no robot in rviz's window ({kept})"
    assert _axis_green_pixels(shot) > 50, f"no TF axes in rviz's window ({kept})"
    text = log.read_text()
    for complaint in ("failed to load", "PluginlibFactory", "does not exist", "No transform"):
        assert complaint not in text, text
