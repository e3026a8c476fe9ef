"""``robomodel launch`` end to end: the examples' launch files run as processes on the Zenoh
bus, checked from other processes with ``robomodel topic/param/tf/control``, as a student
checks them with rostopic in another terminal."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import EXAMPLES, ROBOMODEL, end_process, unique_domain
from tests.timing import scaled, wait_until

pytest.importorskip("zenoh")


def _env() -> dict[str, str]:
    return {**os.environ, "ROS_PACKAGE_PATH": str(EXAMPLES), "PYTHONUNBUFFERED": "1"}


@contextmanager
def _launch(domain: str, *argv: str, log: Path) -> Iterator[subprocess.Popen[str]]:
    with log.open("w") as out:
        proc = subprocess.Popen(
            [*ROBOMODEL, "launch", *argv, "--headless", "--domain-id", domain],
            stdout=out,
            stderr=subprocess.STDOUT,
            text=True,
            env=_env(),
        )
        try:
            yield proc
        finally:
            end_process(proc, signal.SIGTERM, timeout_s=20)


def _wait_for_line(log: Path, text: str, proc: subprocess.Popen[str], timeout_s: float) -> None:
    """Until the launch writes ``text`` to ``log``; fails at once when it has ended."""

    def printed() -> bool:
        if text in log.read_text():
            return True
        assert proc.poll() is None, f"launch ended early:\n{log.read_text()}"
        return False

    wait_until(
        printed, timeout_s, what=lambda: f"'{text}' printed:\n{log.read_text()}", interval_s=0.2
    )


def _cli(domain: str, *argv: str, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *argv, "--domain-id", domain],
        capture_output=True,
        text=True,
        env=_env(),
        timeout=scaled(timeout),
    )


def _echo_once(domain: str, topic: str) -> Any:
    result = _cli(domain, "topic", "echo", topic, "--once")
    assert result.returncode == 0, result.stderr
    return yaml.safe_load(result.stdout.split("---")[0])


def _joint(
    domain: str,
    topic: str,
    joint: str,
    target: float,
    *,
    tolerance: float = 0.05,
    timeout_s: float = 25,
) -> float:
    timeout_s = scaled(timeout_s)
    deadline = time.monotonic() + timeout_s
    value = float("nan")
    while time.monotonic() < deadline:
        msg = _echo_once(domain, topic)
        value = msg["position"][msg["name"].index(joint)]
        if abs(value - target) < tolerance:
            return float(value)
    raise AssertionError(f"{joint} at {value}, not near {target} after {timeout_s:.0f} s")


def test_rrbot_two_terminals_as_seed_000(tmp_path: Path) -> None:
    """roslaunch rrbot_gazebo rrbot_world.launch; roslaunch rrbot_control rrbot_control.launch;
    rostopic pub /rrbot/joint1_position_controller/command: the joint goes there."""
    domain = unique_domain()
    world_log, control_log = tmp_path / "world.log", tmp_path / "control.log"
    with _launch(domain, "rrbot_gazebo", "rrbot_world.launch", "gui:=false", log=world_log) as w:
        _wait_for_line(world_log, "Successfully spawned entity", w, 60)
        with _launch(domain, "rrbot_control", "rrbot_control.launch", log=control_log) as c:
            _wait_for_line(control_log, "Started controllers: joint_state_controller", c, 60)
            # the second launch's parameters live in the first one's parameter server
            got = _cli(domain, "param", "get", "/rrbot/joint1_position_controller/pid/p")
            assert got.returncode == 0 and float(got.stdout) == 100.0, got.stderr
            listed = _cli(domain, "control", "list-controllers", "-c", "/rrbot/controller_manager")
            assert "joint1_position_controller" in listed.stdout and "active" in listed.stdout
            # Without -c, the error names the manager that is on the bus
            default = _cli(domain, "control", "list-controllers")
            assert default.returncode == 2 and "Traceback" not in default.stderr
            assert "controller managers that are: /rrbot/controller_manager" in default.stderr
            assert "(pass -c /rrbot/controller_manager)" in default.stderr
            pub = _cli(
                domain, "topic", "pub", "-1", "/rrbot/joint1_position_controller/command",
                "std_msgs/msg/Float64", "data: 0.8",
            )  # fmt: skip
            assert pub.returncode == 0, pub.stderr
            # effort PID (p=100, i=0.01) against gravity on a 2 m arm: it settles near the
            # target, off by the gravity sag, as in Gazebo
            _joint(domain, "/rrbot/joint_states", "joint1", 0.8, tolerance=0.25)
            # robot_state_publisher (remapped to /rrbot/joint_states) follows the simulation
            tf = _cli(domain, "tf", "link1", "link3", "--once", "--timeout", f"{scaled(20):.1f}")
            assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr
        assert c.returncode is not None
        assert "Loaded controllers: joint_state_controller, joint1_position_controller" in (
            control_log.read_text()
        )


def test_ur5_two_terminals_as_seed_001(tmp_path: Path) -> None:
    domain = unique_domain()
    world_log, control_log = tmp_path / "world.log", tmp_path / "control.log"
    with _launch(domain, "ur5_gazebo", "ur_gazebo.launch", log=world_log) as w:
        _wait_for_line(world_log, "Successfully spawned entity", w, 60)
        with _launch(domain, "ur5_gazebo", "ur_controller.launch", log=control_log) as c:
            _wait_for_line(control_log, "Started controllers: joint_state_controller", c, 60)
            pub = _cli(
                domain, "topic", "pub", "-1", "/joint2_position_controller/command",
                "std_msgs/msg/Float64", "data: -1.0",
            )  # fmt: skip
            assert pub.returncode == 0, pub.stderr
            _joint(domain, "/joint_states", "shoulder_lift_joint", -1.0)


def test_display_launch_serves_tf_and_parameters(tmp_path: Path) -> None:
    """Seed 000's display.launch (rviz -d required): headless, robot_state_publisher publishes
    the gripper's frames and the parameters are readable from another process."""
    domain = unique_domain()
    log = tmp_path / "display.log"
    with _launch(domain, "gripper_description", "display.launch", log=log) as proc:
        _wait_for_line(log, "nodes running", proc, 60)
        tf = _cli(domain, "tf", "base_link", "gripper", "--once", "--timeout", f"{scaled(20):.1f}")
        assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr
        text = _cli(domain, "param", "get", "/robot_description")
        assert text.returncode == 0 and "<robot" in text.stdout and "planar_3dof" in text.stdout
        nodes = _cli(domain, "topic", "list")
        assert "/tf_static" in nodes.stdout.split() and "/joint_states" in nodes.stdout.split()


