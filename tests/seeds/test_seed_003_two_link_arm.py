"""Seed 003, "URDF in ROS 2": the urdf_cpp_demo package (simple_arm.urdf, visualize.launch.py,
simple_arm.xacro with ros2_control, position_controllers.yaml, control.launch.py, Gazebo's
gazebo.launch.py and empty.world), ``colcon build``, ``ros2 launch``, ``ros2 control
load_controller --set-state start`` and ``ros2 topic pub``, as the student types them, with
robomodel's CLI (``ros2 launch`` → ``robomodel launch``, ``ros2 control load_controller`` →
``robomodel control load``, ``ros2 topic pub`` → ``robomodel topic pub``).

The seed's launch files read ``src/urdf_cpp_demo/...`` relative to the workspace: commands run
from the workspace's root, as the seed's do. Typo fixes are named in comments. The C++
``urdf_loader`` node of the seed's first part is not built (robomodel runs no C++).
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from tests.conftest import debian_check_urdf
from tests.seeds.conftest import (
    LINE_TIMEOUT_S,
    Ros2Workspace,
    joint_position,
    until,
    write_tree,
)
from tests.timing import scaled

PKG = "urdf_cpp_demo"
INSTALLED = ("launch", "urdf", "config", "worlds")  # install(DIRECTORY launch ...) and friends

# "Example: Simple 2-Link Robot (Arm)". Typos fixed: "link name=" lost its "<" twice; the
# listing's closing </robot> is cut off.
SIMPLE_ARM_URDF = """<!-- simple_arm.urdf -->
<robot name="two_link_arm">

<link name="base_link"/>

<joint name="joint1" type="revolute">

<parent link="base_link"/>

<child link="link1"/>

<origin xyz="0 0 1" rpy="0 0 0"/>
<axis xyz="0 0 1"/>
</joint>

<link name="link1">

<visual>

<geometry>

<box size="0.5 0.1 0.1"/>

</geometry>

</visual>

</link>
</robot>
"""

# What urdfdom (and so ROS 2's robot_state_publisher) requires of a revolute joint and the seed
# leaves out: the student's fix after check_urdf's error, the same for the URDF and the xacro.
LIMIT = '<limit lower="-3.14" upper="3.14" effort="10" velocity="1.0"/>\n'

# visualize.launch.py. Typos fixed: the "return" block lost its indentation.
VISUALIZE_LAUNCH = """from launch import LaunchDescription
from launch_ros.actions import Node

def generate_launch_description():
    urdf_path = 'src/urdf_cpp_demo/urdf/simple_arm.urdf'

    return LaunchDescription([
        Node(
            package='robot_state_publisher',
            executable='robot_state_publisher',
            name='state_publisher',
            output='screen',
            parameters=[{'robot_description': open(urdf_path).read()}],
        ),
        Node(
            package='joint_state_publisher_gui',
            executable='joint_state_publisher_gui',
            name='joint_state_publisher',
            output='screen',
        ),
        Node(
            package='rviz2',
            executable='rviz2',
            name='rviz2',
            output='screen',
        )
    ])
"""

# "Convert URDF to XACRO": simple_arm.xacro, with "Add ros2_control Support" (the block "at the
# top after robot tag", the transmission after the joint). Typos fixed: underscores read as
# spaces ("two link arm", "link length", "base link", "fake components", "command interface",
# "state interface", "transmission interface", "hardware interface"); "k name=" for
# "<link name="; the transmission's second <hardwareInterface> is not closed.
SIMPLE_ARM_XACRO = """<?xml version="1.0"?>
<robot name="two_link_arm" xmlns:xacro="http://ros.org/wiki/xacro">
 <ros2_control name="SimpleArmHardware" type="system">
  <hardware>
   <plugin>fake_components/GenericSystem</plugin>
  </hardware>
  <joint name="joint1">
   <command_interface name="position"/>
   <state_interface name="position"/>
   <state_interface name="velocity"/>
  </joint>
 </ros2_control>
 <xacro:property name="link_length" value="0.5"/>
 <xacro:property name="link_width" value="0.1"/>
 <xacro:property name="link_height" value="0.1"/>
 <link name="base_link"/>
 <joint name="joint1" type="revolute">
  <parent link="base_link"/>
  <child link="link1"/>
  <origin xyz="0 0 1" rpy="0 0 0"/>
  <axis xyz="0 0 1"/>
 </joint>
 <transmission name="joint1_trans">
  <type>transmission_interface/SimpleTransmission</type>
  <joint name="joint1">
   <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
  </joint>
  <actuator name="motor1">
   <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
   <mechanicalReduction>1</mechanicalReduction>
  </actuator>
 </transmission>
 <link name="link1">
  <visual>
   <geometry>
    <box size="${link_length} ${link_width} ${link_height}"/>
   </geometry>
   <material name="blue">
    <color rgba="0 0 1 1"/>
   </material>
  </visual>
 </link>
 <gazebo>
  <plugin name="gazebo_ros_control" filename="libgazebo_ros2_control.so"/>
 </gazebo>
 <gazebo reference="link1">
  <material>Gazebo/Blue</material>
 </gazebo>
