"""A ``colcon build --symlink-install`` prefix runs as the copied one does.

The package is modelled on ros2_control_demos' example_1 (Jazzy): its source tree keeps the
launch file in ``bringup/launch``, the controllers in ``bringup/config`` and the description in
``description/urdf`` and ``description/ros2_control``, and CMake installs those folders flat
into ``share/<pkg>/{launch,config,urdf,ros2_control}``. colcon's ``--symlink-install`` makes
every installed file a symlink into the source tree, whose layout differs, so a lookup that
follows the symlink (``FindPackageShare`` giving the source folder) looks for
``<src>/urdf/rrbot.urdf.xacro``, which does not exist.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.ros2.loader import load_launch
from tests.conftest import ROBOMODEL, end_process, unique_domain
from tests.timing import scaled

PKG = "ros2_control_demo_example_1"
CORPUS = Path(__file__).parent / "ros2" / "corpus" / "rrbot_demo"

# where each installed file comes from in the source tree: CMake's
# install(DIRECTORY bringup/launch bringup/config DESTINATION share/${PROJECT_NAME}) and
# install(DIRECTORY description/urdf description/ros2_control DESTINATION share/...)
_INSTALLED = {
    "package.xml": "package.xml",
    "launch/rrbot.launch.py": "bringup/launch/rrbot.launch.py",
    "config/rrbot_controllers.yaml": "bringup/config/rrbot_controllers.yaml",
    "urdf/rrbot.urdf.xacro": "description/urdf/rrbot.urdf.xacro",
    "ros2_control/rrbot.ros2_control.xacro": "description/ros2_control/rrbot.ros2_control.xacro",
}

_ROS2_CONTROL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="rrbot_ros2_control" params="name prefix">
    <ros2_control name="${name}" type="system">
      <hardware>
        <plugin>ros2_control_demo_example_1/RRBotSystemPositionOnlyHardware</plugin>
      </hardware>
      <joint name="${prefix}joint1">
        <command_interface name="position"/>
        <state_interface name="position"/>
      </joint>
    </ros2_control>
  </xacro:macro>
</robot>
"""

_URDF = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="rrbot">
  <xacro:arg name="prefix" default=""/>
  <xacro:include filename="$(find ros2_control_demo_example_1)/ros2_control/rrbot.ros2_control.xacro"/>
  <link name="world"/>
  <link name="$(arg prefix)base_link"/>
  <joint name="$(arg prefix)base_joint" type="fixed">
    <parent link="world"/>
    <child link="$(arg prefix)base_link"/>
  </joint>
  <link name="$(arg prefix)link1"/>
  <joint name="$(arg prefix)joint1" type="continuous">
    <parent link="$(arg prefix)base_link"/>
    <child link="$(arg prefix)link1"/>
    <axis xyz="0 1 0"/>
  </joint>
  <xacro:rrbot_ros2_control name="RRBot" prefix="$(arg prefix)"/>
</robot>
"""


def _source_tree(src: Path) -> Path:
    """``src/ros2_control_demos/example_1`` as in the demos' repository."""
    root = src / "ros2_control_demos" / "example_1"
    files = {
        "package.xml": f"<package format='3'><name>{PKG}</name><version>1.0.0</version></package>",
        "bringup/launch/rrbot.launch.py": (CORPUS / "launch/rrbot.launch.py")
        .read_text()
        .replace('"rrbot_demo"', f'"{PKG}"'),
        "bringup/config/rrbot_controllers.yaml": (
            CORPUS / "config/rrbot_controllers.yaml"
        ).read_text(),
        "description/urdf/rrbot.urdf.xacro": _URDF,
        "description/ros2_control/rrbot.ros2_control.xacro": _ROS2_CONTROL,
    }
    for relative, text in files.items():
        (root / relative).parent.mkdir(parents=True, exist_ok=True)
        (root / relative).write_text(text)
    return root


def _install(workspace: Path, *, symlink: bool) -> Path:
    """``install/<pkg>`` as ``colcon build [--symlink-install]`` leaves it (isolated layout)."""
    source = _source_tree(workspace / "src")
    prefix = workspace / "install" / PKG
    share = prefix / "share" / PKG
    for installed, origin in _INSTALLED.items():
        (share / installed).parent.mkdir(parents=True, exist_ok=True)
        if symlink:
            (share / installed).symlink_to(source / origin)
        else:
            shutil.copy(source / origin, share / installed)
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / PKG
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    return prefix


