"""Seed 003's gazebo.launch.py: Gazebo (gazebo_ros's gazebo.launch.py with a world) and the
arm with gazebo_ros2_control.

ros2 launch two_link_arm gazebo.launch.py

Two corrections to the seed, which would not run as written: the robot is spawned
(spawn_entity.py -topic robot_description; the seed never spawns it, so Gazebo stays empty), and
the controllers run in the controller manager of the gazebo_ros2_control plugin, loaded by
spawners (the seed also starts a ros2_control_node, a second manager on the same services).
"""

import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription, RegisterEventHandler
from launch.event_handlers import OnProcessExit
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory("two_link_arm")
    urdf_file = os.path.join(share, "urdf", "two_link_arm.urdf.xacro")
    world_file = os.path.join(share, "worlds", "empty.world")
    robot_description = xacro.process_file(urdf_file, mappings={"use_gazebo": "true"}).toxml()
    gazebo_launch = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(
            [os.path.join(get_package_share_directory("gazebo_ros"), "launch", "gazebo.launch.py")]
        ),
        launch_arguments={"world": world_file}.items(),
    )
    spawn = Node(
        package="gazebo_ros",
        executable="spawn_entity.py",
        arguments=["-topic", "robot_description", "-entity", "two_link_arm"],
        output="screen",
    )
    joint_state_broadcaster = Node(
        package="controller_manager",
        executable="spawner",
        arguments=["joint_state_broadcaster"],
    )
    arm_controller = Node(
        package="controller_manager",
        executable="spawner",
        arguments=["joint1_position_controller"],
    )
    return LaunchDescription(
        [
            gazebo_launch,
            Node(
                package="robot_state_publisher",
                executable="robot_state_publisher",
                parameters=[{"robot_description": robot_description, "use_sim_time": True}],
                output="screen",
            ),
            spawn,
            RegisterEventHandler(
                OnProcessExit(target_action=spawn, on_exit=[joint_state_broadcaster])
            ),
            RegisterEventHandler(
                OnProcessExit(target_action=joint_state_broadcaster, on_exit=[arm_controller])
            ),
        ]
    )
