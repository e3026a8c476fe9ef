"""Run ROS 1 and ROS 2 launch files by mapping their nodes onto robomodel's layers.

``robomodel launch PKG FILE`` / ``robomodel launch PATH`` reads a launch file (ROS 1 XML,
ROS 2 Python/XML/YAML), builds what it describes (parameters, nodes with their names,
namespaces, remaps and arguments) as :mod:`robomodel.launch.model` data, and runs each node
that robomodel provides (robot_state_publisher, joint_state_publisher, rviz, gazebo, the
controller manager, ...) in this process.
"""

from robomodel.launch.model import LaunchError, NodeSpec, ParamSource

__all__ = ["LaunchError", "NodeSpec", "ParamSource"]
