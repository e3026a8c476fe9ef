"""ROS 1 launch files (roslaunch XML) with roslaunch 1.16's semantics.

The names are re-exported lazily (PEP 562), so that a process that takes one module of this
package (the parameter server's ``params``: ``robomodel run``, ``service``, ``param``) does not
load the launch-file loader and its tags.
"""

from __future__ import annotations

from robomodel._lazy import lazy_exports

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (mypy knows the name)
if TYPE_CHECKING:
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

_MODULE_OF: dict[str, str] = {
    "MachineSpec": "robomodel.launch.ros1.config",
    "ParamDump": "robomodel.launch.ros1.config",
    "Ros1Launch": "robomodel.launch.ros1.config",
    "load_launch": "robomodel.launch.ros1.loader",
    "find_node_executable": "robomodel.launch.ros1.printing",
    "format_dump_params": "robomodel.launch.ros1.printing",
    "format_files": "robomodel.launch.ros1.printing",
    "format_node_args": "robomodel.launch.ros1.printing",
    "format_nodes": "robomodel.launch.ros1.printing",
    "format_ros_args": "robomodel.launch.ros1.printing",
}

__getattr__, __dir__ = lazy_exports(__name__, _MODULE_OF, globals(), __all__)
