# Seed 003, first version: the URDF read with open() (paths relative to the workspace).
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    urdf_path = 'src/urdf_cpp_demo/urdf/simple_arm.urdf'

    return LaunchDescription([
        Node(
            package='robot_state_publisher',
            executable='robot_state_publisher',
            name='state_publisher',
            output='screen',
            parameters=[{'robot_description': open(urdf_path).read()}],
        ),
        Node(
            package='joint_state_publisher_gui',
            executable='joint_state_publisher_gui',
            name='joint_state_publisher',
            output='screen',
        ),
        Node(
            package='rviz2',
            executable='rviz2',
            name='rviz2',
            output='screen',
        )
    ])