</robot>
"""

# config/position_controllers.yaml. Typo fixed: the PDF lost the YAML's indentation (restored
# as ros2_control reads it: the controllers' types under controller_manager.ros__parameters).
POSITION_CONTROLLERS_YAML = """controller_manager:
  ros__parameters:
    update_rate: 50

    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster

    joint1_position_controller:
      type: position_controllers/JointGroupPositionController

joint1_position_controller:
  ros__parameters:
    joints:
      - joint1
"""

# launch/control.launch.py. Typos fixed: "launch ros.actions" and "generate launch description"
# (underscores), the list's closing "])" is cut off.
CONTROL_LAUNCH = """from launch import LaunchDescription
from launch_ros.actions import Node
import xacro
def generate_launch_description():
  urdf_file = "src/urdf_cpp_demo/urdf/simple_arm.xacro"
  robot_description = xacro.process_file(urdf_file).toxml()
  return LaunchDescription([
    Node(
       package='controller_manager',
       executable='ros2_control_node',
       parameters=[
         {'robot_description': robot_description},
         'src/urdf_cpp_demo/config/position_controllers.yaml'
       ],
       output='screen'
     ),
    Node(
       package='robot_state_publisher',
       executable='robot_state_publisher',
       parameters=[{'robot_description': robot_description}],
       output='screen'
     ),
    Node(
package='rviz2',
executable='rviz2',
output='screen'
)
  ])
"""

# launch/gazebo.launch.py. Fixed: the seed calls get_package_share_directory without importing
# it (a NameError in ROS too), and the "return" block lost its indentation.
GAZEBO_LAUNCH = """from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory
import os
import xacro
def generate_launch_description():
  urdf_file = 'src/urdf_cpp_demo/urdf/simple_arm.xacro'
  world_file = 'src/urdf_cpp_demo/worlds/empty.world'
  robot_description = xacro.process_file(urdf_file).toxml()
  gazebo_launch = IncludeLaunchDescription(
    PythonLaunchDescriptionSource([
       os.path.join(
         get_package_share_directory('gazebo_ros'),
         'launch',
         'gazebo.launch.py'
       )
    ]),
    launch_arguments={'world': world_file}.items()
  )
  return LaunchDescription([
    gazebo_launch,
    Node(
       package='controller_manager',
       executable='ros2_control_node',
       parameters=[
         {'robot_description': robot_description},
         'src/urdf_cpp_demo/config/position_controllers.yaml'
       ],
       output='screen'
    ),
    Node(
       package='robot_state_publisher',
       executable='robot_state_publisher',
       parameters=[{'robot_description': robot_description}],
       output='screen'
    ),
  ])
