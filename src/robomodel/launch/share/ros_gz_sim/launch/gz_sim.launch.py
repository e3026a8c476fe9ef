"""ros_gz_sim gz_sim.launch.py as robomodel provides it: gz_args as Gazebo Sim takes them
(-r to run, -s server only, -v N, the world file); with robomodel the simulator is MuJoCo and
the GUI the browser viewer."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                "gz_args", default_value="", description="Arguments to be passed to Gazebo Sim"
            ),
            DeclareLaunchArgument(
                "gz_version", default_value="8", description="Gazebo Sim's major version"
            ),
            DeclareLaunchArgument(
                "on_exit_shutdown",
                default_value="false",
                description="If ignition should close when ros2 launch does",
            ),
            Node(
                package="ros_gz_sim",
                executable="gz_sim",
                name="gz_sim",
                output="screen",
                arguments=[LaunchConfiguration("gz_args")],
            ),
        ]
    )
