"""A user's executables found as ``ros2 run`` and ``rosrun`` find them, and the command lines
the launch builds for them from each front-end, in-process (nothing is started)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.executables import (
    AmbiguousExecutableError,
    CompiledNodeError,
    ExecutableNotFoundError,
    build_type,
    console_scripts,
    find_executable,
)
from robomodel.launch.model import NodeSpec
from robomodel.launch.user_nodes import node_command, node_environment

WS = Path(__file__).parent / "user_ws" / "src"


def test_console_scripts_of_setup_py_and_setup_cfg_are_read_without_running_setup_py(
    tmp_path: Path,
) -> None:
    scripts = console_scripts(WS / "py_nodes")
    assert scripts == {
        "cfg_node": "py_nodes.echo_args:main",
        "echo_args": "py_nodes.echo_args:main",
        "crasher": "py_nodes.crasher:main",  # an f-string with the package_name variable
    }
    marker = tmp_path / "ran"
    package = tmp_path / "evil"
    package.mkdir()
    (package / "setup.py").write_text(
        f"open({str(marker)!r}, 'w').write('x')\n"
        "setup(entry_points={'console_scripts': ['go = evil.go:main']})\n"
    )
    assert console_scripts(package) == {"go": "evil.go:main"}
    assert not marker.exists()


def test_an_ament_python_entry_point_runs_with_its_package_on_the_path() -> None:
    found = find_executable("py_nodes", "echo_args", WS / "py_nodes")
    assert (found.build_type, found.flavour) == ("ament_python", "rosidl")
    assert found.source_dir == WS / "py_nodes"
    command = found.command("/py")
    assert command[:2] == ["/py", "-c"]
    assert "from py_nodes.echo_args import main" in command[2]


def test_a_catkin_script_is_found_by_name_anywhere_in_the_package() -> None:
    found = find_executable("catkin_nodes", "crasher.py", WS / "catkin_nodes")
    assert found.path == WS / "catkin_nodes" / "scripts" / "crasher.py"
    assert found.flavour == "genpy"
    assert found.command("/py") == ["/py", str(found.path)]
    assert build_type(WS / "catkin_nodes") == "catkin"


def test_two_files_of_one_name_are_ambiguous_as_for_rosrun() -> None:
    with pytest.raises(AmbiguousExecutableError, match="More than one executable named twin"):
        find_executable("catkin_nodes", "twin", WS / "catkin_nodes")


def test_an_unknown_executable_lists_the_close_names() -> None:
    with pytest.raises(ExecutableNotFoundError) as caught:
        find_executable("py_nodes", "echo", WS / "py_nodes")
    assert "did you mean 'echo_args'?" in str(caught.value)
    assert caught.value.available == ("cfg_node", "crasher", "echo_args")


def test_a_cmake_target_built_from_cpp_is_refused_in_one_line() -> None:
    with pytest.raises(CompiledNodeError) as caught:
        find_executable("urdf_cpp_demo", "urdf_loader", WS / "urdf_cpp_demo")
    text = str(caught.value)
    assert "\n" not in text
    assert "src/urdf_loader.cpp" in text and "robomodel runs Python nodes" in text
    assert "ROS 2 and colcon" in text


def test_a_compiled_file_in_an_install_prefix_is_refused(tmp_path: Path) -> None:
    share = tmp_path / "install" / "share" / "demo_cpp"
    lib = tmp_path / "install" / "lib" / "demo_cpp"
    share.mkdir(parents=True)
    lib.mkdir(parents=True)
    (share / "package.xml").write_text("<package><name>demo_cpp</name></package>")
    shutil.copy("/bin/true", lib / "talker")
    (lib / "listener.py").write_text("print('hi')\n")
    (lib / "listener.py").chmod(0o755)
    index = PackageIndex(environ={"AMENT_PREFIX_PATH": str(tmp_path / "install")})
    package = index.get("demo_cpp")
    with pytest.raises(CompiledNodeError, match="is a compiled program"):
        find_executable("demo_cpp", "talker", package.path)
    found = find_executable("demo_cpp", "listener.py", package.path)
    assert (found.build_type, found.path) == ("install", lib / "listener.py")


def _spec_from(path: Path, dialect: str) -> NodeSpec:
    index = PackageIndex(package_paths=[WS], use_environment=False)
    if dialect == "ros1":
        from robomodel.launch.ros1 import load_launch as load_ros1

        launch = load_ros1(path, args={"stop_file": "/nowhere"}, packages=index)
        return next(n for n in launch.nodes if n.name == "echo")
    from robomodel.launch.ros2 import load_launch as load_ros2

    loaded = load_ros2(path, packages=index)
    try:
        return next(s.node for s in loaded.steps if s.node is not None and s.node.name == "echo")
    finally:
        loaded.remove_temporary_files()


@pytest.mark.parametrize("frontend", ["args.launch.py", "args.launch.xml", "args.launch.yaml"])
def test_ros2_frontends_pass_name_namespace_remaps_and_parameters_as_launch_ros(
    frontend: str,
) -> None:
    spec = _spec_from(WS / "py_nodes" / "launch" / frontend, "ros2")
    found = find_executable("py_nodes", "echo_args", WS / "py_nodes")
    temporary: list[Path] = []
    words = node_command(spec, found, python="/py", temporary=temporary)
    ros = words[words.index("--ros-args") :]
    assert words[3] == "--loud"
    assert ros[:7] == ["--ros-args", "-r", "__node:=echo", "-r", "__ns:=/robot1", "-r",
                       "chatter:=talk"]  # fmt: skip
    files = [ros[i + 1] for i, w in enumerate(ros) if w == "--params-file"]
    import yaml

    values: dict[str, object] = {}
    for file in files:
        values.update(yaml.safe_load(Path(file).read_text())["/**"]["ros__parameters"])
    assert values == {"rate_hz": 5.0, "frame": "base"}
    for path in temporary:
        path.unlink()


def test_ros1_nodes_get_roslaunch_args_and_the_master_and_namespace_in_their_environment() -> None:
    spec = _spec_from(WS / "catkin_nodes" / "launch" / "all.launch", "ros1")
    found = find_executable("catkin_nodes", "echo_args", WS / "catkin_nodes")
    words = node_command(spec, found, python="/py")
    assert words[2:] == ["--loud", "chatter:=talk", "__name:=echo", "__ns:=/robot1"]
    env = node_environment(spec, found, master_uri="http://localhost:11999/", environ={})
    assert env["ROS_MASTER_URI"] == "http://localhost:11999/"
    assert env["ROS_NAMESPACE"] == "/robot1"
    assert env["ROBOMODEL_MESSAGE_FLAVOUR"] == "genpy"


def test_an_ament_python_node_gets_its_package_on_pythonpath() -> None:
    spec = NodeSpec("ros2", "py_nodes", "echo_args", None, env=(("EXTRA", "1"),))
    found = find_executable("py_nodes", "echo_args", WS / "py_nodes")
    env = node_environment(spec, found, domain_id=7, environ={"PYTHONPATH": "/x"})
    assert env["PYTHONPATH"].split(":") == [str(WS / "py_nodes"), "/x"]
    assert (env["ROS_DOMAIN_ID"], env["EXTRA"], env["ROBOMODEL_MESSAGE_FLAVOUR"]) == (
        "7",
        "1",
        "rosidl",
    )
    assert json.dumps(env)  # plain strings only


def test_run_refuses_a_cpp_node_in_one_line_with_exit_2(cli: Any) -> None:
    result = cli("run", "--package-path", str(WS), "urdf_cpp_demo", "urdf_loader")
    assert result.code == 2
    lines = result.err.strip().splitlines()
    assert len(lines) == 1
    assert "urdf_cpp_demo/urdf_loader is a C++ node" in lines[0]
    assert "needs ROS 2 and colcon" in lines[0]


def test_run_names_the_close_packages_and_executables(cli: Any) -> None:
    result = cli("run", "--package-path", str(WS), "py_nodse", "echo_args")
    assert result.code == 2
    assert "unknown package 'py_nodse' (did you mean 'py_nodes'?)" in result.err
    assert "robot_state_publisher" in result.err  # robomodel's own nodes are listed too
    assert f"--package-path {WS}" in result.err
    result = cli("run", "--package-path", str(WS), "py_nodes", "echo")
    assert result.code == 2
    assert "has no executable 'echo' (did you mean 'echo_args'?)" in result.err


def test_robomodel_s_mapped_names_keep_priority_over_a_user_package_of_that_name(
    tmp_path: Path,
) -> None:
    from robomodel.launch.runner import LaunchRunner, RunOptions

    package = tmp_path / "robot_state_publisher"
    (package / "scripts").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>robot_state_publisher</name></package>")
    for name in ("robot_state_publisher", "helper"):
        (package / "scripts" / name).write_text("#!/usr/bin/env python3\n")
        (package / "scripts" / name).chmod(0o755)
    index = PackageIndex(package_paths=[tmp_path], use_environment=False)
    mapped = NodeSpec("ros1", "robot_state_publisher", "robot_state_publisher", "rsp")
    own = NodeSpec("ros1", "robot_state_publisher", "helper", "helper")
    runner = LaunchRunner([mapped, own], RunOptions(bus="inproc", package_index=index))
    assert runner.user_nodes() == [own]


def test_run_refuses_zenoh_endpoints_for_a_user_node_rather_than_ignore_them(cli: Any) -> None:
    result = cli("run", "--connect", "tcp/10.0.0.1:7447", "--package-path", str(WS), "py_nodes",
                 "echo_args")  # fmt: skip
    assert result.code == 2
    assert "--connect and --listen" in result.err and "py_nodes/echo_args" in result.err


def test_an_execute_process_of_ros2_run_is_the_user_s_node() -> None:
    from robomodel.launch.runner import LaunchRunner, RunOptions
    from robomodel.launch.steps import node_of_command

    spec = node_of_command(["ros2", "run", "py_nodes", "echo_args", "--ros-args", "-r",
                            "__node:=e2"])  # fmt: skip
    assert spec is not None and spec.name == "e2"
    index = PackageIndex(package_paths=[WS], use_environment=False)
    runner = LaunchRunner([spec], RunOptions(bus="inproc", package_index=index))
    found = runner.user_executable(spec)
    assert found is not None and found.entry_point == "py_nodes.echo_args:main"
    assert runner.user_nodes() == [spec]
