"""``robomodel run`` on Zenoh with ``ros2 run``'s arguments: seed 003's ros2_control_node from
``--params-file`` files, the ROS 2 spawner and unspawner, ROS 1's controller_manager script on
the same manager, static_transform_publisher's flag form renamed and namespaced by
``--ros-args -r``, robot_state_publisher with ``-p``, tf2_echo; each checked by its effect."""

from __future__ import annotations

import os
import signal
import subprocess
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
import yaml

from tests.conftest import EXAMPLES, ROBOMODEL, unique_domain
from tests.timing import scaled, wait_until

ARM = EXAMPLES / "two_link_arm"


class _Bus:
    def __init__(self, tmp_path: Path) -> None:
        self.domain = unique_domain()
        self.tmp = tmp_path
        self.procs: list[subprocess.Popen[str]] = []

    def cli(self, *argv: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
        command = [*ROBOMODEL, *argv, "--domain-id", self.domain]
        return subprocess.run(command, capture_output=True, text=True, timeout=scaled(timeout))

    def run(self, *argv: str, timeout: float = 90) -> subprocess.CompletedProcess[str]:
        command = [*ROBOMODEL, "run", "--domain-id", self.domain, *argv]
        return subprocess.run(command, capture_output=True, text=True, timeout=scaled(timeout))

    def start(self, name: str, *argv: str) -> subprocess.Popen[str]:
        log = (self.tmp / f"{name}.log").open("w")
        proc = subprocess.Popen(
            [*ROBOMODEL, "run", "--domain-id", self.domain, *argv],
            stdout=log, stderr=subprocess.STDOUT, text=True, start_new_session=True,
        )  # fmt: skip
        self.procs.append(proc)
        return proc

    def log(self, name: str) -> str:
        return (self.tmp / f"{name}.log").read_text()

    def listed(self, node: str) -> bool:
        """``robomodel node list`` shows ``node`` (False while a loaded machine is slow)."""
        try:
            return node in self.cli("node", "list", timeout=30).stdout.split()
        except subprocess.TimeoutExpired:
            return False

    def until(self, check: Callable[[], bool], what: str, timeout_s: float = 120) -> None:
        """``wait_until`` at the pace of a CLI call (``timeout_s`` is scaled)."""
        wait_until(check, timeout_s, what=what, interval_s=0.3)


@pytest.fixture
def bus(tmp_path: Path) -> Iterator[_Bus]:
    graph = _Bus(tmp_path)
    try:
        yield graph
    finally:
        for proc in graph.procs:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()


def _params_file(path: Path, node: str, values: dict[str, object]) -> Path:
    path.write_text(yaml.safe_dump({node: {"ros__parameters": values}}))
    return path


def _stop(proc: subprocess.Popen[str]) -> int:
    os.killpg(proc.pid, signal.SIGINT)
    return proc.wait(scaled(30))


def test_ros2_control_node_spawners_and_the_ros1_script_by_run(bus: _Bus) -> None:
    description = subprocess.run(
        [*ROBOMODEL, "xacro", str(ARM / "urdf/two_link_arm.urdf.xacro")],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert description.returncode == 0, description.stderr
    urdf = _params_file(bus.tmp / "urdf.yaml", "/**", {"robot_description": description.stdout})
    manager = bus.start(
        "manager", "controller_manager", "ros2_control_node", "--ros-args",
        "--params-file", str(urdf), "--params-file", str(ARM / "config/position_controllers.yaml"),
    )  # fmt: skip
    bus.until(lambda: "controller manager" in bus.log("manager") or manager.poll() is not None,
              "the controller manager")  # fmt: skip
    assert manager.poll() is None, bus.log("manager")
    spawned = bus.run("controller_manager", "spawner", "joint_state_broadcaster",
                      "joint1_position_controller", "--controller-manager-timeout", "120")  # fmt: skip
    assert spawned.returncode == 0, spawned.stderr
    listed = bus.run("controller_manager", "controller_manager", "list")
    assert listed.stdout.splitlines() == [
        "'joint_state_broadcaster' - 'hardware_interface::JointStateInterface' ( running )",
        "'joint1_position_controller' - 'hardware_interface::PositionJointInterface' ( running )",
    ], listed.stderr
    stopped = bus.run(
        "controller_manager", "controller_manager", "stop", "joint1_position_controller"
    )
    assert stopped.stdout == "Stopped ['joint1_position_controller'] successfully\n", stopped.stderr
    assert bus.run("controller_manager", "controller_manager", "list").stdout.splitlines()[1] == (
        "'joint1_position_controller' - 'hardware_interface::PositionJointInterface' ( stopped )"
    )
    assert bus.run("controller_manager", "controller_manager", "start",
                   "joint1_position_controller").returncode == 0  # fmt: skip
    unspawned = bus.run("controller_manager", "unspawner", "joint1_position_controller")
    assert unspawned.returncode == 0, unspawned.stderr
    after = bus.cli("control", "list-controllers")
    assert "joint_state_broadcaster" in after.stdout
    assert "joint1_position_controller" not in after.stdout
    # robot_state_publisher with -p and a remap: the broadcaster's joints become /tf
    rsp = bus.start(
        "rsp", "robot_state_publisher", "robot_state_publisher", "--ros-args",
        "--params-file", str(urdf), "-p", "frame_prefix:=arm/", "-r", "__node:=arm_rsp",
    )  # fmt: skip
    bus.until(lambda: bus.listed("/arm_rsp"), "/arm_rsp listed")
    tf = bus.cli("topic", "echo", "/tf", "--once", timeout=60)
    assert tf.returncode == 0 and "child_frame_id: arm/link1" in tf.stdout, tf.stdout
    assert _stop(rsp) == 0 and _stop(manager) == 0


def test_static_transform_publisher_flags_with_ros_args_and_tf2_echo(bus: _Bus) -> None:
    stp = bus.start(
        "stp", "tf2_ros", "static_transform_publisher", "--x", "1", "--y", "2", "--z", "3",
        "--yaw", "1.5707963", "--frame-id", "world", "--child-frame-id", "tool",
        "--ros-args", "-r", "__node:=tool_stp", "-r", "__ns:=/sensors",
    )  # fmt: skip
    bus.until(lambda: bus.listed("/sensors/tool_stp"), "/sensors/tool_stp listed")
    echo = bus.start("echo", "tf2_ros", "tf2_echo", "world", "tool")
    bus.until(lambda: "Translation" in bus.log("echo"), "tf2_echo prints")
    text = bus.log("echo")
    assert "- Translation: [1.000, 2.000, 3.000]" in text
    assert "in RPY (degree) [0.000, -0.000, 90.000]" in text
    assert _stop(echo) == 0 and _stop(stp) == 0
    bad = bus.run("tf2_ros", "static_transform_publisher", "--x", "1", "--ros-args", "-x", "y")
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1, bad.stderr


def test_readme_run_commands(bus: _Bus) -> None:
    """The two commands of the docs' `robomodel run` section, as written (on Zenoh)."""
    from tests.conftest import ROOT

    text = (ROOT / "docs/reference/commands.md").read_text()
    section = text.split("## `robomodel run PKG EXECUTABLE [ARGS]`", 1)[1].split("\n## ")[0]
    blocks = [part.split("```")[0] for part in section.split("```bash\n")[1:]]
    commands = [line.split("#")[0].split() for block in blocks for line in block.splitlines()]
    assert [c[:3] for c in commands] == [["robomodel", "run", "tf2_ros"]] * 2
    publisher = bus.start("publisher", *commands[0][2:])
    echo = bus.start("readme_echo", *commands[1][2:])
    bus.until(lambda: "Translation" in bus.log("readme_echo"), "tf2_echo prints")
    assert "- Translation: [1.000, 2.000, 3.000]" in bus.log("readme_echo")
    assert _stop(echo) == 0 and _stop(publisher) == 0


def test_view_frames_draws_frames_whose_names_are_yaml_and_dot_syntax(bus: _Bus) -> None:
    """A child frame named ``it's: [x`` or ``b" -> "PWNED" [label="injected``: frames.gv and
    frames.pdf are written, the names quoted, and no edge of their own."""
    children = ("it's: [x", 'b" -> "PWNED" [label="injected')
    publishers = [
        bus.start(f"stp{k}", "tf2_ros", "static_transform_publisher", "--frame-id", "world",
                  "--child-frame-id", child, "--ros-args", "-r", f"__node:=stp{k}")
        for k, child in enumerate(children)
    ]  # fmt: skip
    bus.until(lambda: bus.listed("/stp0") and bus.listed("/stp1"), "the publishers listed")
    run = subprocess.run(
        [*ROBOMODEL, "run", "--domain-id", bus.domain, "tf", "view_frames"],
        capture_output=True, text=True, timeout=scaled(90), cwd=bus.tmp,
    )  # fmt: skip
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stderr
    gv = (bus.tmp / "frames.gv").read_text()
    assert '"world" -> "it\'s: [x"' in gv
    assert '"world" -> "b\\" -> \\"PWNED\\" [label=\\"injected"' in gv
    assert (bus.tmp / "frames.pdf").read_bytes().startswith(b"%PDF")
    assert all(_stop(p) == 0 for p in publishers)


def test_tf2_tools_view_frames_writes_the_tree(bus: _Bus) -> None:
    """``ros2 run tf2_tools view_frames -t 2 -o tree``: tree.gv with the static transform's edge
    (frame names from the bus, so a buffer that heard nothing fails), tree.pdf; its lines."""
    stp = bus.start(
        "stp", "tf2_ros", "static_transform_publisher", "--x", "1", "--frame-id", "world",
        "--child-frame-id", "tool",
    )  # fmt: skip
    bus.until(lambda: bus.listed("/static_transform_publisher"), "the publisher listed")
    run = subprocess.run(
        [*ROBOMODEL, "run", "--domain-id", bus.domain, "tf2_tools", "view_frames", "-t", "2",
         "-o", "tree"],
        capture_output=True, text=True, timeout=scaled(90), cwd=bus.tmp,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == [
        "Listening to tf data for 2.0 seconds...", "Generating graph in tree.pdf file...",
    ]  # fmt: skip
    assert '"world" -> "tool"' in (bus.tmp / "tree.gv").read_text()
    assert (bus.tmp / "tree.pdf").read_bytes().startswith(b"%PDF")
    assert _stop(stp) == 0
    for argv, said in (
        (["view_frames", "--wait", "x"], "view_frames: argument --wait-time/-t: invalid float"),
        (["view_frames", "--bogus"], "view_frames: unrecognized arguments: --bogus"),
    ):
        bad = bus.run("tf2_tools", *argv)
        errors = [x for x in bad.stderr.splitlines() if "error" in x]
        assert bad.returncode == 2 and len(errors) == 1 and said in errors[0], bad.stderr
        assert "Traceback" not in bad.stderr
