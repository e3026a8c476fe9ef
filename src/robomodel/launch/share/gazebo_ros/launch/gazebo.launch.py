"""gazebo_ros (ROS 2) gazebo.launch.py as robomodel provides it: the server and the client,
each with gazebo_ros's arguments (gzserver.launch.py, gzclient.launch.py); with robomodel the
server is its simulator and the client its browser viewer."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, ThisLaunchFileDir


def generate_launch_description():
    gzserver = IncludeLaunchDescription(
        PythonLaunchDescriptionSource([ThisLaunchFileDir(), "/gzserver.launch.py"]),
        condition=IfCondition(LaunchConfiguration("server")),
    )
    gzclient = IncludeLaunchDescription(
        PythonLaunchDescriptionSource([ThisLaunchFileDir(), "/gzclient.launch.py"]),
        condition=IfCondition(LaunchConfiguration("gui")),
    )
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                "gui", default_value="true", description="Set to 'false' to run headless."
            ),
            DeclareLaunchArgument(
                "server", default_value="true", description="Set to 'false' not to run gzserver."
            ),
            gzserver,
            gzclient,
        ]
    )
