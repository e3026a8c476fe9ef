"""Seed 004's display launch: robot_state_publisher + joint_state_publisher_gui + RViz, with a
robot_name argument that the xacro turns into the frame prefix of every link.

ros2 launch example_description display.launch.py robot_name:=robot1_
"""

import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def robot_nodes(context):
    robot_name = LaunchConfiguration("robot_name").perform(context)
    pkg = get_package_share_directory("example_description")
    path = os.path.join(pkg, "urdf", "example.urdf.xacro")
    robot_desc = xacro.process_file(path, mappings={"robot_name": robot_name}).toxml()
    robot_state_publisher = Node(
        package="robot_state_publisher",
        executable="robot_state_publisher",
        parameters=[{"robot_description": robot_desc}],
    )
    joint_state_publisher_gui = Node(
        package="joint_state_publisher_gui",
        executable="joint_state_publisher_gui",
    )
    rviz = Node(package="rviz2", executable="rviz2")
    return [robot_state_publisher, rviz, joint_state_publisher_gui]


def generate_launch_description():
    launch_description = LaunchDescription()
    launch_description.add_action(
        DeclareLaunchArgument(
            "robot_name", default_value="", description="frame prefix of every link (e.g. robot1_)"
        )
    )
    launch_description.add_action(OpaqueFunction(function=robot_nodes))
    return launch_description
