# Shape of gazebo_ros's gazebo.launch.py: arguments, then gzserver and gzclient includes,
# modelled here as two processes.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('world', default_value='', description='Specify world file name'),
        DeclareLaunchArgument('gui', default_value='true', description='Set to "false" to run headless.'),
        DeclareLaunchArgument('verbose', default_value='false', description='Set "true" to increase messages written to terminal.'),
        ExecuteProcess(cmd=['gzserver', LaunchConfiguration('world')], output='screen'),
        ExecuteProcess(cmd=['gzclient'], output='screen', condition=IfCondition(LaunchConfiguration('gui'))),
    ])
