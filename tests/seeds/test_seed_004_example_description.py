"""Seed 004, "RBE502: Robot Modelling": example_description with the seed's xacro file
management (properties.xacro loading a YAML dictionary, part_1.xacro's macro, the assembly),
``xacro FILE ARGS > FILE.urdf``, ``xacro.process_file(...).toxml()`` in a launch file that finds
its package with ``get_package_share_directory``, and robot_state_publisher with a namespace and
``frame_prefix`` (one robot, then two), as the student types them, with robomodel's CLI.

The seed is slides: its xacro listings are fragments with underscores read as spaces; the
course's repository (kittinook/FRA501, branch robot-modelling-exercise) is not part of the seed.
The files below are the slides' text with the typos fixed (each named), completed where the
slides elide ("<joint name="joint 1"> </joint>").
"""

from __future__ import annotations

from pathlib import Path

from tests.seeds.conftest import (
    LINE_TIMEOUT_S,
    Ros2Workspace,
    box_stl,
    joint_position,
    package_xml,
    write_tree,
)
from tests.timing import scaled

PKG = "example_description"

# properties.xacro (the slide's "property.xacro", included as properties.xacro). Typos fixed:
# "description package", "param dict", "xacro.load yaml" (underscores). Added: COLOR, which the
# slide's part_1.xacro uses and its property file does not define.
PROPERTIES_XACRO = """<?xml version='1.0'?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="description_package" value="example_description"/>
  <!-- File paths-->
 <xacro:property name="params_path" value="$(find ${description_package})/config/parameters.yaml"/>
  <xacro:property name="param_dict" value="${xacro.load_yaml(params_path)}"/>
  <!-- Mathematics Constants -->
 <xacro:property name="PI" value="3.1415926535897931"/>
  <!-- Robot Properties -->
  <xacro:property name="LENGTH" value="${param_dict['length']}"/>
  <xacro:property name="WIDTH" value="${param_dict['width']}"/>
  <xacro:property name="OFFSET" value="${param_dict['offset']}"/>
  <xacro:property name="COLOR" value="${param_dict['color']}"/>
</robot>
"""

# part_1.xacro. Typos fixed: "my macro", "example description", "link ${id-1}.stl".
PART_1_XACRO = """<?xml version='1.0'?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name= "my_macro" params="id">
        <visual>
            <origin xyz="${OFFSET[id-1]}"/>
            <geometry>
                <mesh filename="file://$(find example_description)/meshes/link_${id-1}.stl"/>
            </geometry>
            <material name="link_color">
                <color rgba="${COLOR[id-1]}"/>
            </material>
        </visual>
  </xacro:macro>
</robot>
"""

# assembly.xacro. Typos fixed: "robot name" (the arg), "part 1.xacro", "example description",
# "my macro", "link 1", "joint 1"; the unquoted name=base / name=link 1. Completed: the slide's
# empty <joint name="joint 1"> (a revolute joint from base to link_1 about z).
ASSEMBLY_XACRO = """<?xml version='1.0'?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="example" >
  <xacro:arg name="robot_name" default=""/>
  <xacro:property name="namespace" value="$(arg robot_name)"/>
  <xacro:include filename="$(find example_description)/robot/visual/properties.xacro"/>
  <xacro:include filename="$(find example_description)/robot/visual/part_1.xacro"/>
  <link name="base">
     <xacro:my_macro id="0"/>
  </link>
  <link name="link_1">
     <xacro:my_macro id="1"/>
  </link>
  <joint name="joint_1" type="revolute">
    <parent link="base"/>
    <child link="link_1"/>
    <origin xyz="0 0 ${LENGTH}" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="${-PI}" upper="${PI}" velocity="1000.0" effort="1000.0"/>
  </joint>
</robot>
"""

# config/parameters.yaml: the keys properties.xacro reads, strings as the slide's YAML has them
PARAMETERS_YAML = """length: "0.2"
width: "0.05"
offset: ["0 0 0.05", "0 0 0.1"]
color: ["0 1.0 1.0 1.0", "1 1 1 1"]
"""

# launch/display.launch.py: the slides' "Example: Package my_robot_description" launch
# (get_package_share_directory, os.path.join, xacro.process_file(...).toxml()) with the
# "Passing namespace as a Launch Argument" robot_state_publisher. Typos fixed: "launch ros",
# "generate launch description", "robot state publisher", "get package share directory"
# (underscores), the missing ":" after the def; the slide's 'robot_description': namespace is
# its shorthand for the description itself.
DISPLAY_LAUNCH = """import os
import xacro
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory

def generate_launch_description():
    pkg = get_package_share_directory('example_description')
    path = os.path.join(pkg,'robot','visual','assembly.xacro')
    robot_desc = xacro.process_file(path).toxml()
    namespace = LaunchConfiguration('namespace')
    frame_prefix = LaunchConfiguration('frame_prefix',default= [namespace, '/'])
    robot_state_publisher = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        output='screen',
        namespace=namespace,
        parameters=[{
            'robot_description':robot_desc,
            'frame_prefix': frame_prefix
        }]
        )
    joint_state_publisher_gui = Node(
        package = 'joint_state_publisher_gui',
        executable = 'joint_state_publisher_gui',
        namespace=namespace,
    )
    rviz = Node(package = 'rviz2', executable = 'rviz2')
    launch_description = LaunchDescription()
    launch_description.add_action(DeclareLaunchArgument('namespace', default_value='r1'))
    launch_description.add_action(robot_state_publisher)
    launch_description.add_action(rviz)
    launch_description.add_action(joint_state_publisher_gui)
    return launch_description
"""