def test_a_launch_error_starts_nothing(tmp_path: Path) -> None:
    broken = tmp_path / "broken.launch"
    broken.write_text('<launch>\n  <param name="x" value="$(arg missing)"/>\n</launch>\n')
    result = subprocess.run(
        [*ROBOMODEL, "launch", str(broken), "--headless", "--bus", "inproc"],
        capture_output=True,
        text=True,
        env=_env(),
        timeout=scaled(60),
    )
    assert result.returncode == 2
    assert f"{broken}:2:" in result.stderr and "missing" in result.stderr
    assert "Traceback" not in result.stderr and "started" not in result.stderr


def test_robomodel_new_writes_a_launch_file_robomodel_launch_runs(tmp_path: Path) -> None:
    """``robomodel new`` then ``robomodel launch PKG display.launch`` (gui:=false: the
    joint_state_publisher branch): robot_state_publisher's frames are seen from another
    process."""
    from robomodel.description.scaffold import create_description_package

    create_description_package("arm_description", tmp_path / "ws")
    domain = unique_domain()
    log = tmp_path / "arm.log"
    argv = ("arm_description", "display.launch", "gui:=false", "--package-path", str(tmp_path))
    with _launch(domain, *argv, log=log) as proc:
        _wait_for_line(log, "nodes running", proc, 60)
        frames = _cli(
            domain, "tf", "base_link", "link_2", "--once", "--timeout", f"{scaled(20):.1f}"
        )
        assert frames.returncode == 0 and "Translation" in frames.stdout, frames.stderr
        # the launch's parameter server is a hidden node: no /rosmaster on a Zenoh graph
        nodes = _cli(domain, "node", "list").stdout.split()
        assert "/robot_state_publisher" in nodes and "/rosmaster" not in nodes, nodes
        assert not [n for n in nodes if "_robomodel" in n], nodes
        assert "/_robomodel_params" in _cli(domain, "node", "list", "--all").stdout.split()
        services = _cli(domain, "service", "list").stdout.split()
        assert "/rosmaster" not in services and "/_robomodel_params/call" not in services
        assert _cli(domain, "param", "get", "/robot_description").stdout.startswith("<?xml")
    text = log.read_text()
    assert "started /joint_state_publisher (joint_state_publisher/joint_state_publisher)" in text
    assert "started /robot_state_publisher (robot_state_publisher" in text
    assert "joint_state_publisher_gui" not in text  # if="$(arg gui)" was false
