"""Node mappings: which robomodel component runs for each ROS node of a launch file."""

from robomodel.launch.nodes import (
    bridges,
    cm_script,
    controllers,
    gazebo,
    ros2_control,
    ros2_gazebo,
    ros2_nodes,
    state,
    tf_static,
    tools,
    view_frames,
    viewer,
)
from robomodel.launch.nodes.base import (
    NodeContext,
    RunningNode,
    ViewerRequest,
    factory_for,
    register,
    supported,
)

__all__ = [
    "NodeContext",
    "RunningNode",
    "ViewerRequest",
    "bridges",
    "cm_script",
    "controllers",
    "factory_for",
    "gazebo",
    "register",
    "ros2_control",
    "ros2_gazebo",
    "ros2_nodes",
    "state",
    "supported",
    "tf_static",
    "tools",
    "view_frames",
    "viewer",
]