# "What if we want to display 2 identical robots simultaneously?": the display twice
TWO_ROBOTS_LAUNCH = """import os
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from ament_index_python.packages import get_package_share_directory

def generate_launch_description():
    display = os.path.join(
        get_package_share_directory('example_description'), 'launch', 'display.launch.py')
    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(display),
            launch_arguments={'namespace': name}.items())
        for name in ('r1', 'r2')
    ])
"""


def example_description(ws: Ros2Workspace) -> Path:
    """The package (robot/visual for the xacro files, as the slides' include paths say),
    ``colcon build``."""
    root = write_tree(
        ws.src / PKG,
        {
            "package.xml": package_xml(PKG),
            "robot/visual/properties.xacro": PROPERTIES_XACRO,
            "robot/visual/part_1.xacro": PART_1_XACRO,
            "robot/visual/assembly.xacro": ASSEMBLY_XACRO,
            "config/parameters.yaml": PARAMETERS_YAML,
            "launch/display.launch.py": DISPLAY_LAUNCH,
            "launch/two_robots.launch.py": TWO_ROBOTS_LAUNCH,
            # the meshes the macro's "link_${id-1}.stl" names for ids 0 and 1
            "meshes/link_-1.stl": box_stl((0.1, 0.1, 0.1)),
            "meshes/link_0.stl": box_stl((0.05, 0.05, 0.2)),
        },
    )
    ws.colcon_build(PKG, ("robot", "config", "launch", "meshes"))
    return root


def test_xacro_on_the_command_line(ros2_ws: Ros2Workspace) -> None:
    """``xacro [xacro_file.xacro] [optional arguments] > [urdf_file.urdf]``: the YAML's values
    in the URDF, and it checks."""
    root = example_description(ros2_ws)
    run = ros2_ws.robomodel_plain(
        "xacro", str(root / "robot/visual/assembly.xacro"), "robot_name:=robot1"
    )
    assert run.returncode == 0, run.stderr
    assert '<origin rpy="0 0 0" xyz="0 0 0.2"/>' in run.stdout  # LENGTH from the YAML
    assert '<color rgba="1 1 1 1"/>' in run.stdout  # COLOR[-1] for id 0
    (ros2_ws.root / "example.urdf").write_text(run.stdout)
    check = ros2_ws.robomodel_plain("check", "example.urdf")
    assert check.returncode == 0, check.stderr
    assert "root Link: base has 1 child(ren)" in check.stdout


def test_frame_prefix_puts_the_namespace_on_the_static_description(
    ros2_ws: Ros2Workspace, tmp_path: Path
) -> None:
    """robot_state_publisher in namespace r1 with frame_prefix "r1/": its robot_description
    is /r1/robot_description."""
    example_description(ros2_ws)
    ros2_ws.launch(tmp_path / "display.log", PKG, "display.launch.py", wait_for="nodes running")
    topics = ros2_ws.wait_for_topics("/r1/robot_description")
    assert "/robot_description" not in topics


def test_one_robot_in_a_namespace(ros2_ws: Ros2Workspace, tmp_path: Path) -> None:
    """``ros2 launch example_description display.launch.py``: /r1/joint_states, and /tf with
    r1/ frames (link_1 0.2 m above base)."""
    example_description(ros2_ws)
    ros2_ws.launch(tmp_path / "display.log", PKG, "display.launch.py", wait_for="nodes running")
    ros2_ws.wait_for_topics("/r1/robot_description")  # the launch's nodes are on the graph
    states = ros2_ws.echo("/r1/joint_states", timeout_s=LINE_TIMEOUT_S)
    assert joint_position(states, "joint_1") == 0.0
    tf = ros2_ws.robomodel("tf", "r1/base", "r1/link_1", "--once", "--timeout", f"{scaled(30):.1f}")
    assert tf.returncode == 0 and "[0.000, 0.000, 0.200]" in tf.stdout, tf.stdout + tf.stderr


def test_two_robots_with_frame_prefixes(ros2_ws: Ros2Workspace, tmp_path: Path) -> None:
    """The display twice, namespaces r1 and r2: two trees in one /tf, r1/ and r2/ frames."""
    example_description(ros2_ws)
    ros2_ws.launch(tmp_path / "two.log", PKG, "two_robots.launch.py", wait_for="nodes running")
    ros2_ws.wait_for_topics("/r1/robot_description", "/r2/robot_description")
    for name in ("r1", "r2"):
        states = ros2_ws.echo(f"/{name}/joint_states", timeout_s=LINE_TIMEOUT_S)
        assert joint_position(states, "joint_1") == 0.0
        tf = ros2_ws.robomodel(
            "tf", f"{name}/base", f"{name}/link_1", "--once", "--timeout", f"{scaled(30):.1f}"
        )
        assert tf.returncode == 0 and "[0.000, 0.000, 0.200]" in tf.stdout, tf.stderr
