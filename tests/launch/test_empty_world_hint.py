"""Seed 003's ``gazebo.launch.py`` starts Gazebo but never spawns the robot. The
world runs empty, as Gazebo's would, and robomodel prints one hint line: no entity was spawned,
the launch file, and the spawner line that would spawn one (ROS 2's spawn_entity.py, ROS 1's
spawn_model). A launch with a spawner gets no hint."""

from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ROBOMODEL
from tests.timing import scaled

pytest.importorskip("mujoco")

SEED003 = Path(__file__).parent / "ros2" / "corpus" / "ws_seed003"


def _run_until(argv: list[str], cwd: Path, wanted: str, log: Path) -> str:
    """Run ``robomodel launch`` until ``wanted`` is printed (or it ends); the whole output."""
    env = {**os.environ, "ROS_PACKAGE_PATH": str(EXAMPLES), "PYTHONUNBUFFERED": "1"}
    with log.open("w") as out:
        proc = subprocess.Popen(
            [*ROBOMODEL, "launch", *argv, "--headless", "--bus", "inproc", "--duration", str(scaled(120))],
            cwd=cwd, stdout=out, stderr=subprocess.STDOUT, text=True, env=env,
        )  # fmt: skip
        try:
            deadline = time.monotonic() + scaled(120)
            while wanted not in log.read_text() and proc.poll() is None:
                assert time.monotonic() < deadline, log.read_text()
                time.sleep(0.2)
        finally:
            proc.terminate()
            proc.wait(scaled(30))
    return log.read_text()


def _hints(text: str) -> list[str]:
    return [line for line in text.splitlines() if "hint: no entity was spawned" in line]


def test_seed_003_gazebo_launch_says_that_nothing_was_spawned(tmp_path: Path) -> None:
    """Run from the workspace root, as the seed does (its paths are relative to it)."""
    launch = "src/urdf_cpp_demo/launch/gazebo.launch.py"
    text = _run_until([launch], SEED003, "hint:", tmp_path / "seed003.log")
    assert "started /gazebo (gazebo_ros/gzserver)" in text  # the world runs, empty
    [hint] = _hints(text)
    assert f"{SEED003 / launch} starts Gazebo but spawns no robot" in hint
    assert (
        "Node(package='gazebo_ros', executable='spawn_entity.py', "
        "arguments=['-topic', 'robot_description', '-entity', 'two_link_arm'])" in hint
    )  # the name is the robot's, from the launch's robot_description


def test_a_ros1_launch_without_spawn_model_gets_the_ros1_line(tmp_path: Path) -> None:
    """Seed 001's ur_gazebo.launch without its spawn_model node."""
    seed = (EXAMPLES / "ur5_gazebo" / "launch" / "ur_gazebo.launch").read_text()
    start = seed.index("  <!-- spawn robot in gazebo -->")
    world_only = tmp_path / "world_only.launch"
    world_only.write_text(seed[:start] + "</launch>\n")
    text = _run_until([str(world_only)], tmp_path, "hint:", tmp_path / "ros1.log")
    [hint] = _hints(text)
    assert f"{world_only} starts Gazebo but spawns no robot" in hint
    assert (
        '<node name="spawn_gazebo_model" pkg="gazebo_ros" type="spawn_model" '
        'args="-urdf -param robot_description -model ur5"/>' in hint
    )


@pytest.mark.parametrize(
    ("dialect", "package", "executable"),
    [("ros1", "gazebo_ros", "spawn_model"), ("ros2", "gazebo_ros", "spawn_entity.py"),
     ("ros2", "ros_gz_sim", "create")],
)  # fmt: skip
def test_a_launch_with_a_spawner_gets_no_hint(dialect: str, package: str, executable: str) -> None:
    """The spawner reports its own failures; the hint is only for launches without one."""
    from robomodel.launch.model import NodeSpec
    from robomodel.launch.nodes.base import LaunchShared, NodeContext, ViewerRequest
    from robomodel.launch.nodes.gazebo_hint import spawn_hint

    server = NodeSpec(dialect, "gazebo_ros", "gzserver", "gazebo")  # type: ignore[arg-type]
    spawner = NodeSpec(dialect, package, executable, "spawn")  # type: ignore[arg-type]
    ctx = NodeContext(server, None, None, ViewerRequest(), print, LaunchShared(nodes=(server,)))
    assert spawn_hint(ctx) is not None
    ctx.shared.nodes = (server, spawner)
    assert spawn_hint(ctx) is None
