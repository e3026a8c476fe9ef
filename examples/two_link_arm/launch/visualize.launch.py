"""Seed 003's visualize.launch.py: robot_state_publisher + joint_state_publisher_gui + RViz.

ros2 launch two_link_arm visualize.launch.py     (robomodel launch two_link_arm visualize.launch.py)

The seed reads 'src/urdf_cpp_demo/urdf/simple_arm.xacro' relative to the workspace; here the
path comes from the package's share directory, so it runs from any directory.
"""

import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    urdf_path = os.path.join(
        get_package_share_directory("two_link_arm"), "urdf", "two_link_arm.urdf.xacro"
    )
    robot_description = xacro.process_file(urdf_path).toxml()

    return LaunchDescription(
        [
            Node(
                package="robot_state_publisher",
                executable="robot_state_publisher",
                name="state_publisher",
                output="screen",
                parameters=[{"robot_description": robot_description}],
            ),
            Node(
                package="joint_state_publisher_gui",
                executable="joint_state_publisher_gui",
                name="joint_state_publisher",
                output="screen",
            ),
            Node(
                package="rviz2",
                executable="rviz2",
                name="rviz2",
                output="screen",
            ),
        ]
    )