"""

# worlds/empty.world. Fixed: the PDF's last lines ("</include>", "</irchy") are the world's
# "</world>" and "</sdf>".
EMPTY_WORLD = """<?xml version="1.0" ?>
<sdf version="1.6">
<world name="default">
<include>
<uri>model://ground_plane</uri>
</include>
<include>
<uri>model://sun</uri>
</include>
</world>
</sdf>
"""


def urdf_cpp_demo(ws: Ros2Workspace, *, with_limits: bool) -> Path:
    """``ros2 pkg create --build-type ament_cmake urdf_cpp_demo --dependencies rclcpp`` as
    ``robomodel new`` writes it (the course's line, typed as written), the seed's files,
    ``colcon build``."""
    from robomodel.cli.main import main

    if not (ws.src / PKG).exists():
        argv = ["new", "--build-type", "ament_cmake", PKG, "--dependencies", "rclcpp"]
        assert main([*argv, "--dir", str(ws.src)]) == 0
    urdf, xacro_text = SIMPLE_ARM_URDF, SIMPLE_ARM_XACRO
    if with_limits:
        urdf = urdf.replace('<axis xyz="0 0 1"/>\n', '<axis xyz="0 0 1"/>\n' + LIMIT)
        xacro_text = xacro_text.replace(
            '  <axis xyz="0 0 1"/>\n </joint>', '  <axis xyz="0 0 1"/>\n  ' + LIMIT + " </joint>"
        )
    root = write_tree(
        ws.src / PKG,
        {
            "urdf/simple_arm.urdf": urdf,
            "urdf/simple_arm.xacro": xacro_text,
            "launch/visualize.launch.py": VISUALIZE_LAUNCH,
            "launch/control.launch.py": CONTROL_LAUNCH,
            "launch/gazebo.launch.py": GAZEBO_LAUNCH,
            "config/position_controllers.yaml": POSITION_CONTROLLERS_YAML,
            "worlds/empty.world": EMPTY_WORLD,
        },
    )
    ws.colcon_build(PKG, INSTALLED)
    return root


def _wait_for_the_manager(ws: Ros2Workspace) -> subprocess.CompletedProcess[str]:
    """``ros2 control list_controllers`` until the launch's manager answers."""

    def listed() -> subprocess.CompletedProcess[str] | None:
        run = ws.robomodel("control", "list-controllers")
        return run if run.returncode == 0 else None

    result: subprocess.CompletedProcess[str] = until(listed, "the controller manager answers")
    return result


def test_check_urdf_names_the_seed_s_missing_limit(ros2_ws: Ros2Workspace) -> None:
    """The seed's simple_arm.urdf has a revolute joint without <limit>: urdfdom refuses it (so
    does ROS 2's robot_state_publisher); ``robomodel check`` says the same, with the line."""
    root = urdf_cpp_demo(ros2_ws, with_limits=False)
    ours = ros2_ws.robomodel_plain("check", "src/urdf_cpp_demo/urdf/simple_arm.urdf")
    reference = subprocess.run(
        [debian_check_urdf(), str(root / "urdf/simple_arm.urdf")], capture_output=True, text=True
    )
    assert reference.returncode != 0 and "does not specify limits" in reference.stderr
    assert ours.returncode == 2
    assert "simple_arm.urdf:6:1: error: Joint [joint1] is of type REVOLUTE but it does not " in (
        ours.stderr
    )
    fixed = urdf_cpp_demo(ros2_ws, with_limits=True)
    run = ros2_ws.robomodel_plain("check", str(fixed / "urdf/simple_arm.urdf"))
    assert run.returncode == 0 and "root Link: base_link has 1 child(ren)" in run.stdout


def test_visualize_launch_publishes_tf(ros2_ws: Ros2Workspace, tmp_path: Path) -> None:
    """``ros2 launch urdf_cpp_demo visualize.launch.py``: robot_state_publisher named
    state_publisher, the GUI's joint states, the TF tree (link1 1 m above base_link)."""
    urdf_cpp_demo(ros2_ws, with_limits=True)
    log = tmp_path / "visualize.log"
    ros2_ws.launch(log, PKG, "visualize.launch.py", wait_for="nodes running")
    assert "started /state_publisher (robot_state_publisher/robot_state_publisher)" in (
        log.read_text()
    )
    assert ros2_ws.echo("/joint_states")["name"] == ["joint1"]
    tf = ros2_ws.robomodel("tf", "base_link", "link1", "--once", "--timeout", f"{scaled(60):.1f}")
    assert tf.returncode == 0 and "[0.000, 0.000, 1.000]" in tf.stdout, tf.stdout + tf.stderr


def test_control_launch_then_load_controllers_and_command(
    ros2_ws: Ros2Workspace, tmp_path: Path
) -> None:
    """``ros2 launch urdf_cpp_demo control.launch.py``; ``ros2 control list_controllers``
    (none loaded); ``ros2 control load_controller --set-state start`` twice; ``ros2 topic pub
    /joint1_position_controller/commands ... "data: [1.0]"``: joint1 goes to 1.0."""
    urdf_cpp_demo(ros2_ws, with_limits=True)
    ros2_ws.launch(tmp_path / "control.log", PKG, "control.launch.py", wait_for="nodes running")
    assert _wait_for_the_manager(ros2_ws).stdout.strip() == ""
    for name in ("joint_state_broadcaster", "joint1_position_controller"):
        run = ros2_ws.robomodel("control", "load", "--set-state", "start", name)
        assert run.returncode == 0, run.stderr
    listed = ros2_ws.robomodel("control", "list-controllers").stdout.split()
    assert listed.count("active") == 2
    # ros2 topic pub repeats at 1 Hz until Ctrl-C: started, then ended by the fixture
    ros2_ws.start(
        tmp_path / "pub.log", "topic", "pub", "/joint1_position_controller/commands",
        "std_msgs/msg/Float64MultiArray", "data: [1.0]",
    )  # fmt: skip
    until(
        lambda: abs(joint_position(ros2_ws.echo("/joint_states"), "joint1") - 1.0) < 1e-3,
        "joint1 at 1.0",
    )


def test_gazebo_launch_says_the_world_is_empty(ros2_ws: Ros2Workspace, tmp_path: Path) -> None:
    """``ros2 launch urdf_cpp_demo gazebo.launch.py``: Gazebo with ground and sun, but the
    seed's file never spawns the arm; robomodel says so in one line."""
    urdf_cpp_demo(ros2_ws, with_limits=True)
    log = tmp_path / "gazebo.log"
    ros2_ws.launch(log, PKG, "gazebo.launch.py", wait_for="nodes running")
    until(lambda: "no entity" in log.read_text(), "the hint", LINE_TIMEOUT_S, log=log)
    assert "gazebo.launch.py" in log.read_text()


def test_gazebo_launch_controllers_and_command(ros2_ws: Ros2Workspace, tmp_path: Path) -> None:
    """ "6. Control the Robot in Gazebo": load_controller --set-state start twice, then a
    command to 1.5 moves joint1 (in the launch's ros2_control_node, the only manager the seed's
    file starts)."""
    urdf_cpp_demo(ros2_ws, with_limits=True)
    ros2_ws.launch(tmp_path / "gazebo.log", PKG, "gazebo.launch.py", wait_for="nodes running")
    _wait_for_the_manager(ros2_ws)
    for name in ("joint_state_broadcaster", "joint1_position_controller"):
        run = ros2_ws.robomodel("control", "load", "--set-state", "start", name)
        assert run.returncode == 0, run.stderr
    ros2_ws.start(
        tmp_path / "pub.log", "topic", "pub", "/joint1_position_controller/commands",
        "std_msgs/msg/Float64MultiArray", "data: [1.5]",
    )  # fmt: skip
    until(
        lambda: abs(joint_position(ros2_ws.echo("/joint_states"), "joint1") - 1.5) < 1e-3,
        "joint1 at 1.5",
    )


URDF_LOADER_CMAKE = """
add_executable(urdf_loader src/urdf_loader.cpp)
ament_target_dependencies(urdf_loader rclcpp)
install(TARGETS urdf_loader DESTINATION lib/${PROJECT_NAME})
"""


def test_ros2_run_of_the_seed_s_cpp_node_names_the_cause_in_one_line(
    ros2_ws: Ros2Workspace,
) -> None:
    """The seed's first part, ``ros2 run urdf_cpp_demo urdf_loader`` after ``colcon build``:
    a C++ node. robomodel says why it cannot run it and what would (the docs' tutorial shows
    the Python node that does the same)."""
    root = urdf_cpp_demo(ros2_ws, with_limits=True)
    (root / "src").mkdir(exist_ok=True)
    (root / "src" / "urdf_loader.cpp").write_text("int main() { return 0; }\n")
    with (root / "CMakeLists.txt").open("a") as cmake:
        cmake.write(URDF_LOADER_CMAKE)
    run = ros2_ws.robomodel_plain("run", PKG, "urdf_loader")
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1, run.stderr
    assert "urdf_cpp_demo/urdf_loader is a C++ node" in lines[0]
    assert "add_executable from src/urdf_loader.cpp" in lines[0]
    assert "robomodel runs Python nodes" in lines[0] and "ROS 2 and colcon" in lines[0]
