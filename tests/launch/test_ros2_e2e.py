"""ROS 2 launch files end to end: the examples' seed 003/004 launch files and ``robomodel new``'s
display.launch.py run by ``robomodel launch`` on the Zenoh bus, checked from other processes
with ``robomodel topic/control/tf`` as ``ros2 topic``/``ros2 control`` would check them."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from tests.conftest import unique_domain
from tests.launch.test_launch_e2e import _cli, _joint, _launch, _wait_for_line
from tests.timing import scaled

pytest.importorskip("zenoh")


def test_two_link_arm_visualize_launch(tmp_path: Path) -> None:
    """Seed 003: ros2 launch urdf_cpp_demo visualize.launch.py (xacro.process_file in the
    launch file; headless, the sliders' defaults come from a joint_state_publisher)."""
    domain = unique_domain()
    log = tmp_path / "visualize.log"
    with _launch(domain, "two_link_arm", "visualize.launch.py", log=log) as proc:
        _wait_for_line(log, "nodes running", proc, 60)
        tf = _cli(domain, "tf", "base_link", "gripper", "--once", "--timeout", f"{scaled(20):.1f}")
        assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr
        text = log.read_text()
        assert "started /state_publisher (robot_state_publisher/robot_state_publisher)" in text


def test_two_link_arm_control_launch_then_ros2_control_from_another_terminal(
    tmp_path: Path,
) -> None:
    """Seed 003 steps 4-7: control.launch.py, then load_controller --set-state and a command."""
    domain = unique_domain()
    log = tmp_path / "control.log"
    with _launch(domain, "two_link_arm", "control.launch.py", log=log) as proc:
        _wait_for_line(log, "nodes running", proc, 60)
        for name in ("joint_state_broadcaster", "joint1_position_controller"):
            loaded = _cli(domain, "control", "load", name, "--set-state", "active")
            assert loaded.returncode == 0, loaded.stderr
        pub = _cli(
            domain, "topic", "pub", "-1", "/joint1_position_controller/commands",
            "std_msgs/msg/Float64MultiArray", "data: [1.0]",
        )  # fmt: skip
        assert pub.returncode == 0, pub.stderr
        _joint(domain, "/joint_states", "joint1", 1.0)


def test_two_link_arm_gazebo_launch_spawns_and_controls_in_the_simulator(tmp_path: Path) -> None:
    """Seed 003's Gazebo launch: gazebo_ros's gazebo.launch.py with a world, spawn_entity.py
    from the robot_description topic, gazebo_ros2_control's manager, spawners chained by
    OnProcessExit; a command moves the simulated joint."""
    domain = unique_domain()
    log = tmp_path / "gazebo.log"
    with _launch(domain, "two_link_arm", "gazebo.launch.py", "gui:=false", log=log) as proc:
        _wait_for_line(log, "Configured and activated joint1_position_controller", proc, 90)
        text = log.read_text()
        assert text.index("Configured and activated joint_state_broadcaster") < text.index(
            "Configured and activated joint1_position_controller"
        )
        pub = _cli(
            domain, "topic", "pub", "-1", "/joint1_position_controller/commands",
            "std_msgs/msg/Float64MultiArray", "data: [0.5]",
        )  # fmt: skip
        assert pub.returncode == 0, pub.stderr
        _joint(domain, "/joint_states", "joint1", 0.5, tolerance=0.05, timeout_s=30)
        clock = _cli(domain, "topic", "echo", "/clock", "--once")
        assert clock.returncode == 0 and "clock" in clock.stdout


def test_example_description_display_launch_prefixes_frames_with_robot_name(
    tmp_path: Path,
) -> None:
    """Seed 004: display.launch.py robot_name:=robot1/ (an OpaqueFunction passing the arg to
    xacro.process_file(mappings=...))."""
    domain = unique_domain()
    log = tmp_path / "display.log"
    argv = ("example_description", "display.launch.py", "robot_name:=r1")
    with _launch(domain, *argv, log=log) as proc:
        _wait_for_line(log, "nodes running", proc, 60)
        within = f"{scaled(20):.1f}"
        tf = _cli(domain, "tf", "r1/base_link", "r1/arm_link_2", "--once", "--timeout", within)
        assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr + log.read_text()


def test_show_args_of_a_python_launch_file() -> None:
    import subprocess

    from tests.conftest import EXAMPLES, ROBOMODEL

    result = subprocess.run(
        [*ROBOMODEL, "launch", str(EXAMPLES / "example_description/launch/display.launch.py"),
         "--show-args"],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert "'robot_name':" in result.stdout and "frame prefix of every link" in result.stdout


def test_robomodel_new_display_launch_py_runs(tmp_path: Path) -> None:
    from robomodel.description.scaffold import BuildType, PackageSpec, create_description_package

    spec = PackageSpec("arm_description", build_type=BuildType.AMENT_CMAKE)
    create_description_package(spec, tmp_path / "ws")
    domain = unique_domain()
    log = tmp_path / "arm.log"
    argv = ("arm_description", "display.launch.py", "--package-path", str(tmp_path))
    with _launch(domain, *argv, log=log) as proc:
        _wait_for_line(log, "nodes running", proc, 60)
        tf = _cli(domain, "tf", "base_link", "link_2", "--once", "--timeout", f"{scaled(20):.1f}")
        assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr + log.read_text()


def test_ctrl_c_stops_a_simulation_launch_within_seconds(tmp_path: Path) -> None:
    import signal

    domain = unique_domain()
    log = tmp_path / "gazebo.log"
    with _launch(domain, "two_link_arm", "gazebo.launch.py", "gui:=false", log=log) as proc:
        _wait_for_line(log, "Configured and activated joint1_position_controller", proc, 90)
        proc.send_signal(signal.SIGINT)
        try:
            # a hang fails here; the bound is generous, not a timing claim
            code = proc.wait(scaled(30))
        except subprocess.TimeoutExpired:
            raise AssertionError(f"no exit 30 s after Ctrl-C:\n{log.read_text()[-4000:]}") from None
    assert code == 0, log.read_text()
    assert "Traceback" not in log.read_text()
