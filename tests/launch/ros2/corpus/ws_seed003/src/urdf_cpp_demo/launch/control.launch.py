# Seed 003's control.launch.py.
from launch import LaunchDescription
from launch_ros.actions import Node
import xacro


def generate_launch_description():
    urdf_file = "src/urdf_cpp_demo/urdf/simple_arm.xacro"
    robot_description = xacro.process_file(urdf_file).toxml()
    return LaunchDescription([
        Node(
            package='controller_manager',
            executable='ros2_control_node',
            parameters=[
                {'robot_description': robot_description},
                'src/urdf_cpp_demo/config/position_controllers.yaml'
            ],
            output='screen'
        ),
        Node(
            package='robot_state_publisher',
            executable='robot_state_publisher',
            parameters=[{'robot_description': robot_description}],
            output='screen'
        ),
        Node(
            package='rviz2',
            executable='rviz2',
            output='screen'
        )
    ])
