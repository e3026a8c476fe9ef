# urdf_tutorial's display.launch.py style (Humble): gui argument, jsp / jsp_gui by condition,
# robot_description as ParameterValue(Command(['xacro ', path]), value_type=str).
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import Command, LaunchConfiguration, PythonExpression
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    pkg_share = FindPackageShare('rrbot_demo')
    default_model_path = pkg_share / 'urdf' / 'rrbot.urdf.xacro'
    gui_arg = DeclareLaunchArgument(name='gui', default_value='true', choices=['true', 'false'],
                                    description='Flag to enable joint_state_publisher_gui')
    model_arg = DeclareLaunchArgument(name='model', default_value=default_model_path,
                                      description='Absolute path to robot urdf file')
    robot_description = ParameterValue(
        Command(['xacro ', LaunchConfiguration('model'), ' prefix:=', LaunchConfiguration('prefix', default='arm_')]),
        value_type=str)
    return LaunchDescription([
        gui_arg,
        model_arg,
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': robot_description}]),
        Node(package='joint_state_publisher', executable='joint_state_publisher',
             condition=UnlessCondition(LaunchConfiguration('gui'))),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui',
             condition=IfCondition(LaunchConfiguration('gui'))),
        Node(package='rviz2', executable='rviz2', name='rviz2', output='screen',
             condition=IfCondition(PythonExpression(["'", LaunchConfiguration('gui'), "' == 'true' and ", str(2 * 1), " > 1"]))),
    ])
