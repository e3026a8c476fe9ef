"""gazebo_ros (ROS 2) gzserver.launch.py as robomodel provides it: gazebo_ros's arguments; the
node is robomodel's simulator (MuJoCo) on the world file."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    world = LaunchConfiguration("world")
    pause = LaunchConfiguration("pause")
    arguments = [
        ("world", "", "Specify world file name"),
        ("version", "false", "Set 'true' to output version information."),
        ("verbose", "false", "Set 'true' to increase messages written to terminal."),
        ("lockstep", "false", "Set 'true' to respect update rates."),
        ("help", "false", "Set 'true' to produce gzserver help message."),
        ("pause", "false", "Set 'true' to start the server in a paused state."),
        ("physics", "", "Specify a physics engine (ode|bullet|dart|simbody)."),
        ("init", "true", "Set 'false' not to load 'libgazebo_ros_init.so'"),
        ("factory", "true", "Set 'false' not to load 'libgazebo_ros_factory.so'"),
        ("force_system", "true", "Set 'false' not to load 'libgazebo_ros_force_system.so'"),
        (
            "server_required",
            "false",
            "Set 'true' to shut down launch script when server is terminated",
        ),
        ("extra_gazebo_args", "", "Extra arguments to be passed to Gazebo"),
        ("params_file", "", "Path to ROS 2 yaml parameter file"),
    ]
    return LaunchDescription(
        [DeclareLaunchArgument(n, default_value=d, description=t) for n, d, t in arguments]
        + [
            Node(
                package="gazebo_ros",
                executable="gzserver",
                name="gazebo",
                output="screen",
                arguments=["-u", world],
                condition=IfCondition(pause),
            ),
            Node(
                package="gazebo_ros",
                executable="gzserver",
                name="gazebo",
                output="screen",
                arguments=[world],
                condition=UnlessCondition(pause),
            ),
        ]
    )
