"""Seed 004's "Frame Prefix": one robot in a namespace, its frames prefixed with it.

ros2 launch example_description namespaced.launch.py namespace:=robot1

robot_state_publisher and joint_state_publisher_gui run in the namespace (so the robot's topics
are /robot1/robot_description and /robot1/joint_states), and frame_prefix is built from it as the
seed does: LaunchConfiguration('frame_prefix', default=[namespace, '/']).
"""

import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    pkg = get_package_share_directory("example_description")
    robot_desc = xacro.process_file(os.path.join(pkg, "urdf", "example.urdf.xacro")).toxml()
    namespace = LaunchConfiguration("namespace")
    frame_prefix = LaunchConfiguration("frame_prefix", default=[namespace, "/"])
    robot_state_publisher = Node(
        package="robot_state_publisher",
        executable="robot_state_publisher",
        output="screen",
        namespace=namespace,
        parameters=[{"robot_description": robot_desc, "frame_prefix": frame_prefix}],
    )
    joint_state_publisher_gui = Node(
        package="joint_state_publisher_gui",
        executable="joint_state_publisher_gui",
        namespace=namespace,
    )
    launch_description = LaunchDescription()
    launch_description.add_action(DeclareLaunchArgument("namespace", default_value="robot1"))
    launch_description.add_action(robot_state_publisher)
    launch_description.add_action(joint_state_publisher_gui)
    return launch_description
