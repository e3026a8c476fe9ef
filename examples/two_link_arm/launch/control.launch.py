"""Seed 003's control.launch.py: ros2_control_node (mock hardware) + robot_state_publisher + RViz.

ros2 launch two_link_arm control.launch.py
then, in another terminal (seed 003 step 6):
    ros2 control load_controller --set-state active joint_state_broadcaster
    ros2 control load_controller --set-state active joint1_position_controller
    ros2 topic pub /joint1_position_controller/commands std_msgs/msg/Float64MultiArray "data: [1.0]"
(with robomodel: robomodel control load ... --set-state active, robomodel topic pub ...)
"""

import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory("two_link_arm")
    urdf_file = os.path.join(share, "urdf", "two_link_arm.urdf.xacro")
    controllers = os.path.join(share, "config", "position_controllers.yaml")
    robot_description = xacro.process_file(urdf_file).toxml()
    return LaunchDescription(
        [
            Node(
                package="controller_manager",
                executable="ros2_control_node",
                parameters=[{"robot_description": robot_description}, controllers],
                output="screen",
            ),
            Node(
                package="robot_state_publisher",
                executable="robot_state_publisher",
                parameters=[{"robot_description": robot_description}],
                output="screen",
            ),
            Node(package="rviz2", executable="rviz2", output="screen"),
        ]
    )
