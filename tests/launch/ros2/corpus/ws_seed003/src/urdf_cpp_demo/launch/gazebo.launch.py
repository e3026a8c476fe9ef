# Seed 003's gazebo.launch.py (the seed omits the get_package_share_directory import, which
# ros2 launch would also reject with a NameError; it is added here).
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory
import os
import xacro


def generate_launch_description():
    urdf_file = 'src/urdf_cpp_demo/urdf/simple_arm.xacro'
    world_file = 'src/urdf_cpp_demo/worlds/empty.world'
    robot_description = xacro.process_file(urdf_file).toxml()
    gazebo_launch = IncludeLaunchDescription(
        PythonLaunchDescriptionSource([
            os.path.join(
                get_package_share_directory('gazebo_ros'),
                'launch',
                'gazebo.launch.py'
            )
        ]),
        launch_arguments={'world': world_file}.items()
    )

    return LaunchDescription([
        gazebo_launch,
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
    ])
