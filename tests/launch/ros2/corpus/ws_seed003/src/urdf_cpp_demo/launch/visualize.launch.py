# Seed 003, "Update Launch File to Use .xacro" (paths relative to the workspace, as written).
from launch import LaunchDescription
from launch_ros.actions import Node
import xacro


def generate_launch_description():
    urdf_path = 'src/urdf_cpp_demo/urdf/simple_arm.xacro'
    robot_description = xacro.process_file(urdf_path).toxml()

    return LaunchDescription([
        Node(
            package='robot_state_publisher',
            executable='robot_state_publisher',
            name='state_publisher',
            output='screen',
            parameters=[{'robot_description': robot_description}],
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
