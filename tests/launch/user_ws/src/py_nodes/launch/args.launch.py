from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            Node(
                package="py_nodes",
                executable="echo_args",
                name="echo",
                namespace="robot1",
                remappings=[("chatter", "talk")],
                parameters=[{"rate_hz": 5.0, "frame": "base"}],
                arguments=["--loud"],
                output="screen",
            ),
            Node(package="py_nodes", executable="crasher", output="screen"),
        ]
    )
