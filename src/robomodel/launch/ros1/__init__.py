"""ROS 1 launch files (roslaunch XML) with roslaunch 1.16's semantics."""

from robomodel.launch.ros1.config import MachineSpec, ParamDump, Ros1Launch
from robomodel.launch.ros1.loader import load_launch
from robomodel.launch.ros1.printing import (
    find_node_executable,
    format_dump_params,
    format_files,
    format_node_args,
    format_nodes,
    format_ros_args,
)

__all__ = [
    "MachineSpec",
    "ParamDump",
    "Ros1Launch",
    "find_node_executable",
    "format_dump_params",
    "format_files",
    "format_node_args",
    "format_nodes",
    "format_ros_args",
    "load_launch",
]
