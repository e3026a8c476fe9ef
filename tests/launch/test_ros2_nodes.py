"""ROS 2 nodes of launch files mapped onto robomodel: parameters as rcl resolves them, the
command lines of spawner and static_transform_publisher, and a control launch run in-process
(ros2_control_node + robot_state_publisher + spawners chained by OnProcessExit)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from robomodel.errors import RobomodelError
from robomodel.launch.model import NodeSpec, ParamSource
from robomodel.launch.nodes.ros2_control import controller_config_text, parse_ros2_spawner_args
from robomodel.launch.nodes.ros2_nodes import parse_ros2_static_transform_args
from robomodel.launch.nodes.ros2_params import node_parameters
from robomodel.launch.ros2.model import LaunchStep
from robomodel.runtime.param_files import parameters_from_file
from tests.conftest import EXAMPLES
from tests.timing import scaled

ARM = EXAMPLES / "two_link_arm"


def test_parameter_files_match_node_names_as_rcl(tmp_path: Path) -> None:
    """rcl_yaml_param_parser: /** for every node, * one token, ** any, names relative to /."""
    path = tmp_path / "p.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    use_sim_time: true\n    shared: 1\n"
        "rsp:\n  ros__parameters:\n    shared: 2\n    frame_prefix: a/\n"
        "/robots/*:\n  ros__parameters:\n    wild: one\n"
        "/**/deep:\n  ros__parameters:\n    nested: {x: 1.5, y: [1, 2]}\n"
    )
    assert parameters_from_file(path, "/rsp") == {
        "use_sim_time": True, "shared": 2, "frame_prefix": "a/",
    }  # fmt: skip
    assert parameters_from_file(path, "/robots/r1") == {
        "use_sim_time": True, "shared": 1, "wild": "one",
    }  # fmt: skip
    assert parameters_from_file(path, "/robots/r1/x")["shared"] == 1  # * is one token
    assert "wild" not in parameters_from_file(path, "/robots/r1/x")
    deep = parameters_from_file(path, "/a/b/deep")
    assert deep["nested.x"] == 1.5 and deep["nested.y"] == [1, 2]
    spec = NodeSpec(
        "ros2", "robot_state_publisher", "robot_state_publisher", "rsp",
        parameters=(ParamSource(values={"shared": 0, "a": {"b": 3}}), ParamSource(file=path)),
    )  # fmt: skip
    params = node_parameters(spec)
    assert params["shared"] == 2 and params["a.b"] == 3  # later sources win; dicts dotted


def test_static_transform_publisher_both_argument_forms() -> None:
    xyz, quat, parent, child = parse_ros2_static_transform_args(
        ("--x", "1", "--y", "2", "--yaw", str(math.pi / 2), "--frame-id", "world",
         "--child-frame-id", "base")
    )  # fmt: skip
    assert xyz == (1.0, 2.0, 0.0) and (parent, child) == ("world", "base")
    assert quat == pytest.approx((0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)))
    xyz, quat, parent, child = parse_ros2_static_transform_args(
        ("0", "0", "1", "0", "0", "0", "1", "a", "b")
    )
    assert xyz == (0.0, 0.0, 1.0) and quat == (0.0, 0.0, 0.0, 1.0) and child == "b"
    with pytest.raises(ValueError, match="--frame-id and --child-frame-id are required"):
        parse_ros2_static_transform_args(("--x", "1"))


