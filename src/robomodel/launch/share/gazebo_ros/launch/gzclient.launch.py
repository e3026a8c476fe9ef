"""gazebo_ros (ROS 2) gzclient.launch.py as robomodel provides it: the browser viewer."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                "version", default_value="false", description="Set 'true' to output version."
            ),
            DeclareLaunchArgument(
                "verbose", default_value="false", description="Set 'true' for more messages."
            ),
            DeclareLaunchArgument(
                "gui_required",
                default_value="false",
                description="Set 'true' to shut down launch script when GUI is terminated",
            ),
            Node(package="gazebo_ros", executable="gzclient", name="gzclient", output="screen"),
        ]
    )
