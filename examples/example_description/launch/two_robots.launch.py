"""Seed 004's two identical robots: the namespaced launch twice, and one tree.

ros2 launch example_description two_robots.launch.py

Each robot's frames carry its namespace (robot1/..., robot2/...); two static transforms from
`world` connect the two trees ("Concern 2: Connecting tree"), robot2 one metre to the left, and
one RViz shows both with the fixed frame `world`.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node


def generate_launch_description():
    one = os.path.join(
        get_package_share_directory("example_description"), "launch", "namespaced.launch.py"
    )
    actions = []
    for index, name in enumerate(("robot1", "robot2")):
        actions.append(
            IncludeLaunchDescription(
                PythonLaunchDescriptionSource(one), launch_arguments={"namespace": name}.items()
            )
        )
        actions.append(
            Node(
                package="tf2_ros",
                executable="static_transform_publisher",
                name=f"world_to_{name}",
                arguments=["0", str(index), "0", "0", "0", "0", "world", f"{name}/base_footprint"],
            )
        )
    actions.append(Node(package="rviz2", executable="rviz2", arguments=["-f", "world"]))
    return LaunchDescription(actions)