def test_static_transform_publishers_of_ros2_tf2_and_ros1_tf() -> None:
    """ROS 2's and tf2's publish once, latched on /tf_static; ROS 1 tf's every period on /tf."""
    from robomodel.launch.runner import LaunchRunner, RunOptions
    from robomodel.runtime.msg import TFMessage
    from robomodel.runtime.qos import latched

    nodes = [
        NodeSpec("ros2", "tf2_ros", "static_transform_publisher", "s2",
                 args=("--x", "1", "--frame-id", "world", "--child-frame-id", "a")),
        NodeSpec("ros1", "tf2_ros", "static_transform_publisher", "s1",
                 args=("0", "2", "0", "0", "0", "0", "world", "b")),
        NodeSpec("ros1", "tf", "static_transform_publisher", "t1",
                 args=("0", "0", "3", "0", "0", "0", "world", "c", "50")),
    ]  # fmt: skip
    runner = LaunchRunner(nodes, RunOptions(bus="inproc", headless=True, duration_s=0.5))
    runner.open_bus()
    static: list[TFMessage] = []
    dynamic: list[TFMessage] = []
    listener = runner.context.create_node("listener")
    listener.create_subscription(TFMessage, "/tf_static", static.append, latched())
    listener.create_subscription(TFMessage, "/tf", dynamic.append)
    try:
        runner.start_nodes()
        runner.spin()
    finally:
        runner.shutdown()
    latched_xyz = {
        t.child_frame_id: (t.transform.translation.x, t.transform.translation.y)
        for m in static
        for t in m.transforms
    }
    assert latched_xyz == {"a": (1.0, 0.0), "b": (0.0, 2.0)}
    assert len(static) == 2  # once each
    periodic = [t for m in dynamic for t in m.transforms]
    assert {t.child_frame_id for t in periodic} == {"c"}
    assert periodic[0].transform.translation.z == 3.0
    assert len(periodic) >= 2  # republished every period, not once


def test_spawner_command_line() -> None:
    args = parse_ros2_spawner_args(
        ("jsb", "arm", "-c", "/my_ctrl_mgr", "--param-file", "/p.yaml", "--inactive",
         "-p", "/q.yaml", "--switch-asap",
         "--activate-as-group", "-u", "--controller-manager-timeout=30",
         "--controller-ros-args", "-r /a:=/b", "--ros-args", "-r", "__node:=sp")
    )  # fmt: skip
    assert args.controllers == ("jsb", "arm") and args.controller_manager == "/my_ctrl_mgr"
    assert args.param_files == ("/p.yaml", "/q.yaml") and args.inactive and args.activate_as_group
    assert args.unload_on_kill and args.timeout_s == 30.0
    with pytest.raises(RobomodelError, match="unrecognized arguments: --bogus"):
        parse_ros2_spawner_args(("jsb", "--bogus"))
    with pytest.raises(RobomodelError, match=re.escape("required: controller_names")):
        parse_ros2_spawner_args(("-c", "cm"))


def test_controller_parameters_come_from_the_manager_and_controller_keys() -> None:
    from robomodel.control.config import load_controller_config

    spec = NodeSpec(
        "ros2", "controller_manager", "ros2_control_node", "my_ctrl_mgr",
        parameters=(ParamSource(file=ARM / "config" / "position_controllers.yaml"),),
    )  # fmt: skip
    # the file says controller_manager:, so a manager named my_ctrl_mgr gets only /** params
    assert "update_rate" not in node_parameters(spec)
    spec = NodeSpec(
        "ros2", "controller_manager", "ros2_control_node", None,
        parameters=(ParamSource(file=ARM / "config" / "position_controllers.yaml"),),
    )  # fmt: skip
    config = load_controller_config("x", text=controller_config_text(spec, "controller_manager"))
    assert config.update_rate_hz == 100
    spec_of = {s.name: s for s in config.controllers}
    assert spec_of["joint1_position_controller"].params["joints"] == ["joint1"]


