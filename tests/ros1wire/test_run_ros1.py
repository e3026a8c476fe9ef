"""``robomodel run PKG EXECUTABLE [ARGS]`` on a ROS 1 graph, each node checked by its effect
through Debian's ``rostopic``, ``rosparam``, ``rosnode`` and ``rosservice``: rosrun's arguments
(``__name:=``, ``__ns:=``, ``_param:=``, ``from:=to``), controller_manager's ROS 1 script, the
type lookup and ROS 1 field names of ``robomodel service call``."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import urllib.request
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import EXAMPLES
from tests.ros1wire.conftest import Ros1, free_port
from tests.ros1wire.test_debian_ros1 import PLANAR, _echo, _launch, _transforms
from tests.timing import scaled

ROSSERVICE = "/usr/bin/rosservice"
DEFINITIONS = Path(__file__).parents[2] / "src/robomodel/runtime/transport/ros1/definitions"


def _master(ros1: Ros1) -> None:
    ros1.robomodel("master", "--port", str(ros1.port))
    ros1.wait_for_master()


def _node_up(ros1: Ros1, name: str, proc: subprocess.Popen[str]) -> None:
    def up() -> bool:
        assert proc.poll() is None, f"{name} ended with {proc.returncode}"
        return name in ros1.names("nodes")

    ros1.until(up, f"the master lists {name}")
    assert name in ros1.run("/usr/bin/rosnode", "list").stdout.split()


def _terminate(proc: subprocess.Popen[str]) -> int:
    os.killpg(proc.pid, signal.SIGTERM)
    return proc.wait(scaled(30))


def test_run_static_transform_publisher_both_forms_and_tf_echo(ros1: Ros1, tmp_path: Path) -> None:
    _master(ros1)
    euler = ros1.robomodel(
        "run", "tf2_ros", "static_transform_publisher", "1", "2", "3", "0", "0", "0",
        "world", "tool", "__name:=euler_stp",
    )  # fmt: skip
    quaternion = ros1.robomodel(
        "run", "tf2_ros", "static_transform_publisher", "0", "0", "0.5", "0", "0", "0.7071068",
        "0.7071068", "tool", "camera", "__name:=quat_stp", "__ns:=/sensors",
    )  # fmt: skip
    _node_up(ros1, "/euler_stp", euler)
    _node_up(ros1, "/sensors/quat_stp", quaternion)
    seen: dict[str, Any] = {}
    ros1.until(
        lambda: len(seen.update(_transforms(_echo(ros1, "/tf_static"))) or seen) >= 2,
        "both transforms on /tf_static",
    )  # each latched publisher delivers its own message
    assert seen["tool"] == ("world", pytest.approx((1, 2, 3, 0, 0, 0, 1)))
    assert seen["camera"] == ("tool", pytest.approx((0, 0, 0.5, 0, 0, 0.7071068, 0.7071068)))
    echo = ros1.start([*_robomodel(), "run", "tf", "tf_echo", "world", "camera"],
                      log=tmp_path / "echo.log")  # fmt: skip
    ros1.until(lambda: "Translation" in (tmp_path / "echo.log").read_text(), "tf_echo prints")
    assert "- Translation: [1.000, 2.000, 3.500]" in (tmp_path / "echo.log").read_text()
    assert _terminate(echo) == 0
    assert _terminate(euler) == 0 and _terminate(quaternion) == 0
    # tf's static_transform_publisher: x y z qx qy qz qw frame child period_in_ms, on /tf
    periodic = ros1.robomodel(
        "run", "tf", "static_transform_publisher", "0", "0", "1", "0", "0", "0", "1",
        "world", "marker", "50",
    )  # fmt: skip
    assert _transforms(_echo(ros1, "/tf"))["marker"] == (
        "world",
        pytest.approx((0, 0, 1, 0, 0, 0, 1)),
    )
    assert _terminate(periodic) == 0


def _robomodel() -> list[str]:
    return [sys.executable, "-m", "robomodel.cli.main"]


def test_run_state_publishers_with_rosrun_arguments(ros1: Ros1, tmp_path: Path) -> None:
    _master(ros1)
    assert (
        ros1.run("/usr/bin/rosparam", "set", "/robot_description", "-t", str(PLANAR)).returncode
        == 0
    )
    jsp = ros1.robomodel(
        "run", "joint_state_publisher", "joint_state_publisher", "_rate:=7",
        "joint_states:=/planar/joint_states", "__name:=jsp",
    )  # fmt: skip
    rsp = ros1.robomodel(
        "run", "robot_state_publisher", "state_publisher",  # ROS 1's old name
        "joint_states:=/planar/joint_states", "__name:=robot_state_publisher",
    )  # fmt: skip
    _node_up(ros1, "/jsp", jsp)
    _node_up(ros1, "/robot_state_publisher", rsp)
    rate = ros1.run("/usr/bin/rosparam", "get", "/jsp/rate")
    assert rate.stdout.strip() == "7", rate.stderr  # _rate:=7 is ~rate, an int
    states = _echo(ros1, "/planar/joint_states")
    assert {"joint_1", "joint_2", "joint_3"} <= set(states["name"])
    assert {"link_1", "link_2"} <= set(_transforms(_echo(ros1, "/tf")))
    info = ros1.run("/usr/bin/rostopic", "info", "/planar/joint_states").stdout
    assert "/jsp" in info and "/robot_state_publisher" in info
    # rviz -d: the browser viewer serves the robot
    port = free_port()
    config = EXAMPLES / "gripper_description/urdf/urdf.rviz"
    rviz = ros1.robomodel("run", "--no-browser", "--port", str(port), "rviz", "rviz", "-d",
                          str(config))  # fmt: skip
    ros1.until(lambda: _serves(port) or rviz.poll() is not None, "the viewer serves")
    assert rviz.poll() is None
    # 143: SIGTERM came while the viewer was still being set up (ended through its cleanup)
    assert _terminate(rviz) in (0, 143)
    assert _terminate(jsp) == 0 and _terminate(rsp) == 0
    # joint_state_publisher_gui: the viewer's sliders publish the joints
    gui_port = free_port()
    gui = ros1.robomodel(
        "run", "--no-browser", "--port", str(gui_port), "joint_state_publisher_gui",
        "joint_state_publisher_gui",
    )  # fmt: skip
    ros1.until(lambda: _serves(gui_port) or gui.poll() is not None, "the sliders are served")
    assert {"joint_1", "joint_2", "joint_3"} <= set(_echo(ros1, "/joint_states")["name"])
    assert "/joint_state_publisher" in ros1.run("/usr/bin/rosnode", "list").stdout.split()
    assert _terminate(gui) in (0, 143)


def _serves(port: int) -> bool:
    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=scaled(2)) as reply:
            return bool(reply.status == 200)
    except OSError:
        return False


def test_run_xacro_prints_the_expansion_and_unknown_names_get_one_line(ros1: Ros1) -> None:
    _master(ros1)
    source = EXAMPLES / "rrbot_description/urdf/rrbot.xacro"
    reference = ros1.robomodel_run("xacro", str(source))
    for executable in ("xacro", "xacro.py"):
        ours = ros1.robomodel_run("run", "xacro", executable, str(source))
        assert ours.returncode == 0, ours.stderr
        assert ours.stdout == reference.stdout and "<robot" in ours.stdout
    for argv, said in (
        (["contrller_manager", "spawner"], "did you mean 'controller_manager'?"),
        (["tf2_ros", "static_transform_publsher"], "did you mean 'static_transform_publisher'"),
    ):
        done = ros1.robomodel_run("run", *argv)
        assert done.returncode == 2
        assert len(done.stderr.strip().splitlines()) == 1 and said in done.stderr, done.stderr


# -- controller_manager and service call against seed 000's rrbot_control ---------------------


def _generated_messages(work: Path) -> Path:
    """controller_manager_msgs for Debian's rosservice (Debian ships no such package):
    genpy's generators run on the Noetic definitions robomodel speaks."""
    package = work / "controller_manager_msgs"
    source = DEFINITIONS / "controller_manager_msgs"
    for kind in ("msg", "srv"):
        (package / kind).mkdir(parents=True)
        files = sorted(str(f) for f in (source / kind).glob(f"*.{kind}"))
        tool = f"/usr/lib/genpy/gen{kind}_py.py"
        base = [
            "/usr/bin/python3",
            tool,
            "-p",
            "controller_manager_msgs",
            "-o",
            str(package / kind),
        ]
        include = [f"-Icontroller_manager_msgs:{source / 'msg'}"]
        subprocess.run([*base, *include, *files], check=True, capture_output=True)
        subprocess.run([*base, "--initpy"], check=True, capture_output=True)
    (package / "__init__.py").write_text("")
    return work