@pytest.mark.parametrize("symlink", [False, True], ids=["copied", "symlink-install"])
def test_a_symlinked_launch_file_finds_its_package_in_the_prefix(
    tmp_path: Path, symlink: bool
) -> None:
    """The index (AMENT_PREFIX_PATH) answers first, with the prefix's path as given."""
    prefix = _install(tmp_path, symlink=symlink)
    launch_file = prefix / "share" / PKG / "launch" / "rrbot.launch.py"
    index = PackageIndex(environ={"AMENT_PREFIX_PATH": str(prefix)}).with_workspace_of(launch_file)
    assert index.find(PKG) == prefix / "share" / PKG
    # no index at all: the file's own package is the prefix's share folder, not the source's
    alone = PackageIndex(use_environment=False).with_workspace_of(launch_file)
    assert alone.find(PKG) == prefix / "share" / PKG


def test_a_package_on_the_search_paths_wins_over_the_input_s_own_package(tmp_path: Path) -> None:
    """ROS finds the package on ROS_PACKAGE_PATH, whichever file mentions it: the input's own
    package applies only where the search paths know no package of that name."""
    for where in ("listed", "mine"):
        (tmp_path / where / "p").mkdir(parents=True)
        (tmp_path / where / "p" / "package.xml").write_text("<package><name>p</name></package>")
    mine = tmp_path / "mine" / "p" / "x.urdf"
    env = {"ROS_PACKAGE_PATH": str(tmp_path / "listed")}
    assert PackageIndex(environ=env).with_workspace_of(mine).find("p") == tmp_path / "listed/p"
    assert PackageIndex(environ={}).with_workspace_of(mine).find("p") == tmp_path / "mine/p"


def _launch_until(
    argv: list[str], env: dict[str, str], log: Path, line: str, timeout_s: float = 90
) -> str:
    """Run ``robomodel launch`` until ``line`` is printed; return the log then."""
    with log.open("w") as out:
        proc = subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, text=True, env=env)
        try:
            deadline = time.monotonic() + scaled(timeout_s)
            while line not in log.read_text():
                assert proc.poll() is None, f"launch ended early:\n{log.read_text()}"
                assert time.monotonic() < deadline, f"no '{line}':\n{log.read_text()}"
                time.sleep(0.2)
            return log.read_text()
        finally:
            end_process(proc, signal.SIGTERM, timeout_s=20)


@pytest.mark.parametrize("symlink", [False, True], ids=["copied", "symlink-install"])
def test_the_ros2_control_demo_runs_from_a_symlink_install_prefix(
    tmp_path: Path, symlink: bool
) -> None:
    """``ros2 launch ros2_control_demo_example_1 rrbot.launch.py`` after ``source
    install/setup.bash``: the description comes from the install's xacro path and both
    controllers are configured, the same with copied and with symlinked files."""
    pytest.importorskip("zenoh")
    prefix = _install(tmp_path, symlink=symlink)
    env = {
        **{k: v for k, v in os.environ.items() if not k.startswith("ROS")},
        "AMENT_PREFIX_PATH": str(prefix),
        "PYTHONUNBUFFERED": "1",
    }
    share = prefix / "share" / PKG
    launch = load_launch(
        share / "launch" / "rrbot.launch.py",
        packages=PackageIndex(environ={"AMENT_PREFIX_PATH": str(prefix)}),
        args={"gui": "false"},
    )
    nodes = [step.node for step in launch.steps if step.node is not None]
    (description,) = [
        source.values["robot_description"]
        for node in nodes
        for source in node.parameters
        if source.values and "robot_description" in source.values
    ]
    assert f"autogenerated by xacro from {share}/urdf/rrbot.urdf.xacro" in description
    assert '<ros2_control name="RRBot"' in description  # the $(find)-included macro
    manager = next(node for node in nodes if node.executable == "ros2_control_node")
    assert manager.parameters[0].file == share / "config" / "rrbot_controllers.yaml"
    argv = [*ROBOMODEL, "launch", PKG, "rrbot.launch.py", "gui:=false", "--headless"]
    text = _launch_until(
        [*argv, "--domain-id", unique_domain()],
        env,
        tmp_path / "launch.log",
        "Configured and activated joint_state_broadcaster",
    )
    assert "Configured and activated forward_position_controller" in text
    assert "No such file" not in text