def test_control_launch_runs_with_spawners_chained_by_on_process_exit() -> None:
    from robomodel.launch.runner import LaunchRunner, RunOptions
    from robomodel.xacro import process_file

    urdf = process_file(str(ARM / "urdf" / "two_link_arm.urdf.xacro")).toxml()
    controllers = ParamSource(file=ARM / "config" / "position_controllers.yaml")
    rsp = NodeSpec(
        "ros2", "robot_state_publisher", "robot_state_publisher", None,
        parameters=(ParamSource(values={"robot_description": urdf}),),
    )  # fmt: skip
    cm = NodeSpec(
        "ros2", "controller_manager", "ros2_control_node", None, parameters=(controllers,)
    )
    jsb = NodeSpec("ros2", "controller_manager", "spawner", None, args=("joint_state_broadcaster",))
    arm = NodeSpec(
        "ros2", "controller_manager", "spawner", None,
        args=("joint1_position_controller", "-c", "/controller_manager"),
    )  # fmt: skip
    steps = (
        LaunchStep("node", cm),  # Jazzy: robot_description from robot_state_publisher
        LaunchStep("node", rsp),
        LaunchStep("node", jsb),
        LaunchStep("node", arm, after_exit_of=2),
        LaunchStep("log", message="all spawned", after_exit_of=3),
    )
    lines: list[str] = []
    runner = LaunchRunner(
        [s.node for s in steps if s.node is not None],
        RunOptions(bus="inproc", headless=True, duration_s=scaled(30)),  # a bound
        steps=steps,
        log=lines.append,
    )
    runner.open_bus()
    try:
        runner.start_nodes()
        runner.spin(stopped=lambda: any("all spawned" in line for line in lines))
        manager = runner.started[0].handle.system.manager
        states = {c["name"]: c["state"] for c in manager.list_controllers()}
        assert states == {
            "joint_state_broadcaster": "active",
            "joint1_position_controller": "active",
        }
    finally:
        runner.shutdown()
    text = "\n".join(lines)
    assert text.index("Configured and activated joint_state_broadcaster") < text.index(
        "started /spawner (controller_manager/spawner)", text.index("Configured and activated")
    )
    assert "[INFO] [launch.user]: all spawned" in text


def test_named_manager_unknown_plugin_and_unknown_controller_type(tmp_path: Path) -> None:
    """A ros2_control_node named my_ctrl_mgr is found by spawners' -c my_ctrl_mgr; a demo's own
    hardware plugin runs as mock_components/GenericSystem with one warning; a controller type
    robomodel lacks fails in the spawner as the manager reports it, and the others start."""
    from robomodel.launch.runner import LaunchRunner, RunOptions
    from robomodel.xacro import process_file

    urdf = process_file(str(ARM / "urdf" / "two_link_arm.urdf.xacro")).toxml()
    urdf = urdf.replace(
        "mock_components/GenericSystem",
        "ros2_control_demo_example_1/RRBotSystemPositionOnlyHardware",
    )
    config = tmp_path / "controllers.yaml"
    config.write_text(
        "my_ctrl_mgr:\n  ros__parameters:\n    update_rate: 50\n"
        "    joint_state_broadcaster:\n      type: joint_state_broadcaster/JointStateBroadcaster\n"
        "    mystery:\n      type: acme_controllers/TeleportController\n"
    )
    cm = NodeSpec(
        "ros2", "controller_manager", "ros2_control_node", "my_ctrl_mgr",
        parameters=(ParamSource(values={"robot_description": urdf}), ParamSource(file=config)),
    )  # fmt: skip
    spawn = NodeSpec(
        "ros2", "controller_manager", "spawner", None,
        args=("mystery", "joint_state_broadcaster", "-c", "my_ctrl_mgr"),
    )  # fmt: skip
    lines: list[str] = []
    runner = LaunchRunner(
        [cm, spawn],
        RunOptions(bus="inproc", headless=True, duration_s=scaled(30)),  # a bound
        steps=(LaunchStep("node", cm), LaunchStep("node", spawn)),
        log=lines.append,
    )
    runner.open_bus()
    try:
        with pytest.warns(UserWarning, match="RRBotSystemPositionOnlyHardware.*mock_components"):
            runner.start_nodes()
        runner.spin(stopped=lambda: runner.started[1].handle.exit_code() is not None)
        manager = runner.started[0].handle.system.manager
        assert manager.service_prefix == "/my_ctrl_mgr" and manager.update_rate_hz == 50
        states = {c["name"]: c["state"] for c in manager.list_controllers()}
        assert states == {"joint_state_broadcaster": "active"}
        assert runner.started[1].handle.exit_code() == 1  # the spawner failed on one
    finally:
        runner.shutdown()
    text = "\n".join(lines)
    assert (
        "acme_controllers/TeleportController" in text
        and "Failed loading controller mystery" in text
    )


