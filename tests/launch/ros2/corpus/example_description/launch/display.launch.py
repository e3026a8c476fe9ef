# Seed 004's display launch: robot_name as namespace and frame prefix, an OpaqueFunction that
# writes a per-robot rviz config and adds rviz.
import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchContext, LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def render_namespace(context: LaunchContext, namespace: LaunchConfiguration):
    namespace_str = context.perform_substitution(namespace)
    my_pkg = get_package_share_directory('example_description')
    config_path = os.path.join(my_pkg, 'config', 'config.rviz')
    rviz = Node(
        package='rviz2',
        executable='rviz2',
        arguments=['-d', config_path],
        namespace=namespace_str,
    )
    return [rviz]


def generate_launch_description():
    pkg = get_package_share_directory('example_description')
    path = os.path.join(pkg, 'robot', 'visual', 'my_robot.xacro')
    namespace = LaunchConfiguration('robot_name')
    frame_prefix = LaunchConfiguration('frame_prefix', default=[namespace, '/'])
    robot_desc = xacro.process_file(path, mappings={'robot_name': 'example'}).toxml()
    robot_state_publisher = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        output='screen',
        namespace=namespace,
        parameters=[{
            'robot_description': robot_desc,
            'frame_prefix': frame_prefix,
        }],
    )
    launch_description = LaunchDescription()
    launch_description.add_action(
        DeclareLaunchArgument('robot_name', default_value='robot1', description='Robot name'))
    launch_description.add_action(robot_state_publisher)
    launch_description.add_action(
        OpaqueFunction(function=render_namespace, args=[namespace]))
    return launch_description