def _rosservice(ros1: Ros1, generated: Path, *argv: str) -> subprocess.CompletedProcess[str]:
    env = {**ros1.env, "PYTHONPATH": str(generated)}
    return subprocess.run(
        [ROSSERVICE, *argv], capture_output=True, text=True, env=env, timeout=scaled(60)
    )


def _response(stdout: str) -> Any:
    """The reply block of ``robomodel service call``."""
    return yaml.safe_load(stdout.split("):\n", 1)[1])


BOX = """<robot name="box">
  <link name="box_link">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
  </link>
</robot>
"""


def _line(text: str, word: str) -> str:
    return next((line for line in text.splitlines() if word in line), "")


_ROS1_STATES = {"active": "running", "inactive": "stopped", "unconfigured": "initialized"}


def _cm(ros1: Ros1, *argv: str) -> subprocess.CompletedProcess[str]:
    return ros1.robomodel_run("run", "controller_manager", "controller_manager", *argv,
                              "__ns:=/rrbot")  # fmt: skip


def test_controller_manager_script_and_service_call_on_seed_000_rrbot(
    ros1: Ros1, tmp_path: Path
) -> None:
    world, control = tmp_path / "world.log", tmp_path / "control.log"
    _launch(
        ros1, world, "rrbot_gazebo", "rrbot_world.launch", "gui:=false", "--ros1-master",
        until="Successfully spawned entity",
    )  # fmt: skip
    _launch(ros1, control, "rrbot_control", "rrbot_control.launch",
            until="Started controllers: joint_state_controller")  # fmt: skip
    listed = _cm(ros1, "list")
    assert listed.returncode == 0, listed.stderr
    assert sorted(listed.stdout.splitlines()) == [
        "'joint1_position_controller' - 'hardware_interface::EffortJointInterface' ( running )",
        "'joint2_position_controller' - 'hardware_interface::EffortJointInterface' ( running )",
        "'joint_state_controller' - 'hardware_interface::JointStateInterface' ( running )",
    ]
    stopped = _cm(ros1, "stop", "joint2_position_controller")
    assert stopped.stdout == "Stopped ['joint2_position_controller'] successfully\n"
    killed = _cm(ros1, "kill", "joint1_position_controller")
    assert killed.stdout.splitlines() == [
        "Stopped ['joint1_position_controller'] successfully",
        "Unloaded 'joint1_position_controller' successfully",
    ]
    # Debian's rosservice and robomodel's service call (no type given) read the same states
    generated = _generated_messages(tmp_path / "gen")
    theirs = _rosservice(ros1, generated, "call", "/rrbot/controller_manager/list_controllers")
    assert theirs.returncode == 0, theirs.stderr
    ours = ros1.robomodel_run("service", "call", "/rrbot/controller_manager/list_controllers")
    assert ours.returncode == 0, ours.stderr
    their_states = {
        c["name"]: (c["state"], c["type"]) for c in yaml.safe_load(theirs.stdout)["controller"]
    }
    our_states = {
        c["name"]: (_ROS1_STATES[c["state"]], c["type"])
        for c in _response(ours.stdout)["controller"]
    }
    assert our_states == their_states
    claims = {
        c["name"]: c["claimed_resources"] for c in yaml.safe_load(theirs.stdout)["controller"]
    }
    assert claims["joint2_position_controller"] == []  # stopped: ROS 2 claims nothing
    missing = _cm(ros1, "load", "no_such_controller")
    assert missing.returncode == 1 and missing.stdout == "Error when loading 'no_such_controller'\n"
    assert their_states["joint2_position_controller"][0] == "stopped"
    assert "joint1_position_controller" not in their_states
    spawned = _cm(ros1, "spawn", "joint1_position_controller")
    assert spawned.stdout.splitlines() == [
        "Loaded 'joint1_position_controller'",
        "Started ['joint1_position_controller'] successfully",
    ]
    # ROS 1 field names in the request: start_controllers, timeout in seconds
    switch = ros1.robomodel_run(
        "service", "call", "/rrbot/controller_manager/switch_controller",
        "{start_controllers: [joint2_position_controller], stop_controllers: [], "
        "strictness: 2, timeout: 1.5}",
    )  # fmt: skip
    assert switch.returncode == 0 and _response(switch.stdout)["ok"] is True, switch.stderr
    running = _rosservice(ros1, generated, "call", "/rrbot/controller_manager/list_controllers")
    controllers = yaml.safe_load(running.stdout)["controller"]
    states = {c["name"]: c["state"] for c in controllers}
    assert states == dict.fromkeys(states, "running") and len(states) == 3
    claims = {c["name"]: c["claimed_resources"] for c in controllers}
    assert claims["joint2_position_controller"] == [
        {"hardware_interface": "hardware_interface::EffortJointInterface", "resources": ["joint2"]}
    ]
    # std_srvs/Empty, type looked up by both tools; time fields as secs/nsecs
    assert _rosservice(ros1, generated, "type", "/gazebo/pause_physics").stdout.strip() == (
        "std_srvs/Empty"
    )
    assert ros1.robomodel_run("service", "type", "/gazebo/pause_physics").stdout == (
        "std_srvs/srv/Empty\n"
    )
    paused = _rosservice(ros1, generated, "call", "/gazebo/pause_physics")
    unpaused = ros1.robomodel_run("service", "call", "/gazebo/unpause_physics")
    assert paused.returncode == 0 and unpaused.returncode == 0, unpaused.stderr
    assert paused.stdout.strip() == "" and unpaused.stdout.rstrip().endswith("{}")
    wrench = ros1.robomodel_run(
        "service", "call", "/gazebo/apply_body_wrench",
        "{body_name: 'rrbot::link3', wrench: {force: {x: 1.0}}, start_time: {secs: 0, nsecs: 0}, "
        "duration: {secs: 0, nsecs: 200000000}}",
    )  # fmt: skip
    assert wrench.returncode == 0, wrench.stderr
    assert "nanosec: 200000000" in wrench.stdout
    # ROS 1's spawner by run: loads and starts; on SIGINT stops and unloads (its shutdown hook)
    assert _cm(ros1, "kill", "joint2_position_controller").returncode == 0
    spawner = ros1.robomodel(
        "run", "controller_manager", "spawner", "joint2_position_controller", "__ns:=/rrbot"
    )
    ros1.until(lambda: "( running )" in _line(_cm(ros1, "list").stdout, "joint2"), "spawned")
    assert ros1.stop(spawner) == 0
    assert "joint2" not in _cm(ros1, "list").stdout
    # ROS 1's unspawner: the controller is gone while it runs, back when it ends
    unspawner = ros1.robomodel(
        "run", "controller_manager", "unspawner", "joint1_position_controller", "__ns:=/rrbot"
    )
    ros1.until(lambda: "joint1" not in _cm(ros1, "list").stdout, "unspawned")
    assert ros1.stop(unspawner) == 0
    assert "( running )" in _line(_cm(ros1, "list").stdout, "joint1")
    # gazebo_ros spawn_model: a second model in the world
    box = tmp_path / "box.urdf"
    box.write_text(BOX)
    spawned_box = ros1.robomodel_run(
        "run", "gazebo_ros", "spawn_model", "-urdf", "-file", str(box), "-model", "box", "-z", "2"
    )
    assert spawned_box.returncode == 0, spawned_box.stderr
    world = ros1.robomodel_run("service", "call", "/gazebo/get_world_properties")
    assert "box" in _response(world.stdout)["model_names"], world.stdout
    # without __ns: ROS 1's script waits for /controller_manager; robomodel says where they are
    hint = tmp_path / "hint.log"
    waiting = ros1.robomodel("run", "controller_manager", "controller_manager", "list", log=hint)
    ros1.until(lambda: "waiting for service" in hint.read_text(), "the waiting line")
    assert "controller managers on the graph are in: /rrbot (give __ns:=NS)" in hint.read_text()
    assert ros1.stop(waiting) == 0
    bad = _cm(ros1, "lst")
    assert bad.returncode == 2 and "did you mean 'list'" in bad.stderr