_SPAWNER_YAML = """\
joint_state_broadcaster:
  ros__parameters:
    type: joint_state_broadcaster/JointStateBroadcaster
joint1_position_controller:
  ros__parameters:
    type: position_controllers/JointGroupPositionController
    joints: [joint1]
"""


@pytest.mark.parametrize("how", ["node parameters", "--param-file"])
def test_jazzy_spawner_gives_its_parameter_files_to_the_controllers(
    tmp_path: Path, how: str
) -> None:
    """Jazzy's spawner adds the node's ``--params-file`` files (and ``--param-file``) to the
    controllers it loads: a manager that knows no controller types gets them typed and active."""
    from robomodel.launch.runner import LaunchRunner, RunOptions
    from robomodel.xacro import process_file

    urdf = process_file(str(ARM / "urdf" / "two_link_arm.urdf.xacro")).toxml()
    controllers = tmp_path / "controllers.yaml"
    controllers.write_text(_SPAWNER_YAML)
    manager_yaml = tmp_path / "manager.yaml"
    manager_yaml.write_text("controller_manager:\n  ros__parameters:\n    update_rate: 100\n")
    cm = NodeSpec(
        "ros2", "controller_manager", "ros2_control_node", None,
        parameters=(ParamSource(file=manager_yaml), ParamSource(values={"robot_description": urdf})),
    )  # fmt: skip
    names = ("joint_state_broadcaster", "joint1_position_controller")
    if how == "--param-file":
        spawner = NodeSpec(
            "ros2", "controller_manager", "spawner", None, args=(*names, "-p", str(controllers))
        )
    else:
        spawner = NodeSpec(
            "ros2", "controller_manager", "spawner", None, args=names,
            parameters=(ParamSource(file=controllers),),
        )  # fmt: skip
    lines: list[str] = []
    runner = LaunchRunner(
        [cm, spawner],
        RunOptions(bus="inproc", headless=True, duration_s=scaled(30)),  # a bound
        log=lines.append,
    )
    runner.open_bus()
    try:
        runner.start_nodes()
        runner.spin(stopped=lambda: runner.started[1].handle.exit_code() is not None)
        manager = runner.started[0].handle.system.manager
        states = {c["name"]: (c["state"], c["type"]) for c in manager.list_controllers()}
    finally:
        runner.shutdown()
    assert states == {
        "joint_state_broadcaster": ("active", "joint_state_broadcaster/JointStateBroadcaster"),
        "joint1_position_controller": (
            "active", "position_controllers/JointGroupPositionController",
        ),
    }, "\n".join(lines)  # fmt: skip


def test_spawner_with_a_missing_parameter_file_fails_naming_it(tmp_path: Path) -> None:
    from robomodel.launch.runner import LaunchRunner, RunOptions

    missing = tmp_path / "nope.yaml"
    spawner = NodeSpec(
        "ros2", "controller_manager", "spawner", None, args=("jsb", "-p", str(missing))
    )
    lines: list[str] = []
    runner = LaunchRunner(
        [spawner],
        RunOptions(bus="inproc", headless=True, duration_s=scaled(30)),  # a bound
        log=lines.append,
    )
    runner.open_bus()
    try:
        runner.start_nodes()
        runner.spin(stopped=lambda: runner.started[0].handle.exit_code() is not None)
        code = runner.started[0].handle.exit_code()
    finally:
        runner.shutdown()
    assert code == 1
    assert any(str(missing) in line for line in lines), lines
