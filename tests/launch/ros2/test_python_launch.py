"""Python launch files: the corpus (ros2_control demo, urdf_tutorial, seeds 003/004) to steps."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2 import format_print, format_show_args, load_launch

from .conftest import CORPUS


def _nodes(launch):
    return [(s.node.executable, s.node.name, s.node.namespace) for s in launch.steps if s.node]


def test_rrbot_spawner_chain(corpus_index: PackageIndex) -> None:
    """ros2_control demo 1: OnProcessExit chains put the broadcaster after the controller
    spawner and rviz after the broadcaster (test_launch/test_event_handlers' semantics)."""
    launch = load_launch(CORPUS / "rrbot_demo/launch/rrbot.launch.py", packages=corpus_index)
    assert [s.node.executable for s in launch.steps] == [
        "ros2_control_node", "robot_state_publisher", "spawner", "spawner", "rviz2",
    ]  # fmt: skip
    assert [s.after_exit_of for s in launch.steps] == [None, None, None, 2, 3]
    assert launch.steps[3].node.args == ("joint_state_broadcaster",)
    controllers = CORPUS / "rrbot_demo/config/rrbot_controllers.yaml"
    assert launch.steps[0].node.parameters[0].file == controllers
    assert launch.steps[2].node.args == (
        "forward_position_controller",
        "--param-file",
        str(controllers),
    )
    description = launch.steps[1].node.parameters[0].values["robot_description"]
    assert '<robot name="rrbot">' in description and "joint1" in description
    assert str(launch.steps[0].location).endswith("rrbot.launch.py:43")
    assert launch.steps[4].node.args[0] == "-d"


def test_rrbot_gui_false_drops_rviz(corpus_index: PackageIndex) -> None:
    """IfCondition on a node run by an event handler still applies."""
    launch = load_launch(
        CORPUS / "rrbot_demo/launch/rrbot.launch.py", packages=corpus_index, args={"gui": "false"}
    )
    assert [s.node.executable for s in launch.steps] == [
        "ros2_control_node", "robot_state_publisher", "spawner", "spawner",
    ]  # fmt: skip


def test_urdf_tutorial_display(corpus_index: PackageIndex) -> None:
    """ParameterValue(value_type=str) keeps the xacro output verbatim (newlines included);
    gui selects joint_state_publisher_gui or joint_state_publisher; PythonExpression gates rviz."""
    path = CORPUS / "rrbot_demo/launch/display.launch.py"
    launch = load_launch(path, packages=corpus_index)
    assert [n[0] for n in _nodes(launch)] == [
        "robot_state_publisher",
        "joint_state_publisher_gui",
        "rviz2",
    ]
    text = launch.steps[0].node.parameters[0].values["robot_description"]
    assert "\n" in text and 'name="arm_joint1"' in text
    off = load_launch(path, packages=corpus_index, args={"gui": "false"})
    assert [n[0] for n in _nodes(off)] == ["robot_state_publisher", "joint_state_publisher"]
    with pytest.raises(
        LaunchError, match=r"Argument \"gui\" provided value \"maybe\" is not valid"
    ):
        load_launch(path, packages=corpus_index, args={"gui": "maybe"})


def test_yaml_parsing_of_plain_command_output(corpus_index: PackageIndex) -> None:
    """Without ParameterValue, substituted text is YAML-parsed as launch_ros does: the
    multi-line xacro output becomes one folded line."""
    launch = load_launch(CORPUS / "rrbot_demo/launch/rrbot.launch.py", packages=corpus_index)
    assert "\n" not in launch.steps[1].node.parameters[0].values["robot_description"]


@pytest.mark.parametrize("name", ["visualize", "visualize_urdf", "control", "gazebo"])
def test_seed_003_launch_files(
    name: str, corpus_index: PackageIndex, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Seed 003's launch files run from the workspace root, as the seed runs them."""
    monkeypatch.chdir(CORPUS / "ws_seed003")
    launch = load_launch(Path(f"src/urdf_cpp_demo/launch/{name}.launch.py"), packages=corpus_index)
    nodes = [s.node for s in launch.steps if s.node]
    assert "joint1" in str(nodes[0].parameters[0].values)
    if name == "gazebo":
        assert launch.steps[0].command == ("gzserver", "src/urdf_cpp_demo/worlds/empty.world")
        assert launch.steps[1].command == ("gzclient",)
        assert [n.executable for n in nodes] == ["ros2_control_node", "robot_state_publisher"]
        assert len(launch.files) == 2
    if name == "control":
        assert (
            nodes[0].parameters[1].file
            == CORPUS / "ws_seed003/src/urdf_cpp_demo/config/position_controllers.yaml"
        )
        assert [n.name for n in nodes] == [None, None, None]


def test_seed_004_display_robot_name(corpus_index: PackageIndex) -> None:
    """Seed 004: namespace from robot_name, frame_prefix defaulting to [namespace, '/'],
    rviz added by an OpaqueFunction with the performed namespace."""
    path = CORPUS / "example_description/launch/display.launch.py"
    launch = load_launch(path, packages=corpus_index, args={"robot_name": "r2"})
    rsp, rviz = (s.node for s in launch.steps)
    assert rsp.namespace == "/r2/" and rsp.parameters[0].values["frame_prefix"] == "r2/"
    assert rviz.namespace == "/r2/" and rviz.args[1].endswith("config/config.rviz")
    default = load_launch(path, packages=corpus_index)
    assert default.steps[0].node.parameters[0].values["frame_prefix"] == "robot1/"


def test_import_hook_is_scoped(corpus_index: PackageIndex) -> None:
    """The shim modules exist only during the load; a real module of the same name returns."""
    before = sys.modules.get("xacro")
    load_launch(CORPUS / "rrbot_demo/launch/rrbot.launch.py", packages=corpus_index)
    assert "launch" not in sys.modules and "launch_ros.actions" not in sys.modules
    assert sys.modules.get("xacro") is before


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "t.launch.py"
    path.write_text(text)
    return path


def test_unknown_api_name_is_located(tmp_path: Path) -> None:
    """A name robomodel lacks: LaunchError naming it at the importing line."""
    path = _write(tmp_path, "import os\nfrom launch.actions import FooBar\n")
    with pytest.raises(
        LaunchError, match=r"t\.launch\.py:2: 'launch\.actions\.FooBar' is not supported"
    ):
        load_launch(path)
    path = _write(tmp_path, "from launch.substitution import LaunchConfiguration\n")
    with pytest.raises(LaunchError, match=r":1: module 'launch\.substitution' is not supported"):
        load_launch(path)


def test_user_errors_are_located(tmp_path: Path) -> None:
    """SyntaxError and NameError in the launch file become LaunchError at file:line."""
    with pytest.raises(LaunchError, match=r"t\.launch\.py:2:\d+: SyntaxError"):
        load_launch(_write(tmp_path, "x = 1\ndef (:\n"))
    text = "from launch import LaunchDescription\n\ndef generate_launch_description():\n    return LaunchDescription([undefined_name])\n"
    with pytest.raises(LaunchError, match=r"t\.launch\.py:4: NameError"):
        load_launch(_write(tmp_path, text))


def test_missing_required_argument(tmp_path: Path) -> None:
    """launch's IncludeLaunchDescription check, also for the top-level file."""
    text = (
        "from launch import LaunchDescription\nfrom launch.actions import DeclareLaunchArgument\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([DeclareLaunchArgument('x', description='the x'),"
        " DeclareLaunchArgument('y', default_value='1')])\n"
    )
    path = _write(tmp_path, text)
    message = r"Included launch description missing required argument 'x' \(description: 'the x'\), given: \[y\]"
    with pytest.raises(LaunchError, match=message):
        load_launch(path, args={"y": "2"})
    launch = load_launch(path, args={"x": "2"})
    assert format_show_args(launch) == (
        "Arguments (pass arguments as '<name>:=<value>'):\n\n    'x':\n        the x\n\n"
        "    'y':\n        no description given\n        (default: '1')\n"
    )


def test_print_tree(corpus_index: PackageIndex) -> None:
    """--print: the introspector's tree of the top-level entities and handler children."""
    launch = load_launch(CORPUS / "rrbot_demo/launch/rrbot.launch.py", packages=corpus_index)
    lines = format_print(launch).splitlines()
    assert lines[0] == "<launch.launch_description.LaunchDescription object at 0x0>"
    assert (
        lines[1]
        == "├── Action('<launch.actions.declare_launch_argument.DeclareLaunchArgument object at 0x0>')"
    )
    assert (
        lines[5]
        == "├── RegisterEventHandler('<launch.event_handlers.on_process_exit.OnProcessExit object at 0x0>'):"
    )
    assert lines[-1].endswith("└── Action('<launch_ros.actions.node.Node object at 0x0>')")
