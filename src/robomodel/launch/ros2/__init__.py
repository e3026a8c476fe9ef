"""ROS 2 launch files (Python, XML, YAML) with Humble/Jazzy ``launch`` / ``launch_ros``
semantics, turned into plain data: the declared arguments and the steps ``ros2 launch`` would
start (nodes with names, namespaces, remaps and parameters; processes; delays; event chains).
"""

from robomodel.launch.ros2.loader import load_launch
from robomodel.launch.ros2.model import DeclaredArgument, LaunchStep, Ros2Launch
from robomodel.launch.ros2.printing import format_print, format_show_args

__all__ = [
    "DeclaredArgument",
    "LaunchStep",
    "Ros2Launch",
    "format_print",
    "format_show_args",
    "load_launch",
]
